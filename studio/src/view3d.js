// The character walking in 3D (three.js): a low-poly body placed on the joints of the walk's
// whole body (body::PathFollower's poses on a straight path: the legs, the pelvis turning, rolling
// and swaying, the trunk and the arms swinging as the set's upper body controllers answer), the
// ground as a tiled strip, a camera that follows the pelvis and orbits with the mouse. A second,
// translucent character walks beside it when a set is compared.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { heightAt, makePose } from './motion.js';

const GROUND_WIDTH = 2.6; // metres across the walk
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
    // The head looks along the straight path, +x.
    this.nose.position.set(this.head.position.x + 0.06 * H, this.head.position.y - 0.005 * H, this.head.position.z);
  }

  set visible(v) {
    this.group.visible = v;
  }
}

function groundMesh(points) {
  const positions = [];
  const colors = [];
  const light = new THREE.Color(0xcfd6c8);
  const dark = new THREE.Color(0xa9b5a0);
  const riser = new THREE.Color(0x8c9886);
  const side = new THREE.Color(0x7c8777);
  const half = GROUND_WIDTH / 2;
  const quad = (a, b, c, d, color) => {
    for (const v of [a, b, c, a, c, d]) {
      positions.push(v[0], v[1], v[2]);
      colors.push(color.r, color.g, color.b);
    }
  };
  let bottom = Infinity;
  for (const [, y] of points) bottom = Math.min(bottom, y);
  bottom -= 0.4;
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
        const color = steep ? riser : (column + row) % 2 === 0 ? light : dark;
        quad([xa, ya, z + TILE], [xb, yb, z + TILE], [xb, yb, z], [xa, ya, z], color);
      }
      // The near side face, down to below the lowest ground: stairs read as solid.
      quad([xa, bottom, half], [xb, bottom, half], [xb, yb, half], [xa, ya, half], side);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  geometry.computeVertexNormals();
  return new THREE.Mesh(
    geometry,
    new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }),
  );
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
    const key = JSON.stringify(motion.ground);
    if (key !== this.groundKey) {
      if (this.ground) {
        this.scene.remove(this.ground);
        this.ground.geometry.dispose();
      }
      this.ground = groundMesh(motion.ground);
      this.scene.add(this.ground);
      this.groundKey = key;
    }
  }

  render(t) {
    if (!this.motion) return;
    const now = performance.now();
    if (this.software && now - this.lastDrawn < 50) return;
    this.lastDrawn = now;
    this.figure.place(this.motion, t, 0);
    this.ghost.visible = !!this.compare;
    if (this.compare) this.ghost.place(this.compare, t, COMPARE_OFFSET);
    this.shadows[1].visible = !!this.compare;
    [[this.figure, 0], [this.ghost, COMPARE_OFFSET]].forEach(([figure, z], i) => {
      const x = figure.pose.pelvis.x;
      this.shadows[i].position.set(x, heightAt(this.motion.ground, x) + 0.004, z);
    });
    // Follow the pelvis: the target moves with it and the camera keeps its offset to it.
    const p = this.figure.pose.pelvis;
    const target = new THREE.Vector3(p.x, p.y * 0.85, this.compare ? COMPARE_OFFSET / 2 : 0);
    const delta = target.clone().sub(this.controls.target);
    this.camera.position.add(delta);
    this.controls.target.copy(target);
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }
}
