// The path panel: the ground seen from above, on which the animator draws the path the whole body
// walks. Draw, then click points (each click from the second walks the body along the path so
// far); Done ends the drawing; Straight walks straight ahead again. The corner radius rounds the
// corners (path::Path::polyline); the server refuses a radius or a corner it cannot round, and the
// panel says why under its fields and keeps the path the server has. On the map: a grid a metre a
// square, the points clicked, the path as the server rounded it, the hips' track and where the
// body is now. Its axes are the 3D view's seen from above: x (the walk's start) to the right, z
// (the body's left) down.
import { apiOf, bodyOf } from './motion.js';

const SPAN = [-2, 22]; // metres of x shown; z from -12 to 12
const SIZE = 216; // pixels a side
const HINT = 'Click points on the map, in order (Esc or Done to stop).';
const SNAP = 0.25; // metres: a click is rounded to it (2.25 pixels)

export class PathPanel {
  // `send(change, refused)`: POST the change of settings ({path, corner_radius}); `refused(message)`
  // is called with the server's reason when it refuses.
  constructor(container, send) {
    this.send = send;
    this.drawing = false;
    this.points = []; // the points drawn, body axes {x, z}
    this.motion = null;
    this.details = document.createElement('details');
    this.details.className = 'path-panel';
    this.summary = document.createElement('summary');
    this.details.append(this.summary);
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'path-map';
    const ratio = window.devicePixelRatio || 1;
    this.canvas.width = SIZE * ratio;
    this.canvas.height = SIZE * ratio;
    this.canvas.style.width = `${SIZE}px`;
    this.canvas.style.height = `${SIZE}px`;
    this.ctx = this.canvas.getContext('2d');
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    const tools = document.createElement('div');
    tools.className = 'path-tools';
    this.drawButton = button('Draw', 'path-draw', 'Click points on the map: the body walks them in order');
    this.straightButton = button('Straight', 'path-straight', 'Walk straight ahead again');
    const label = document.createElement('label');
    label.textContent = 'corners (m) ';
    this.radius = document.createElement('input');
    Object.assign(this.radius, { type: 'number', step: '0.1', className: 'path-radius', value: '1' });
    this.radius.title = 'The radius the corners are rounded to (at least 0.5 m)';
    label.append(this.radius);
    tools.append(this.drawButton, this.straightButton, label);
    this.error = document.createElement('div');
    this.error.className = 'path-error';
    this.details.append(this.canvas, tools, this.error);
    container.append(this.details);
    this.details.addEventListener('toggle', () => this.draw());

    this.drawButton.addEventListener('click', () => {
      if (this.drawing) {
        this.setDrawing(false);
        return;
      }
      this.points = [];
      this.setDrawing(true);
      this.draw();
    });
    this.straightButton.addEventListener('click', () => {
      this.setDrawing(false);
      this.points = [];
      this.submit({ path: null });
    });
    this.radius.addEventListener('change', () => {
      const value = Number(this.radius.value);
      if (this.radius.value.trim() === '' || !Number.isFinite(value)) {
        this.radius.value = String(this.settings.corner_radius);
        return;
      }
      this.submit({ corner_radius: value });
    });
    this.canvas.addEventListener('click', (event) => {
      if (!this.drawing) return;
      const box = this.canvas.getBoundingClientRect();
      const point = this.pointAt(event.clientX - box.left, event.clientY - box.top);
      const last = this.points.at(-1);
      if (last && Math.hypot(last.x - point.x, last.z - point.z) < 0.1) return;
      this.points.push(point);
      this.draw();
      if (this.points.length >= 2) this.submit({ path: this.points.map(apiOf) });
    });
    document.addEventListener('keydown', (event) => {
      if (event.key === 'Escape' && this.drawing) this.setDrawing(false);
    });
  }

  // The map's pixel (from its top left) of a point in the body's axes, and back (snapped).
  pixelOf({ x, z }) {
    const scale = SIZE / (SPAN[1] - SPAN[0]);
    return { u: (x - SPAN[0]) * scale, v: SIZE / 2 + z * scale };
  }
  pointAt(u, v) {
    const scale = SIZE / (SPAN[1] - SPAN[0]);
    const snap = (m) => Number((Math.round(m / SNAP) * SNAP).toFixed(2));
    return { x: snap(SPAN[0] + u / scale), z: snap((v - SIZE / 2) / scale) };
  }

  setDrawing(on) {
    this.drawing = on;
    this.drawButton.textContent = on ? 'Done' : 'Draw';
    this.canvas.classList.toggle('drawing', on);
    this.say(on ? HINT : '', 'hint');
  }

  submit(change) {
    this.say(this.drawing ? HINT : '', 'hint');
    this.send(change, (message) => {
      // Drawing, the point refused goes; the radius and the rest are the server's.
      if (this.drawing && change.path) this.points.pop();
      this.show(this.settings, this.motion);
      this.radius.value = String(this.settings.corner_radius);
      this.say(message, 'error');
    });
  }

  say(text, kind = 'error') {
    this.error.textContent = text;
    this.error.className = `path-error ${kind}`;
  }

  // The server's settings (path, corner_radius) and the walk's motion, shown.
  show(settings, motion) {
    this.settings = settings;
    this.motion = motion;
    const points = settings.path ? settings.path.map(bodyOf) : [];
    // While drawing, the points are the page's (the server has them all but the first alone).
    if (!this.drawing) this.points = points;
    if (document.activeElement !== this.radius) this.radius.value = String(settings.corner_radius);
    const path = motion && motion.track.path;
    this.summary.textContent = path
      ? `Path: ${points.length} points, ${path.length.toFixed(1)} m, corners ${settings.corner_radius} m`
      : 'Path: straight ahead (draw one)';
    this.draw();
  }

  // The map, with the body where it is at time t (drawn only while the panel is open).
  draw(t = null) {
    if (!this.details.open) return;
    const ctx = this.ctx;
    ctx.clearRect(0, 0, SIZE, SIZE);
    ctx.fillStyle = '#f3f6f1';
    ctx.fillRect(0, 0, SIZE, SIZE);
    const scale = SIZE / (SPAN[1] - SPAN[0]);
    for (let m = Math.ceil(SPAN[0]); m <= SPAN[1]; m++) {
      ctx.strokeStyle = m % 5 === 0 ? '#c4ccbd' : '#e1e6dc';
      ctx.lineWidth = 1;
      const u = (m - SPAN[0]) * scale;
      line(ctx, [[u, 0], [u, SIZE]]);
      const v = SIZE / 2 + (m - (SPAN[0] + SPAN[1]) / 2) * scale;
      line(ctx, [[0, v], [SIZE, v]]);
    }
    const motion = this.motion;
    const track = motion && motion.track;
    // The path as the server rounded it, or the straight way ahead.
    ctx.strokeStyle = '#d9822b';
    ctx.lineWidth = 2.5;
    if (track && track.drawn) {
      const pixels = [];
      for (let k = 0; k < track.x.length; k++) {
        const p = this.pixelOf({ x: track.x[k], z: track.z[k] });
        pixels.push([p.u, p.v]);
      }
      line(ctx, pixels);
    } else {
      const from = this.pixelOf({ x: 0, z: 0 });
      line(ctx, [[from.u, from.v], [SIZE, from.v]]);
    }
    // The points clicked, joined as clicked.
    ctx.strokeStyle = 'rgba(31, 59, 99, 0.45)';
    ctx.lineWidth = 1;
    ctx.setLineDash([3, 3]);
    line(ctx, this.points.map((p) => {
      const q = this.pixelOf(p);
      return [q.u, q.v];
    }));
    ctx.setLineDash([]);
    this.points.forEach((p, i) => {
      const q = this.pixelOf(p);
      ctx.fillStyle = i === 0 ? '#2e8a55' : '#1f3b63';
      ctx.beginPath();
      ctx.arc(q.u, q.v, 3.5, 0, 2 * Math.PI);
      ctx.fill();
    });
    // The hips' track over the walk and the body now.
    if (motion) {
      const hips = motion.joints.get('hips');
      const stride = motion.joints.size * 3;
      ctx.fillStyle = 'rgba(47, 109, 181, 0.35)';
      for (let f = 0; f < motion.bodyCount; f += 2) {
        const q = this.pixelOf({ x: motion.bodyData[f * stride + hips * 3], z: motion.bodyData[f * stride + hips * 3 + 2] });
        ctx.fillRect(q.u - 0.75, q.v - 0.75, 1.5, 1.5);
      }
      if (t !== null) {
        const body = motion.sampleBody(t);
        const q = this.pixelOf(body[hips]);
        ctx.fillStyle = '#2f6db5';
        ctx.beginPath();
        ctx.arc(q.u, q.v, 4.5, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
  }
}

function button(text, className, title) {
  const b = document.createElement('button');
  b.type = 'button';
  b.textContent = text;
  b.className = className;
  b.title = title;
  return b;
}

function line(ctx, pixels) {
  if (pixels.length < 2) return;
  ctx.beginPath();
  ctx.moveTo(...pixels[0]);
  for (const p of pixels.slice(1)) ctx.lineTo(...p);
  ctx.stroke();
}
