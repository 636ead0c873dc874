/* fuzzygait from C: controller sets, grounds, walkers and crowds behind opaque handles.
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
double fg_crowd_set_step_length(fg_crowd* crowd, size_t i, double metres);

#ifdef __cplusplus
}
#endif

#endif /* FUZZYGAIT_FUZZYGAIT_H */
