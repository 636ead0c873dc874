// Loads a binary glTF file (.glb) with three.js's GLTFLoader, plays its first animation with an
// AnimationMixer, and prints per keyframe (CSV on stdout) what three.js shows: the sagittal
// angles in degrees, read off the bones' world rotations with fuzzygait's clinical signs; the
// joints' world positions in metres; and the lowest and highest points of the skinned body (its
// vertices as three.js skins them). The C++ test (tests/io/gltf_import_test.cpp) compares them
// with the walk's CSV. The columns are bvh_angles.mjs's, plus body_lowest_y and body_highest_y.
//
//   node gltf_angles.mjs walk.glb > angles.csv
//
// Sagittal angles: the character faces +Z with Y up, so a bone's angle in the (forward, up)
// plane is the angle of its rotated +Z axis, counter-clockwise seen from its left (+X):
//   pelvis tilt = -angle(Hips), thigh inclination = angle(UpLeg),
//   hip = thigh - angle(Hips), knee = angle(UpLeg) - angle(Leg),
//   ankle = angle(Foot) - angle(Leg), toe = angle(ToeBase) - angle(Foot).
import { readFileSync } from 'node:fs';

import { AnimationMixer, LoopOnce, Quaternion, Vector3 } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const file = process.argv[2];
if (!file) {
  console.error('usage: node gltf_angles.mjs FILE.glb');
  process.exit(2);
}

// GLTFLoader.parse wants an ArrayBuffer of the file alone (a Node Buffer may share a larger one).
const bytes = readFileSync(file);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(data, '', resolve, reject));

const scene = gltf.scene;
const bone = (name) => {
  const found = scene.getObjectByName(name);
  if (!found || !found.isBone) throw new Error(`no bone named ${name} in ${file}`);
  return found;
};
if (gltf.animations.length !== 1) {
  throw new Error(`${file} has ${gltf.animations.length} animations, not one`);
}
const clip = gltf.animations[0];
const skinned = [];
scene.traverse((object) => {
  if (object.isSkinnedMesh) skinned.push(object);
});
if (skinned.length === 0) throw new Error(`${file} has no skinned mesh`);

const mixer = new AnimationMixer(scene);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;  // the last frame stays the last frame
action.play();

const quaternion = new Quaternion();
const axis = new Vector3();
const vertex = new Vector3();
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
// The skinned body's vertical extent, as three.js draws it.
const bodyExtent = () => {
  let lowest = Infinity;
  let highest = -Infinity;
  for (const mesh of skinned) {
    const count = mesh.geometry.attributes.position.count;
    for (let i = 0; i < count; ++i) {
      mesh.getVertexPosition(i, vertex);
      mesh.localToWorld(vertex);
      lowest = Math.min(lowest, vertex.y);
      highest = Math.max(highest, vertex.y);
    }
  }
  return [lowest, highest];
};

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
header.push('body_lowest_y', 'body_highest_y');
const lines = [header.join(',')];

const root = bone('Hips');
// Keyframe times as three.js stores them (Float32Array), so each sample hits its keyframe.
const times = clip.tracks[0].times;
for (let frame = 0; frame < times.length; ++frame) {
  mixer.setTime(times[frame]);
  scene.updateMatrixWorld(true);
  const pelvis = sagittal(root);
  const row = [frame, times[frame].toFixed(6)];
  row.push(...position(root).toArray().map((v) => v.toFixed(6)));
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
    for (const b of [upLeg, leg, foot, toes, bone(`${name}Toe_End`)]) {
      points.push(...position(b).toArray().map((v) => v.toFixed(6)));
    }
  }
  for (const name of ['Spine', 'Neck', 'Head', 'HeadTop_End']) {
    points.push(...position(bone(name)).toArray().map((v) => v.toFixed(6)));
  }
  row.push(...points);
  row.push(...bodyExtent().map((v) => v.toFixed(6)));
  lines.push(row.join(','));
}
process.stdout.write(lines.join('\n') + '\n');
