/* The whole body along a curved path, from C: a game's skeleton given as arrays (Mixamo's names,
 * centimetres), a walker on its legs, a follower bending the walk onto an S of two rounded right
 * angles, and each frame the body's joints in the world and the skeleton's local rotations. */
#include <fuzzygait/fuzzygait.h>
#include <stdio.h>

#define JOINTS 24

/* Mixamo-named joints, rest offsets from the parent in centimetres (no rest rotations, as BVH). */
static const char* const names[JOINTS] = {
    "mixamorig:Hips",          "mixamorig:Spine",        "mixamorig:Spine1",
    "mixamorig:Spine2",        "mixamorig:Neck",         "mixamorig:Head",
    "mixamorig:LeftUpLeg",     "mixamorig:LeftLeg",      "mixamorig:LeftFoot",
    "mixamorig:LeftToeBase",   "mixamorig:RightUpLeg",   "mixamorig:RightLeg",
    "mixamorig:RightFoot",     "mixamorig:RightToeBase", "mixamorig:LeftShoulder",
    "mixamorig:LeftArm",       "mixamorig:LeftForeArm",  "mixamorig:LeftHand",
    "mixamorig:RightShoulder", "mixamorig:RightArm",     "mixamorig:RightForeArm",
    "mixamorig:RightHand",     "mixamorig:LeftToe_End",  "mixamorig:RightToe_End"};
static const int parents[JOINTS] = {-1, 0,  1, 2,  3,  4,  0, 6,  7,  8,  0, 10,
                                    11, 12, 3, 14, 15, 16, 3, 18, 19, 20, 9, 13};
static const fg_vec3 offsets[JOINTS] = {
    {0, 100, -2}, {0, 10, -1},  {0, 12, 0},  {0, 13, 1},  {0, 17, 0},  {0, 10, 2},
    {9, -8, 2},   {0, -42, 0},  {0, -42, 0}, {0, -8, 13}, {-9, -8, 2}, {0, -42, 0},
    {0, -42, 0},  {0, -8, 13},  {3, 11, -1}, {14, -1, 0}, {28, 0, 0},  {25, 0, 0},
    {-3, 11, -1}, {-14, -1, 0}, {-28, 0, 0}, {-25, 0, 0}, {0, 0, 7},   {0, 0, 7}};

static int fail(const fg_error* error) {
  fprintf(stderr, "%s\n", error->message);
  return 1;
}

int main(void) {
  fg_error error;
  fg_skeleton_def skeleton_def = fg_skeleton_def_default();
  skeleton_def.joint_count = JOINTS;
  skeleton_def.names = names;
  skeleton_def.parents = parents;
  skeleton_def.offsets = offsets;
  skeleton_def.metres_per_unit = 0.01;
  fg_skeleton* hero = fg_skeleton_new(&skeleton_def, &error); /* joints found by their names */
  if (!hero) return fail(&error);
  printf("skeleton: %zu joints, %s <- %s\n", fg_skeleton_joint_count(hero),
         fg_joint_name(FG_LEFT_UPPER_ARM), names[fg_skeleton_mapped(hero, FG_LEFT_UPPER_ARM)]);

  fg_set* set = fg_set_builtin("default", &error);
  if (!set) return fail(&error);
  fg_walker_def walker_def = fg_walker_def_default();
  fg_skeleton_segments(hero, &walker_def); /* the walker walks on the skeleton's legs */
  walker_def.speed = 1.2;
  fg_walker* walker = fg_walker_new(set, &walker_def, NULL, &error);
  if (!walker) return fail(&error);

  /* 3 m ahead, right angles left then right, each rounded at 1 m, 3 m on (x, z points). */
  const double corners[] = {0.0, 0.0, 0.0, 3.0, 3.0, 3.0, 3.0, 6.0};
  fg_path* route = fg_path_polyline(corners, 4, 1.0, &error);
  if (!route) return fail(&error);
  const fg_follower_def follower_def = fg_follower_def_default();
  fg_follower* follower = fg_follower_new(walker, route, hero, &follower_def, &error);
  if (!follower) return fail(&error);

  fg_quat local[JOINTS];
  fg_vec3 root;
  const double dt = 1.0 / 60.0;
  fg_pose pose;
  fg_walker_pose(walker, &pose);
  for (int frame = 0; frame < 900 && pose.pelvis_x < fg_path_length(route); ++frame) {
    fg_walker_advance(walker, dt);
    fg_walker_pose(walker, &pose); /* pelvis_x: the distance walked along the path */
    const fg_body_pose* body = fg_follower_update(follower, walker); /* no allocation */
    fg_skeleton_pose(hero, body, local, &root);
    if (frame % 60 == 0) {
      const fg_vec3 hips = body->position[FG_HIPS];
      const fg_vec3 hand = body->position[FG_LEFT_HAND];
      const fg_vec3 ankle = body->position[FG_RIGHT_FOOT];
      const fg_quat arm = local[15]; /* mixamorig:LeftArm */
      printf(
          "t=%5.2f s  hips (%5.2f, %4.2f, %5.2f)  left hand (%5.2f, %4.2f, %5.2f)  right ankle "
          "(%5.2f, %4.2f, %5.2f)  LeftArm local (%5.2f %5.2f %5.2f %5.2f)%s\n",
          fg_walker_time(walker), hips.x, hips.y, hips.z, hand.x, hand.y, hand.z, ankle.x, ankle.y,
          ankle.z, arm.w, arm.x, arm.y, arm.z,
          fg_walker_in_contact(walker, FG_RIGHT) ? "  right foot planted" : "");
    }
  }
  fg_path_sample end;
  fg_path_at(route, fg_path_length(route), &end);
  printf("path end (%.2f, %.2f): %s after %.2f m; the root at (%.1f, %.1f, %.1f) cm\n", end.x,
         end.z, pose.pelvis_x >= fg_path_length(route) ? "reached" : "not reached", pose.pelvis_x,
         root.x, root.y, root.z);

  /* A bad request is refused with the reason, not a crash. */
  const double doubled[] = {0.0, 0.0, 0.0, 2.0, 0.0, 2.0};
  if (!fg_path_polyline(doubled, 3, 1.0, &error)) printf("refused: %s\n", error.message);

  fg_follower_free(follower); /* before its path and its walker's set */
  fg_path_free(route);
  fg_walker_free(walker);
  fg_set_free(set);
  fg_skeleton_free(hero);
  return 0;
}
