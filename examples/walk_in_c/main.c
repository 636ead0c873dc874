/* Walking from C: a character asked for a speed, then a faster one, and a crowd of three; every
 * failure reported with its reason. */
#include <fuzzygait/fuzzygait.h>
#include <stdio.h>

int main(void) {
  fg_error error;
  fg_set* set = fg_set_builtin("default", &error);
  if (!set) {
    fprintf(stderr, "%s\n", error.message);
    return 1;
  }
  fg_walker_def def = fg_walker_def_default();
  fg_segments_from_stature(1.80, &def);
  def.speed = 1.2; /* m/s: each step the one people take at that speed */
  fg_walker* walker = fg_walker_new(set, &def, NULL, &error); /* NULL: level ground */
  if (!walker) {
    fprintf(stderr, "%s\n", error.message);
    fg_set_free(set);
    return 1;
  }
  const double dt = 1.0 / 60.0;
  for (int frame = 0; frame < 600; ++frame) {
    if (frame == 300) fg_walker_set_speed(walker, 1.8);
    fg_walker_advance(walker, dt);
    if (frame % 60 == 0) {
      fg_pose pose;
      fg_walker_pose(walker, &pose);
      printf("t=%5.2f s speed %4.2f m/s step %4.2f m pelvis x=%6.3f left knee %5.1f deg %s\n",
             fg_walker_time(walker), fg_walker_speed(walker), fg_walker_step_length(walker),
             pose.pelvis_x, pose.legs[FG_LEFT].knee * 57.29577951308232,
             fg_walker_in_contact(walker, FG_LEFT) ? "left foot planted" : "left foot swinging");
    }
  }

  /* A bad request is refused with the reason, not a crash. */
  fg_walker_def too_fast = def;
  too_fast.speed = 9.0;
  if (!fg_walker_new(set, &too_fast, NULL, &error)) printf("refused: %s\n", error.message);

  fg_walker_def people[3] = {def, def, def};
  fg_segments_from_stature(1.60, &people[1]);
  people[2].speed = 1.5;
  fg_crowd* crowd = fg_crowd_new(set, people, 3, NULL, &error);
  if (!crowd) {
    fprintf(stderr, "%s\n", error.message);
    return 1;
  }
  for (int frame = 0; frame < 300; ++frame)
    fg_crowd_advance(crowd, dt);
  for (size_t i = 0; i < fg_crowd_size(crowd); ++i) {
    fg_pose pose;
    fg_crowd_pose(crowd, i, &pose);
    printf("character %zu after 5 s: pelvis x=%6.3f\n", i, pose.pelvis_x);
  }
  fg_crowd_free(crowd);
  fg_walker_free(walker);
  fg_set_free(set);
  return 0;
}
