// The side view: the sagittal plane the rig lives in, drawn on a canvas as an animator's chart.
// The near (left) leg dark, the far (right) leg light, a foot in contact marked, the ground in
// section, and the left ankle's path over the last second with a dot every 1/30 s: its spacing
// is the walk's timing. A compared set walks as a dashed orange outline.
import { heightAt, makePose } from './motion.js';

const NEAR = '#1f3b63';
const FAR = '#8ea4c4';
const CONTACT = '#2e9e5b';
const GHOST = '#e8892b';
const GROUND = '#c9d1c2';
const GROUND_EDGE = '#6f7c69';

export class SideView {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.motion = null;
    this.compare = null;
    this.pose = makePose();
    this.ghostPose = makePose();
    this.trailPose = makePose();
    this.centre = null;
    this.scale = 1;
    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
    this.resize();
  }

  resize() {
    const parent = this.canvas.parentElement;
    const ratio = window.devicePixelRatio || 1;
    this.width = parent.clientWidth;
    this.height = parent.clientHeight;
    this.canvas.width = Math.max(1, Math.round(this.width * ratio));
    this.canvas.height = Math.max(1, Math.round(this.height * ratio));
    this.canvas.style.width = `${this.width}px`;
    this.canvas.style.height = `${this.height}px`;
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  }

  setWalks(motion, compare) {
    this.motion = motion;
    this.compare = compare;
  }

  render(t) {
    const m = this.motion;
    if (!m || this.width === 0) return;
    const ctx = this.ctx;
    const pose = m.sample(t, this.pose);
    const H = m.stature;
    // Metres to pixels: the body and a stride either side fit.
    const scale = Math.min(this.height / (1.25 * H), this.width / 4.2);
    this.scale = scale;
    // The view follows the pelvis, smoothly in height (stairs lift it a tread at a time).
    const targetY = pose.pelvis.y - 0.05 * H;
    if (!this.centre || Math.abs(this.centre.x - pose.pelvis.x) > 2) {
      this.centre = { x: pose.pelvis.x, y: targetY };
    }
    this.centre.x = pose.pelvis.x;
    this.centre.y += (targetY - this.centre.y) * 0.08;
    const cx = this.width / 2;
    const cy = this.height * 0.5;
    const X = (x) => cx + (x - this.centre.x) * scale;
    const Y = (y) => cy - (y - this.centre.y) * scale;

    ctx.clearRect(0, 0, this.width, this.height);
    this.drawGround(ctx, m.ground, X, Y, scale);
    this.drawTrail(ctx, m, t, X, Y);
    if (this.compare) {
      const ghost = this.compare.sample(t, this.ghostPose);
      this.drawBody(ctx, ghost, H, X, Y, scale, true);
    }
    this.drawBody(ctx, pose, H, X, Y, scale, false);
    ctx.fillStyle = '#55606e';
    ctx.font = '12px system-ui, sans-serif';
    ctx.fillText(`t ${t.toFixed(2)} s`, 10, 18);
    this.drawLegend(ctx);
  }

  drawGround(ctx, ground, X, Y, scale) {
    if (!ground || ground.length < 2) return;
    ctx.beginPath();
    ctx.moveTo(X(ground[0][0]), this.height + 10);
    for (const [x, y] of ground) ctx.lineTo(X(x), Y(y));
    ctx.lineTo(X(ground[ground.length - 1][0]), this.height + 10);
    ctx.closePath();
    ctx.fillStyle = GROUND;
    ctx.fill();
    ctx.beginPath();
    for (let i = 0; i < ground.length; i++) {
      const [x, y] = ground[i];
      if (i === 0) ctx.moveTo(X(x), Y(y));
      else ctx.lineTo(X(x), Y(y));
    }
    ctx.strokeStyle = GROUND_EDGE;
    ctx.lineWidth = 1.5;
    ctx.stroke();
    // Ticks every 0.25 m: the ground passing under the feet.
    const left = this.centre.x - this.width / 2 / scale;
    const right = this.centre.x + this.width / 2 / scale;
    ctx.fillStyle = GROUND_EDGE;
    for (let x = Math.ceil(left / 0.25) * 0.25; x < right; x += 0.25) {
      const y = heightAt(ground, x);
      ctx.fillRect(X(x) - 0.5, Y(y) + 2, 1, Math.abs(x % 1) < 1e-6 ? 9 : 5);
    }
  }

  drawLegend(ctx) {
    const items = [[NEAR, 'left leg (near)'], [FAR, 'right leg'], [CONTACT, 'foot on the ground'],
      [NEAR, '• left ankle, a dot each 1/30 s']];
    if (this.compare) items.push([GHOST, 'compared set']);
    items.push(['#8a94a3', '· drag: scrub, double-click: play']);
    ctx.font = '11px system-ui, sans-serif';
    const widest = Math.max(...items.map(([, text]) => ctx.measureText(text).width + 22));
    const x = this.width - widest - 10;
    let y = 18;
    for (const [colour, text] of items) {
      if (text.startsWith('•') || text.startsWith('·')) {
        ctx.fillStyle = colour;
        ctx.fillText(text, x, y);
      } else {
        ctx.fillStyle = colour;
        ctx.fillRect(x, y - 5, 16, 3);
        ctx.fillStyle = '#55606e';
        ctx.fillText(text, x + 22, y);
      }
      y += 15;
    }
  }

  // The left ankle over the second before t, a dot a frame at 30 frames a second.
  drawTrail(ctx, m, t, X, Y) {
    const p = this.trailPose;
    ctx.fillStyle = NEAR;
    for (let k = 30; k >= 1; k--) {
      const s = t - k / 30;
      if (s < 0) continue;
      m.sample(s, p);
      ctx.globalAlpha = 0.15 + 0.6 * (1 - k / 30);
      ctx.beginPath();
      ctx.arc(X(p.legs[0][2].x), Y(p.legs[0][2].y), 2, 0, Math.PI * 2);
      ctx.fill();
    }
    ctx.globalAlpha = 1;
  }

  drawBody(ctx, pose, H, X, Y, scale, ghost) {
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    ctx.setLineDash(ghost ? [6, 5] : []);
    const line = (points, colour, width) => {
      ctx.beginPath();
      points.forEach((q, i) => (i === 0 ? ctx.moveTo(X(q.x), Y(q.y)) : ctx.lineTo(X(q.x), Y(q.y))));
      ctx.strokeStyle = colour;
      ctx.lineWidth = width;
      ctx.stroke();
    };
    const w = Math.max(2, 0.035 * H * scale);
    // The far leg first, so the near one is drawn over it.
    for (const side of [1, 0]) {
      const [hip, knee, ankle, heel, ball, tip] = pose.legs[side];
      const colour = ghost ? GHOST : side === 0 ? NEAR : FAR;
      line([hip, knee, ankle], colour, w);
      line([ankle, heel, ball, tip, ball, ankle], pose.contact[side] && !ghost ? CONTACT : colour,
        w * 0.55);
    }
    const p = pose.pelvis;
    const shoulder = { x: p.x, y: p.y + 0.29 * H };
    line([{ x: p.x, y: p.y }, shoulder], ghost ? GHOST : NEAR, w * 1.4);
    ctx.beginPath();
    ctx.arc(X(p.x), Y(p.y + 0.405 * H), 0.062 * H * scale, 0, Math.PI * 2);
    ctx.strokeStyle = ghost ? GHOST : NEAR;
    ctx.lineWidth = 2;
    ctx.stroke();
    ctx.setLineDash([]);
  }
}
