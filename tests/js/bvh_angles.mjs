// Loads a BVH file with three.js's BVHLoader, plays its clip with an AnimationMixer, and prints
// per frame (CSV on stdout) what three.js shows: the sagittal angles in degrees, read off the
// bones' world rotations with fuzzygait's clinical signs, and the joints' world positions in the
// file's units (the legs' joints, then the trunk's). The C++ test (tests/io/bvh_import_test.cpp)
// compares them with the walk's CSV.
//
//   node bvh_angles.mjs walk.bvh > angles.csv
//
// Sagittal angles: the character faces +Z with Y up, so a bone's angle in the (forward, up)
// plane is the angle of its rotated +Z axis, counter-clockwise seen from its left (+X):
//   pelvis tilt = -angle(Hips), thigh inclination = angle(UpLeg),
//   hip = thigh - angle(Hips), knee = angle(UpLeg) - angle(Leg),
//   ankle = angle(Foot) - angle(Leg), toe = angle(ToeBase) - angle(Foot).
import { readFileSync } from 'node:fs';

import { AnimationMixer, LoopOnce, Quaternion, Vector3 } from 'three';
import { BVHLoader } from 'three/examples/jsm/loaders/BVHLoader.js';

const file = process.argv[2];
if (!file) {
  console.error('usage: node bvh_angles.mjs FILE.bvh');
  process.exit(2);
}

const { skeleton, clip } = new BVHLoader().parse(readFileSync(file, 'utf8'));
const root = skeleton.bones[0];
const bone = (name) => {
  const found = skeleton.getBoneByName(name);
  if (!found) throw new Error(`no bone named ${name} in ${file}`);
  return found;
};

const mixer = new AnimationMixer(root);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;  // the last frame stays the last frame
action.play();

const quaternion = new Quaternion();
const axis = new Vector3();
const degrees = (radians) => radians * 180 / Math.PI;
// Counter-clockwise angle of the bone's forward axis in the (Z forward, Y up) plane.
const sagittal = (b) => {
  b.getWorldQuaternion(quaternion);
  axis.set(0, 0, 1).applyQuaternion(quaternion);
  return Math.atan2(axis.y, axis.z);
};
// Keeps a difference of two angles within (-180, 180] degrees.
const wrap = (radians) => Math.atan2(Math.sin(radians), Math.cos(radians));
const position = (b) => b.getWorldPosition(new Vector3());

const sides = [['l', 'Left'], ['r', 'Right']];
const joints = ['hip', 'knee', 'ankle', 'ball', 'tip'];
const header = ['frame', 'time', 'pelvis_x', 'pelvis_y', 'pelvis_z', 'pelvis_tilt'];
for (const [s] of sides) {
  header.push(`${s}_thigh`, `${s}_hip`, `${s}_knee`, `${s}_ankle`, `${s}_toe`);
}
for (const [s] of sides) {
  for (const j of joints) header.push(`${s}_${j}_x`, `${s}_${j}_y`, `${s}_${j}_z`);
}
for (const j of ['spine', 'neck', 'head', 'head_top']) header.push(`${j}_x`, `${j}_y`, `${j}_z`);
const lines = [header.join(',')];

// Keyframe times as three.js stores them (Float32Array), so each sample hits its keyframe.
const times = clip.tracks[0].times;
for (let frame = 0; frame < times.length; ++frame) {
  mixer.setTime(times[frame]);
  root.updateMatrixWorld(true);
  const pelvis = sagittal(root);
  const row = [frame, times[frame].toFixed(6)];
  const rootPosition = position(root);
  row.push(...rootPosition.toArray().map((v) => v.toFixed(6)));
  row.push(degrees(-pelvis).toFixed(6));
  const points = [];
  for (const [, name] of sides) {
    const upLeg = bone(`${name}UpLeg`);
    const leg = bone(`${name}Leg`);
    const foot = bone(`${name}Foot`);
    const toes = bone(`${name}ToeBase`);
    const thigh = sagittal(upLeg);
    const shank = sagittal(leg);
    const footAngle = sagittal(foot);
    const toesAngle = sagittal(toes);
    row.push(...[thigh, wrap(thigh - pelvis), wrap(thigh - shank), wrap(footAngle - shank),
      wrap(toesAngle - footAngle)].map((a) => degrees(a).toFixed(6)));
    // The toe tip is the End Site, which BVHLoader makes a child bone of the toes.
    for (const b of [upLeg, leg, foot, toes, toes.children[0]]) {
      points.push(...position(b).toArray().map((v) => v.toFixed(6)));
    }
  }
  const head = bone('Head');
  for (const b of [bone('Spine'), bone('Neck'), head, head.children[0]]) {
    points.push(...position(b).toArray().map((v) => v.toFixed(6)));
  }
  row.push(...points);
  lines.push(row.join(','));
}
process.stdout.write(lines.join('\n') + '\n');
