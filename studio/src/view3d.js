// The character walking in 3D (three.js): a low-poly body placed on the joints of the walk's
// whole body (body::PathFollower's poses on the path drawn, or a straight one: the legs, the
// pelvis turning, rolling and swaying, the trunk and the arms swinging as the set's upper body
// controllers answer), the ground as a tiled strip along the path, a camera that follows the
// pelvis and orbits with the mouse. A second, translucent character walks beside it (on a drawn
// path, on it) when a set is compared.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { heightAt, makePose } from './motion.js';

const GROUND_WIDTH = 2.6; // metres across the walk
const PATH_WIDTH = 1.6; // metres across a drawn path's strip
const PATH_LINE = 0.025; // metres either side of the path's centre line
const TILE = 0.5; // metres, the ground's checker
const COMPARE_OFFSET = -0.9; // metres across: the compared character walks behind, to the far side

// Lambert shading: cheap enough for a browser drawing in software, and enough for flat cloth.
function material(color, ghost) {
  return new THREE.MeshLambertMaterial({
    color,
    transparent: ghost,
    opacity: ghost ? 0.5 : 1,
    depthWrite: !ghost,
  });
}

// A capsule of a given radius whose axis runs between two points; its length is set when placed.
class Limb {
  constructor(radius, mat, parent) {
    this.radius = radius;
    this.mesh = new THREE.Mesh(new THREE.CapsuleGeometry(radius, 1, 4, 10), mat);
    this.length = 1;
    parent.add(this.mesh);
  }
  place(a, b) {
    const dx = b.x - a.x;
    const dy = b.y - a.y;
    const dz = b.z - a.z;
    const length = Math.hypot(dx, dy, dz);
    const axis = Math.max(length - 2 * this.radius, 1e-3);
    if (Math.abs(axis - this.length) > 1e-4) {
      this.mesh.geometry.dispose();
      this.mesh.geometry = new THREE.CapsuleGeometry(this.radius, axis, 4, 10);
      this.length = axis;
    }
    this.mesh.position.set((a.x + b.x) / 2, (a.y + b.y) / 2, (a.z + b.z) / 2);
    const direction = new THREE.Vector3(dx, dy, dz).normalize();
    this.mesh.quaternion.setFromUnitVectors(UP, direction);
  }
}
const UP = new THREE.Vector3(0, 1, 0);

// A box lying along the sole from `a` to `b`, its underside on that line.
class Sole {
  constructor(width, height, mat, parent) {
    this.height = height;
    this.mesh = new THREE.Mesh(new THREE.BoxGeometry(1, height, width), mat);
    parent.add(this.mesh);
  }
  place(a, b) {
    const dx = b.x - a.x;
    const dy = b.y - a.y;
    const length = Math.max(Math.hypot(dx, dy), 1e-3);
    const angle = Math.atan2(dy, dx);
    // Lift the centre half the height off the sole line, perpendicular to it.
    const nx = -Math.sin(angle) * this.height * 0.5;
    const ny = Math.cos(angle) * this.height * 0.5;
    this.mesh.scale.set(length, 1, 1);
    this.mesh.position.set((a.x + b.x) / 2 + nx, (a.y + b.y) / 2 + ny, (a.z + b.z) / 2);
    this.mesh.rotation.set(0, 0, angle);
  }
}

class Figure {
  constructor(scene, ghost) {
    this.group = new THREE.Group();
    scene.add(this.group);
    this.ghost = ghost;
    this.built = null;
    this.pose = makePose();
    this.body = null; // the body's joints, as Motion.sampleBody gives them
  }

  // Builds the body for a stature (metres); sizes in proportion, as the glTF export's.
  build(stature) {
    if (this.built === stature) return;
    const materials = new Set();
    this.group.traverse((object) => {
      if (!object.isMesh) return;
      object.geometry.dispose();
      materials.add(object.material);
    });
    for (const m of materials) m.dispose();
    this.group.clear();
    this.built = stature;
    const H = stature;
    const g = this.ghost;
    const shirt = material(g ? 0xe8923a : 0x3d6fb8, g);
    const trousers = material(g ? 0xd9822b : 0x394452, g);
    const skin = material(g ? 0xf0a860 : 0xe2b48f, g);
    const shoes = material(g ? 0xc4711e : 0x262626, g);
    this.legs = [0, 1].map(() => ({
      thigh: new Limb(0.034 * H, trousers, this.group),
      shank: new Limb(0.025 * H, trousers, this.group),
      foot: new Sole(0.05 * H, 0.03 * H, shoes, this.group),
      toes: new Sole(0.048 * H, 0.018 * H, shoes, this.group),
    }));
    this.pelvis = new Limb(0.05 * H, trousers, this.group);
    this.trunk = new Limb(0.085 * H, shirt, this.group);
    this.shoulders = new Limb(0.04 * H, shirt, this.group);
    this.neck = new Limb(0.022 * H, skin, this.group);
    this.head = new THREE.Mesh(new THREE.SphereGeometry(0.062 * H, 16, 12), skin);
    this.nose = new THREE.Mesh(new THREE.SphereGeometry(0.012 * H, 8, 6), skin);
    this.group.add(this.head, this.nose);
    this.arms = [0, 1].map(() => ({
      upper: new Limb(0.022 * H, shirt, this.group),
      lower: new Limb(0.019 * H, skin, this.group),
      hand: new Limb(0.016 * H, skin, this.group),
    }));
  }

  place(motion, t, offsetZ) {
    const H = motion.stature;
    this.build(H);
    this.pose = motion.sample(t, this.pose);
    this.body = motion.sampleBody(t, offsetZ, this.body || undefined);
    this.ahead = motion.track.at(this.pose.pelvis.x + LOOK_AHEAD, this.ahead);
    this.offsetZ = offsetZ;
    const at = (name) => this.body[motion.joints.get(name)];
    for (const [index, side] of [[0, 'left'], [1, 'right']]) {
      const leg = this.legs[index];
      leg.thigh.place(at(`${side}UpperLeg`), at(`${side}LowerLeg`));
      leg.shank.place(at(`${side}LowerLeg`), at(`${side}Foot`));
      leg.foot.place(at(`${side}Heel`), at(`${side}Toes`));
      leg.toes.place(at(`${side}Toes`), at(`${side}ToesEnd`));
      const arm = this.arms[index];
      arm.upper.place(at(`${side}UpperArm`), at(`${side}LowerArm`));
      arm.lower.place(at(`${side}LowerArm`), at(`${side}Hand`));
      arm.hand.place(at(`${side}Hand`), at(`${side}HandEnd`));
    }
    // The pelvis across the hip joints (a little wider): it turns, rolls and sways with them.
    const hips = at('hips');
    const across = (name, lift) => {
      const p = at(name);
      return { x: hips.x + (p.x - hips.x) * 1.1, y: hips.y + (p.y - hips.y) * 1.1 + lift, z: hips.z + (p.z - hips.z) * 1.1 };
    };
    this.pelvis.place(across('leftUpperLeg', 0.01 * H), across('rightUpperLeg', 0.01 * H));
    // The trunk from the waist, halfway from the hips to the lumbar joint, to the base of the neck.
    const spine = at('spine');
    this.trunk.place({ x: (hips.x + spine.x) / 2, y: (hips.y + spine.y) / 2, z: (hips.z + spine.z) / 2 }, at('neck'));
    this.shoulders.place(at('leftUpperArm'), at('rightUpperArm'));
    this.neck.place(at('neck'), at('head'));
    const head = at('head');
    const top = at('headEnd');
    this.head.position.set((head.x + top.x) / 2, (head.y + top.y) / 2, (head.z + top.z) / 2);
    // The head looks at the path ahead, as body::PathFollower turns it (look_ahead).
    const lx = this.ahead.x - this.head.position.x;
    const lz = this.ahead.z + offsetZ - this.head.position.z;
    const look = Math.hypot(lx, lz) || 1;
    this.nose.position.set(this.head.position.x + (0.06 * H * lx) / look, this.head.position.y - 0.005 * H,
      this.head.position.z + (0.06 * H * lz) / look);
  }

  // Where the hips are now (after place).
  hips(motion) {
    return this.body[motion.joints.get('hips')];
  }

  set visible(v) {
    this.group.visible = v;
  }
}

// How far ahead along the path the head looks (m): body::FollowerOptions::look_ahead.
const LOOK_AHEAD = 0.5;

function disposeAll(object) {
  object.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    if (o.material) o.material.dispose();
  });
}

// The ground's colours: the tiles light and dark, risers, sides, a drawn path's centre line.
const GROUND = {
  light: new THREE.Color(0xcfd6c8),
  dark: new THREE.Color(0xa9b5a0),
  riser: new THREE.Color(0x8c9886),
  side: new THREE.Color(0x7c8777),
  line: new THREE.Color(0xd9822b),
};

// A mesh of coloured quads, added one at a time (corners [x, y, z] in order round each).
class Quads {
  constructor() {
    this.positions = [];
    this.colors = [];
  }
  add(a, b, c, d, color) {
    for (const v of [a, b, c, a, c, d]) {
      this.positions.push(v[0], v[1], v[2]);
      this.colors.push(color.r, color.g, color.b);
    }
  }
  mesh() {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(this.positions, 3));
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(this.colors, 3));
    geometry.computeVertexNormals();
    return new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }));
  }
}

// Where the ground's sides end: 0.4 m below the lowest point of its profile ([[x, y], ...]).
function groundBottom(points) {
  let bottom = Infinity;
  for (const [, y] of points) bottom = Math.min(bottom, y);
  return bottom - 0.4;
}

function groundMesh(points) {
  const quads = new Quads();
  const half = GROUND_WIDTH / 2;
  const bottom = groundBottom(points);
  for (let i = 0; i + 1 < points.length; i++) {
    const [x0, y0] = points[i];
    const [x1, y1] = points[i + 1];
    const steep = Math.abs(x1 - x0) < 0.01;
    // Cut the segment where it crosses a tile edge, so the checker follows the ground.
    const cuts = [x0];
    if (!steep) {
      for (let x = Math.ceil(x0 / TILE) * TILE; x < x1; x += TILE) if (x > x0) cuts.push(x);
    }
    cuts.push(x1);
    for (let k = 0; k + 1 < cuts.length; k++) {
      const xa = cuts[k];
      const xb = cuts[k + 1];
      const ya = y0 + ((y1 - y0) * (xa - x0)) / (x1 - x0 || 1);
      const yb = y0 + ((y1 - y0) * (xb - x0)) / (x1 - x0 || 1);
      const column = Math.floor((xa + xb) / 2 / TILE);
      for (let z = -half; z < half - 1e-9; z += TILE) {
        const row = Math.floor(z / TILE);
        const color = steep ? GROUND.riser : (column + row) % 2 === 0 ? GROUND.light : GROUND.dark;
        quads.add([xa, ya, z + TILE], [xb, yb, z + TILE], [xb, yb, z], [xa, ya, z], color);
      }
      // The near side face, down to below the lowest ground: stairs read as solid.
      quads.add([xa, bottom, half], [xb, bottom, half], [xb, yb, half], [xa, ya, half], GROUND.side);
    }
  }
  return quads.mesh();
}

// The ground under a drawn path: a strip PATH_WIDTH wide along it, at the terrain's height at each
// distance along it (the walker's ground is the terrain along the path), tiled as the straight
// strip; on it the path's centre line; around it a line every metre, level with the strip on
// level ground, else below the lowest ground with the strip's sides down to it.
// On a turn tighter than half the strip its inner edge keeps to 0.9 of the radius, so the strip
// does not fold over itself.
function pathGround(track, profile) {
  const quads = new Quads();
  const level = profile.every(([, y]) => Math.abs(y - profile[0][1]) < 1e-6);
  const bottom = level ? profile[0][1] - 0.002 : groundBottom(profile);
  // Cuts along the path: every 0.1 m (its samples) and at each point of the profile (risers).
  const start = profile[0][0];
  const end = profile[profile.length - 1][0];
  const cuts = new Set();
  for (let s = Math.ceil(start / 0.1) * 0.1; s < end; s += 0.1) cuts.add(Number(s.toFixed(4)));
  for (const [x] of profile) cuts.add(x);
  const sorted = [...cuts].sort((a, b) => a - b);
  const before = { x: 0, z: 0, dx: 1, dz: 0 };
  const after = { x: 0, z: 0, dx: 1, dz: 0 };
  // The cross-section at distance s: points `across` metres to the left (negative: right), at the
  // ground's height there lifted by `lift`.
  const sections = sorted.map((s) => {
    const here = track.at(s);
    track.at(s - 0.1, before);
    track.at(s + 0.1, after);
    const turn = Math.atan2(before.dx * after.dz - before.dz * after.dx, before.dx * after.dx + before.dz * after.dz);
    const radius = Math.abs(turn) > 1e-6 ? 0.2 / Math.abs(turn) : Infinity;
    const inner = Math.min(PATH_WIDTH / 2, 0.9 * radius);
    const y = heightAt(profile, s);
    const nx = -here.dz;
    const nz = here.dx;
    const at = (across, lift = 0) => [here.x + nx * across, y + lift, here.z + nz * across];
    const half = PATH_WIDTH / 2;
    // The left edge is the inner one when the path turns left (turn > 0: towards +z).
    const left = turn > 0 ? inner : half;
    const right = turn < 0 ? inner : half;
    return { s, y, at, left, right };
  });
  for (let i = 0; i + 1 < sections.length; i++) {
    const a = sections[i];
    const b = sections[i + 1];
    const steep = b.s - a.s < 0.01 && Math.abs(b.y - a.y) > 1e-4;
    const column = Math.floor((a.s + b.s) / 2 / (GROUND_WIDTH / 5.2));
    // Across, from the right edge to the left: the right half, the centre line (two spans, lifted
    // 2 mm) and the left half; [a's inner side, b's, a's outer, b's].
    const spans = [[-a.right, -b.right, -PATH_LINE, -PATH_LINE], [-PATH_LINE, -PATH_LINE, 0, 0],
      [0, 0, PATH_LINE, PATH_LINE], [PATH_LINE, PATH_LINE, a.left, b.left]];
    spans.forEach(([a0, b0, a1, b1], row) => {
      const onLine = row === 1 || row === 2;
      const color = steep ? GROUND.riser : onLine ? GROUND.line : (column + row) % 2 === 0 ? GROUND.light : GROUND.dark;
      quads.add(a.at(a1, onLine ? 0.002 : 0), b.at(b1, onLine ? 0.002 : 0), b.at(b0, onLine ? 0.002 : 0),
        a.at(a0, onLine ? 0.002 : 0), color);
    });
    // The sides, down to below the lowest ground: stairs read as solid.
    const down = ([x, , z]) => [x, bottom, z];
    for (const [pa, pb] of level ? [] : [[a.at(a.left), b.at(b.left)], [b.at(-b.right), a.at(-a.right)]]) {
      quads.add(down(pa), down(pb), pb, pa, GROUND.side);
    }
  }
  const group = new THREE.Group();
  group.add(quads.mesh());
  // A grid a metre a square around the path, at the lowest ground.
  let [x0, x1, z0, z1] = [Infinity, -Infinity, Infinity, -Infinity];
  for (let k = 0; k < track.x.length; k++) {
    x0 = Math.min(x0, track.x[k]);
    x1 = Math.max(x1, track.x[k]);
    z0 = Math.min(z0, track.z[k]);
    z1 = Math.max(z1, track.z[k]);
  }
  // Lines only: a plane under them cost a browser drawing in software some 20 ms an edit (a pair
  // of runs of 14 edits).
  const size = Math.ceil(Math.max(x1 - x0, z1 - z0) + 12);
  const grid = new THREE.GridHelper(size, size, 0xc3cbbd, 0xc3cbbd);
  grid.position.set(Math.round((x0 + x1) / 2), bottom, Math.round((z0 + z1) / 2));
  group.add(grid);
  return group;
}

// Whether WebGL runs on the processor (SwiftShader, llvmpipe) rather than a graphics card.
function softwareRendering() {
  try {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
    const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : '';
    gl?.getExtension('WEBGL_lose_context')?.loseContext();
    return /swiftshader|llvmpipe|software/i.test(name);
  } catch {
    return false;
  }
}

export class View3D {
  // `overlay`: an element over the view's right side (the settings); the character is centred in
  // what it leaves free.
  constructor(container, overlay) {
    this.container = container;
    this.overlay = overlay;
    // Drawn in software (no GPU: a headless browser, a remote desktop), the view is drawn without
    // multisampling, at a lower resolution and at most 20 times a second, so that it leaves the
    // processor to the edits (docs/studio.md, "Latency").
    // ?render=full draws it as with a graphics card (for pictures of the page).
    this.software = softwareRendering() && new URLSearchParams(location.search).get('render') !== 'full';
    this.renderer = new THREE.WebGLRenderer({ antialias: !this.software });
    this.renderer.setPixelRatio(this.software ? 0.6 : Math.min(window.devicePixelRatio, 2));
    this.lastDrawn = -Infinity;
    container.prepend(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xeef2f6);
    this.scene.fog = new THREE.Fog(0xeef2f6, 7, 16);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x9aa39a, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, 5, 4);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(38, 1, 0.05, 60);
    this.camera.position.set(1.6, 1.35, 3.9);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0.9, 0);
    this.controls.enablePan = false;
    this.controls.minDistance = 1.5;
    this.controls.maxDistance = 12;
    this.controls.maxPolarAngle = Math.PI * 0.49;
    this.figure = new Figure(this.scene, false);
    this.ghost = new Figure(this.scene, true);
    // A soft shadow under each character, on the ground below its pelvis.
    const shadow = () => {
      const mesh = new THREE.Mesh(new THREE.CircleGeometry(0.32, 24),
        new THREE.MeshBasicMaterial({ color: 0x000000, transparent: true, opacity: 0.16, depthWrite: false }));
      mesh.rotation.x = -Math.PI / 2;
      mesh.scale.set(1.3, 0.6, 1);
      this.scene.add(mesh);
      return mesh;
    };
    this.shadows = [shadow(), shadow()];
    this.ground = null;
    this.groundKey = '';
    this.motion = null;
    this.compare = null;
    const observer = new ResizeObserver(() => this.resize());
    observer.observe(container);
    if (overlay) observer.observe(overlay);
    this.resize();
  }

  resize() {
    const w = this.container.clientWidth;
    const h = this.container.clientHeight;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    const covered = this.overlay ? Math.min(this.overlay.offsetWidth, w / 2) : 0;
    this.camera.setViewOffset(w, h, covered / 2, 0, w, h);
    this.camera.updateProjectionMatrix();
  }

  setWalks(motion, compare) {
    this.motion = motion;
    this.compare = compare;
    const key = JSON.stringify([motion.ground, motion.track.path && motion.track.path.samples]);
    if (key !== this.groundKey) {
      if (this.ground) {
        this.scene.remove(this.ground);
        disposeAll(this.ground);
      }
      this.ground = motion.track.drawn ? pathGround(motion.track, motion.ground) : groundMesh(motion.ground);
      this.scene.add(this.ground);
      this.groundKey = key;
    }
  }

  render(t) {
    if (!this.motion) return;
    const now = performance.now();
    if (this.software && now - this.lastDrawn < 50) return;
    this.lastDrawn = now;
    // On a drawn path the compared character walks it too, not beside it.
    const offset = this.motion.track.drawn ? 0 : COMPARE_OFFSET;
    this.figure.place(this.motion, t, 0);
    this.ghost.visible = !!this.compare;
    if (this.compare) this.ghost.place(this.compare, t, offset);
    this.shadows[1].visible = !!this.compare;
    [[this.figure, this.motion], [this.ghost, this.compare]].forEach(([figure, motion], i) => {
      if (!motion) return;
      const hips = figure.hips(motion);
      this.shadows[i].position.set(hips.x, heightAt(motion.ground, figure.pose.pelvis.x) + 0.004, hips.z);
      // Long along the way it walks (the disc lies flat: its x stays x, its y is -z).
      this.shadows[i].rotation.z = Math.atan2(hips.z - figure.ahead.z - figure.offsetZ, figure.ahead.x - hips.x);
    });
    // Follow the pelvis: the target moves with it and the camera keeps its offset to it.
    const p = this.figure.pose.pelvis;
    const hips = this.figure.hips(this.motion);
    const target = new THREE.Vector3(hips.x, p.y * 0.85, hips.z + (this.compare ? offset / 2 : 0));
    const delta = target.clone().sub(this.controls.target);
    this.camera.position.add(delta);
    this.controls.target.copy(target);
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }
}
