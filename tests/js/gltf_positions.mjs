// Loads a binary glTF file (.glb) of a posed skeleton (io::write_skeleton_gltf) with three.js's
// GLTFLoader, plays its animation "Walk" with an AnimationMixer at every key's time, and prints
// per key (CSV on stdout) every skin joint's world position in metres, glTF's axes: columns frame,
// time, then NAME_x, NAME_y, NAME_z for each joint in skin order, NAME the file's node name (three.js
// renames nodes whose names hold characters its animation paths reserve, such as Mixamo's ':';
// the bones are taken from the skin, not by name). The C++ test
// (tests/io/skeleton_gltf_import_test.cpp) compares them with the skeleton's forward kinematics.
//
//   node gltf_positions.mjs body.glb > positions.csv
import { readFileSync } from 'node:fs';

import { AnimationMixer, LoopOnce, Vector3 } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const file = process.argv[2];
if (!file) {
  console.error('usage: node gltf_positions.mjs FILE.glb');
  process.exit(2);
}

// GLTFLoader.parse wants an ArrayBuffer of the file alone (a Node Buffer may share a larger one).
const bytes = readFileSync(file);
const data = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(data, '', resolve, reject));

const clip = gltf.animations.find((a) => a.name === 'Walk');
if (!clip) throw new Error(`${file} has no animation named Walk`);
const skinned = [];
gltf.scene.traverse((object) => {
  if (object.isSkinnedMesh) skinned.push(object);
});
if (skinned.length !== 1) throw new Error(`${file} has ${skinned.length} skinned meshes, not one`);
const bones = skinned[0].skeleton.bones;
const json = gltf.parser.json;
const names = json.skins[0].joints.map((node) => json.nodes[node].name);
if (bones.length !== names.length || bones.some((b) => !b.isBone)) {
  throw new Error(`${file}: the skin's ${names.length} joints are not ${bones.length} bones`);
}

const mixer = new AnimationMixer(gltf.scene);
const action = mixer.clipAction(clip);
action.setLoop(LoopOnce, 1);
action.clampWhenFinished = true;  // the last frame stays the last frame
action.play();

const header = ['frame', 'time'];
for (const name of names) header.push(`${name}_x`, `${name}_y`, `${name}_z`);
const lines = [header.join(',')];
// Keyframe times as three.js stores them (Float32Array), so each sample hits its keyframe.
const times = clip.tracks[0].times;
const at = new Vector3();
for (let frame = 0; frame < times.length; ++frame) {
  mixer.setTime(times[frame]);
  gltf.scene.updateMatrixWorld(true);
  const row = [frame, times[frame].toFixed(6)];
  for (const b of bones) row.push(...b.getWorldPosition(at).toArray().map((v) => v.toFixed(7)));
  lines.push(row.join(','));
}
process.stdout.write(lines.join('\n') + '\n');
