/* fuzzygait from C: controller sets, grounds, walkers and crowds behind opaque handles; the whole
 * body on a path and a game's skeleton posed from it (below).
 *
 * Every call that can fail takes an `fg_error*` (may be NULL) and returns NULL or 0 on failure,
 * with the reason in error->message (the same text the C++ exception carries: file, line and field
 * where there are some). No exception crosses this boundary. A walker or crowd keeps pointers to
 * its set and ground: free it before them. The per-frame calls (advance, set_speed, pose, points,
 * contact) neither allocate nor fail on a valid handle; they walk bit for bit as the C++ Walker
 * and Crowd with the same options. Angles are radians, lengths metres, times seconds. */
#ifndef FUZZYGAIT_FUZZYGAIT_H
#define FUZZYGAIT_FUZZYGAIT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fg_set fg_set;       /* a controller set (manifest + FLL files) */
typedef struct fg_ground fg_ground; /* the ground walked on: a polyline of heights */
typedef struct fg_walker fg_walker; /* one character */
typedef struct fg_crowd fg_crowd;   /* characters stepped together */

typedef struct fg_error {
  int failed;         /* 0: no error */
  char message[1024]; /* the reason, NUL-terminated (cut at 1023 bytes) */
} fg_error;

/* A character's body, pace and start. fg_walker_def_default() fills the defaults: a 1.75 m adult's
 * segments, a 0.70 m step, no speed (walked by step length), 1/240 s time steps, the default
 * start. */
typedef struct fg_walker_def {
  double thigh, shank, ankle_height, heel, ball, toe; /* segment lengths, m */
  double step_length;                                 /* m, heel to heel; used when speed is 0 */
  double speed;     /* m/s: above 0, the walk is by speed, each step the set's stride's */
  double time_step; /* s, 0.00001 to 0.05 */
  int random_start; /* nonzero: random joint angles (seeded) instead of mid-stride */
  uint64_t start_seed;
  int standing_start; /* nonzero: standing, feet side by side, until fg_walker_go() */
} fg_walker_def;

typedef struct fg_leg_angles {
  double hip, knee, ankle, toe; /* the walker's convention (docs/walk.md) */
} fg_leg_angles;

typedef struct fg_pose {
  double pelvis_x, pelvis_y, pelvis_tilt;
  fg_leg_angles legs[2]; /* [FG_LEFT], [FG_RIGHT] */
} fg_pose;

typedef struct fg_point {
  double x, y;
} fg_point;

typedef struct fg_leg_points {
  fg_point hip, knee, ankle, heel, ball, tip;
} fg_leg_points;

enum { FG_LEFT = 0, FG_RIGHT = 1 };

/* The segments of a body of this height (m, 0.5 to 3) in the defaults' proportions; 0 for a
 * height outside that range. */
int fg_segments_from_stature(double stature, fg_walker_def* def);
fg_walker_def fg_walker_def_default(void);

/* A set compiled into the library ("default", "energetic", "heavy", "cautious"), or a folder. */
fg_set* fg_set_builtin(const char* name, fg_error* error);
fg_set* fg_set_load(const char* directory, fg_error* error);
void fg_set_free(fg_set* set);

/* Level ground, or a polyline through `count` points (x, y pairs in `xy`, x rising). */
fg_ground* fg_ground_flat(fg_error* error);
fg_ground* fg_ground_polyline(const double* xy, size_t count, fg_error* error);
/* The ground's height at x (m). */
double fg_ground_height(const fg_ground* ground, double x);
void fg_ground_free(fg_ground* ground);

fg_walker* fg_walker_new(const fg_set* set, const fg_walker_def* def, const fg_ground* ground,
                         fg_error* error);
void fg_walker_free(fg_walker* walker);
/* Advances by dt (s) in fixed time steps; 0, changing nothing, for NaN, negative or over an hour.
 */
int fg_walker_advance(fg_walker* walker, double dt);
/* As Walker::set_speed and set_step_length: the value now commanded (NaN: nothing changed). */
double fg_walker_set_speed(fg_walker* walker, double metres_per_second);
double fg_walker_set_step_length(fg_walker* walker, double metres);
double fg_walker_speed(const fg_walker* walker);
double fg_walker_step_length(const fg_walker* walker);
double fg_walker_time(const fg_walker* walker);
void fg_walker_pose(const fg_walker* walker, fg_pose* pose);
/* side: FG_LEFT or FG_RIGHT (any other value reads the right leg). */
void fg_walker_points(const fg_walker* walker, int side, fg_leg_points* points);
int fg_walker_in_contact(const fg_walker* walker, int side);
/* As Walker::stop() and go(): stop on the spot (the next foot to lift closes beside the planted
 * one, then the walker stands), and walk on from standing. fg_walker_standing(): 1 while both
 * feet stand still side by side (or settle there). */
void fg_walker_stop(fg_walker* walker);
void fg_walker_go(fg_walker* walker);
int fg_walker_standing(const fg_walker* walker);

/* A game's task system, as Box2D v3 takes one (C++: gait::TaskSystem, whose contract holds):
 * enqueue() runs task over [0, item_count) in ranges of at least min_range items, on workers
 * numbered below worker_count, no two running ranges sharing a worker number, all done when
 * finish() (given what enqueue() returned) returns. */
typedef void fg_task(size_t begin, size_t end, size_t worker, void* task_context);
typedef struct fg_task_system {
  size_t worker_count;
  void* (*enqueue)(fg_task* task, size_t item_count, size_t min_range, void* task_context,
                   void* user_context);
  void (*finish)(void* user_task, void* user_context);
  void* user_context;
} fg_task_system;

/* How a crowd uses the cores. fg_crowd_def_default(): one thread (the caller's), no task system.
 */
typedef struct fg_crowd_def {
  size_t threads;       /* the crowd's own pool: 1 the calling thread alone, 0 one a core */
  fg_task_system tasks; /* enqueue set: the game's task system, threads ignored */
} fg_crowd_def;
fg_crowd_def fg_crowd_def_default(void);

/* `count` characters, each as fg_walker_new() would make it (their time steps equal), stepped on
 * the calling thread; fg_crowd_new_with() on the cores `crowd_def` says (NULL: the default). */
fg_crowd* fg_crowd_new(const fg_set* set, const fg_walker_def* defs, size_t count,
                       const fg_ground* ground, fg_error* error);
fg_crowd* fg_crowd_new_with(const fg_set* set, const fg_walker_def* defs, size_t count,
                            const fg_ground* ground, const fg_crowd_def* crowd_def,
                            fg_error* error);
/* How many workers step the crowd's characters. */
size_t fg_crowd_workers(const fg_crowd* crowd);
void fg_crowd_free(fg_crowd* crowd);
size_t fg_crowd_size(const fg_crowd* crowd);
int fg_crowd_advance(fg_crowd* crowd, double dt);
/* Character i's pose and speed commands; i past the end: nothing written, NaN returned. */
void fg_crowd_pose(const fg_crowd* crowd, size_t i, fg_pose* pose);
double fg_crowd_set_speed(fg_crowd* crowd, size_t i, double metres_per_second);
/* fg_walker_stop() and fg_walker_go() of character i: 0 (nothing changed) when i is not one. */
int fg_crowd_stop(fg_crowd* crowd, size_t i);
int fg_crowd_go(fg_crowd* crowd, size_t i);
double fg_crowd_set_step_length(fg_crowd* crowd, size_t i, double metres);

/* ---- The whole body on a path, on a game's skeleton (docs/body.md) ----
 * A follower bends a walker's walk onto a path and poses the whole body in the world every frame;
 * a skeleton turns that pose into a game skeleton's local rotations. World axes: Y up, Z forward,
 * X to the character's left; headings radians from +Z, turning left (towards +X) positive. A
 * follower keeps pointers to its path and its walker's set: free it before them. */
typedef struct fg_path fg_path;         /* a curve on the ground: lines and circular arcs */
typedef struct fg_follower fg_follower; /* one character's body on a path */
typedef struct fg_skeleton fg_skeleton; /* a game's skeleton, mapped onto the body's joints */

typedef struct fg_vec3 {
  double x, y, z;
} fg_vec3;
typedef struct fg_quat { /* a unit quaternion w + xi + yj + zk */
  double w, x, y, z;
} fg_quat;

/* The body's joints (VRM 1.0's humanoid), parents before children. The *_END joints are end
 * points: a position, their parent's rotation. */
enum {
  FG_HIPS, /* the root: the midpoint of the hip joints; its rotation is the pelvis's */
  FG_SPINE,
  FG_CHEST,
  FG_NECK,
  FG_HEAD,
  FG_HEAD_END,
  FG_LEFT_UPPER_LEG, /* hip joint */
  FG_LEFT_LOWER_LEG, /* knee */
  FG_LEFT_FOOT,      /* ankle */
  FG_LEFT_TOES,      /* ball of the foot */
  FG_LEFT_TOES_END,
  FG_RIGHT_UPPER_LEG,
  FG_RIGHT_LOWER_LEG,
  FG_RIGHT_FOOT,
  FG_RIGHT_TOES,
  FG_RIGHT_TOES_END,
  FG_LEFT_SHOULDER, /* the clavicle's inner end */
  FG_LEFT_UPPER_ARM,
  FG_LEFT_LOWER_ARM, /* elbow */
  FG_LEFT_HAND,      /* wrist */
  FG_LEFT_HAND_END,
  FG_RIGHT_SHOULDER,
  FG_RIGHT_UPPER_ARM,
  FG_RIGHT_LOWER_ARM,
  FG_RIGHT_HAND,
  FG_RIGHT_HAND_END,
  FG_JOINT_COUNT
};
/* A joint's VRM name ("hips", "leftUpperLeg", ...; "headEnd", "leftToesEnd", "leftHandEnd" for
 * the end points), NULL past FG_JOINT_COUNT; its parent joint, -1 for FG_HIPS or past the end. */
const char* fg_joint_name(int joint);
int fg_joint_parent(int joint);

/* The whole body in the world at one frame: each joint's position (m) and world rotation from the
 * reference pose (standing upright facing +Z, arms hanging), and the backs of the heels. */
typedef struct fg_body_pose {
  fg_vec3 position[FG_JOINT_COUNT];
  fg_quat rotation[FG_JOINT_COUNT];
  fg_vec3 heel[2]; /* [FG_LEFT], [FG_RIGHT] */
} fg_body_pose;

/* A path's piece: `length` m at constant `curvature` (1/m, left +; 0: straight). */
typedef struct fg_path_piece {
  double length, curvature;
} fg_path_piece;
typedef struct fg_path_sample {
  double x, z;      /* where the path is, m */
  double heading;   /* radians */
  double curvature; /* 1/m, left + */
} fg_path_sample;

/* Straight ahead along +Z from the origin, without end. */
fg_path* fg_path_straight(fg_error* error);
/* From (start_x, start_z) at `heading`, the pieces in order. Refused, naming the piece, for a
 * length not positive and finite, a turn tighter than 0.5 m, a path over 1e6 m. */
fg_path* fg_path_pieces(double start_x, double start_z, double heading, const fg_path_piece* pieces,
                        size_t count, fg_error* error);
/* Through `count` points (x, z pairs in `xz`), each corner rounded by an arc of `corner_radius`
 * (m) or the largest that fits. Refused, naming the point, for fewer than two points, a point not
 * finite, two points within 1 mm, a corner too sharp for an arc of 0.5 m. */
fg_path* fg_path_polyline(const double* xz, size_t count, double corner_radius, fg_error* error);
/* Its length (m; 0 for the straight path); the path at `distance` m along it, straight on past
 * either end. */
double fg_path_length(const fg_path* path);
void fg_path_at(const fg_path* path, double distance, fg_path_sample* sample);
void fg_path_free(fg_path* path);

/* How a follower places the body. fg_follower_def_default() fills C++'s FollowerOptions. */
typedef struct fg_follower_def {
  double step_width_per_leg_length; /* the feet's centre lines apart, over leg length (0.11) */
  double swing_release; /* share of its swing over which a lifted foot eases onto the path (0.6) */
  double look_ahead;    /* m along the path the head looks (0.5) */
  int upper_body;       /* 0: the set's arm and trunk controllers are not played */
  double stature; /* m, the trunk's and arms' proportions when no skeleton is given; 0: the one
                   * the walker's legs stand for (leg length / 0.530) */
} fg_follower_def;
fg_follower_def fg_follower_def_default(void);

/* A follower of `path` for `walker`. The body: `skeleton`'s proportions (the walker must walk on
 * its legs: fg_skeleton_segments), or with skeleton NULL a body of def->stature on the walker's
 * legs. Refused when the walker's legs are not the body's or an option is out of range. */
fg_follower* fg_follower_new(const fg_walker* walker, const fg_path* path,
                             const fg_skeleton* skeleton, const fg_follower_def* def,
                             fg_error* error);
/* Poses the body for the walker now: call it once a frame after fg_walker_advance, with the
 * walker it was made with. The pose lives in the follower until the next update or its free;
 * NULL for a NULL handle. Neither allocates nor fails; the same frames give the same poses, bit
 * for bit those of C++'s PathFollower. */
const fg_body_pose* fg_follower_update(fg_follower* follower, const fg_walker* walker);
/* How far the hips were lowered below the walker's pelvis at the last update (m). */
double fg_follower_pelvis_drop(const fg_follower* follower);
void fg_follower_free(fg_follower* follower);

/* A game's skeleton as flat arrays, parents before children (joint 0 the root, parent -1). */
typedef struct fg_skeleton_def {
  size_t joint_count;
  const char* const* names; /* each joint's name, unique */
  const int* parents;       /* an earlier joint's index; -1 for joint 0 */
  const fg_vec3* offsets;   /* rest offset from the parent, in the parent's frame, skeleton units */
  const fg_quat* rotations; /* rest rotation relative to the parent; NULL: none (as BVH) */
  double metres_per_unit;   /* 0.01 for centimetres */
  /* NULL: the body's joints found by name (CMU, Mixamo, VRM, VRoid, Unreal names, with or without a
   * "prefix:"); else FG_JOINT_COUNT skeleton joint names, one per body joint (NULL or "" for one
   * the skeleton lacks; hips, upper and lower legs and feet are needed). */
  const char* const* humanoid_names;
} fg_skeleton_def;
fg_skeleton_def fg_skeleton_def_default(void); /* all NULL and 0, metres_per_unit 1 */

/* Refused, naming the joint, for an invalid skeleton (a repeated name, a parent after its child, a
 * rotation not of unit length, ...) or body joints that cannot be found (naming the names tried).
 */
fg_skeleton* fg_skeleton_new(const fg_skeleton_def* def, fg_error* error);
void fg_skeleton_free(fg_skeleton* skeleton);
size_t fg_skeleton_joint_count(const fg_skeleton* skeleton);
/* The skeleton joint that stands for body joint `joint`, or -1. */
int fg_skeleton_mapped(const fg_skeleton* skeleton, int joint);
/* The skeleton's legs into def's segments, so that a walker walks on them; 0 for a NULL handle. */
int fg_skeleton_segments(const fg_skeleton* skeleton, fg_walker_def* def);
/* The skeleton posed as `pose` shows the body: each joint's local rotation (joint_count of them)
 * and the root joint's position (skeleton units, replacing its rest offset). Returns 0 and writes
 * the rest pose for a pose that is not finite; 0, writing nothing, for a NULL argument. Neither
 * allocates nor throws; it uses scratch of the handle's: one thread at a time per skeleton. */
int fg_skeleton_pose(fg_skeleton* skeleton, const fg_body_pose* pose, fg_quat* local_rotations,
                     fg_vec3* root_position);

#ifdef __cplusplus
}
#endif

#endif /* FUZZYGAIT_FUZZYGAIT_H */
