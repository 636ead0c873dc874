// Loads a BVH file with three.js's BVHLoader, plays its clip with an AnimationMixer, and prints
// per frame (CSV on stdout) every joint's world position in the file's units and axes: columns
// frame, then NAME_x, NAME_y, NAME_z for each joint in file order (End Sites left out). The C++
// test (tests/io/skeleton_import_test.cpp) compares them with the skeleton's forward kinematics.
//
//   node bvh_positions.mjs skeleton.bvh > positions.csv
import { readFileSync } from 'node:fs';

import { AnimationMixer, LoopOnce, Vector3 } from 'three';
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';

const file = process.argv[2];
if (!file) {
  console.error('usage: node bvh_positions.mjs FILE.bvh');
  process.exit(2);
}

const { skeleton, clip } = new BVHLoader().parse(readFileSync(file, 'utf8'));
const root = skeleton.bones[0];
const joints = skeleton.bones.filter((b) => b.type !== 'ENDSITE');

const mixer = new AnimationMixer(root);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;  // the last frame stays the last frame
action.play();

const header = ['frame'];
for (const b of joints) header.push(`${b.name}_x`, `${b.name}_y`, `${b.name}_z`);
const lines = [header.join(',')];
// Keyframe times as three.js stores them (Float32Array), so each sample hits its keyframe.
const times = clip.tracks[0].times;
const at = new Vector3();
for (let frame = 0; frame < times.length; ++frame) {
  mixer.setTime(times[frame]);
  root.updateMatrixWorld(true);
  const row = [frame];
  for (const b of joints) row.push(...b.getWorldPosition(at).toArray().map((v) => v.toFixed(6)));
  lines.push(row.join(','));
}
process.stdout.write(lines.join('\n') + '\n');
