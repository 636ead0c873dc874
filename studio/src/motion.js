// A walk's frames as the server sends them (apps/studio/src/walk_view.cpp): per frame the time,
// the pelvis (x, y metres, tilt degrees; x is the distance along the path), both legs' six points
// (hip, knee, ankle, heel, ball, toe tip; x, y metres; left then right), contacts and joint
// angles, the whole body's joints (x along the start of the walk, y up, z to the left: the
// library's z, y, x) and the path they walk. The views sample it at any time.

export const POINTS = ['hip', 'knee', 'ankle', 'heel', 'ball', 'tip'];

export class Motion {
  constructor(walk) {
    const f = walk.frames;
    this.count = f.count;
    this.time = f.time;
    this.pelvisData = f.pelvis;
    this.legData = f.legs;
    this.contactData = f.contact;
    this.duration = this.time[this.count - 1];
    this.segments = walk.segments;
    const s = walk.segments;
    // The stature the legs stand for (leg length is 0.530 of it: Winter 2009, as the rig's).
    this.stature = (s.thigh + s.shank + s.ankle_height) / 0.530;
    this.ground = walk.ground;
    this.track = new Track(walk.path);
    // The body (body::PathFollower's poses, at walk.body.fps): its joints by name, x, y, z each a
    // frame, in metres from the millimetres' changes the server sends (a running sum).
    this.joints = new Map(walk.body.joints.map((name, i) => [name, i]));
    this.bodyFps = walk.body.fps;
    this.bodyCount = walk.body.count;
    const changes = walk.body.changes;
    const stride = this.joints.size * 3;
    const mm = new Float64Array(changes.length);
    for (let k = 0; k < changes.length; k++) mm[k] = (k < stride ? 0 : mm[k - stride]) + changes[k];
    this.bodyData = mm.map((v) => v / 1000);
    // The left foot's strikes (its contact beginning, 0.35 s at least after the last, as the
    // measuring's): they part the gait cycles the curves are drawn over.
    this.strikes = [];
    for (let i = 1; i < this.count; i++) {
      const begins = this.contactData[i * 2] === 1 && this.contactData[(i - 1) * 2] === 0;
      if (begins && (this.strikes.length === 0 || this.time[i] - this.strikes.at(-1) >= 0.35)) {
        this.strikes.push(this.time[i]);
      }
    }
  }

  // Where in its gait cycle the left leg is at time t, in percent (0 at its strike), or null
  // before the first strike and after the last.
  cyclePercent(t) {
    const s = this.strikes;
    for (let k = 0; k + 1 < s.length; k++) {
      if (t >= s[k] && t < s[k + 1]) return (100 * (t - s[k])) / (s[k + 1] - s[k]);
    }
    return null;
  }

  // The frame index at or before time t (s, within the walk) and the fraction to the next.
  locate(t) {
    const time = this.time;
    if (t <= 0 || this.count < 2) return [0, 0];
    if (t >= this.duration) return [this.count - 1, 0];
    // Frames are evenly spaced: start from the estimate and correct.
    let i = Math.min(this.count - 2, Math.floor(t / (this.duration / (this.count - 1))));
    while (i > 0 && time[i] > t) i--;
    while (i < this.count - 2 && time[i + 1] <= t) i++;
    const span = time[i + 1] - time[i];
    return [i, span > 0 ? (t - time[i]) / span : 0];
  }

  // The pose at time t, interpolated between frames, into `pose` (made when not given):
  // {pelvis: {x, y, tilt}, legs: [[{x, y} x 6], [..]], contact: [bool, bool]}.
  sample(t, pose = makePose()) {
    const [i, u] = this.locate(t);
    const j = Math.min(i + 1, this.count - 1);
    const mix = (data, stride, k) => data[i * stride + k] * (1 - u) + data[j * stride + k] * u;
    pose.pelvis.x = mix(this.pelvisData, 3, 0);
    pose.pelvis.y = mix(this.pelvisData, 3, 1);
    pose.pelvis.tilt = mix(this.pelvisData, 3, 2);
    for (let side = 0; side < 2; side++) {
      for (let p = 0; p < 6; p++) {
        const k = side * 12 + p * 2;
        pose.legs[side][p].x = mix(this.legData, 24, k);
        pose.legs[side][p].y = mix(this.legData, 24, k + 1);
      }
      pose.contact[side] = this.contactData[(u < 0.5 ? i : j) * 2 + side] === 1;
    }
    return pose;
  }

  // The body's joints at time t, interpolated between frames, into `points` ({x, y, z} for each
  // of this.joints, made when not given), moved `offsetZ` across.
  sampleBody(t, offsetZ = 0, points = [...this.joints.keys()].map(() => ({ x: 0, y: 0, z: 0 }))) {
    const last = this.bodyCount - 1;
    const at = Math.min(Math.max(t * this.bodyFps, 0), last);
    const i = Math.min(Math.floor(at), Math.max(last - 1, 0));
    const j = Math.min(i + 1, last);
    const u = at - i;
    const stride = this.joints.size * 3;
    const data = this.bodyData;
    points.forEach((point, k) => {
      const a = i * stride + k * 3;
      const b = j * stride + k * 3;
      point.x = data[a] * (1 - u) + data[b] * u;
      point.y = data[a + 1] * (1 - u) + data[b + 1] * u;
      point.z = data[a + 2] * (1 - u) + data[b + 2] * u + offsetZ;
    });
    return points;
  }
}

// The path the body walks in the body's axes (x the library's z, z its x): the server's samples of
// path::Path every `spacing` metres from its start to its end, or straight ahead along x when no
// path is drawn (path null). Before the start and past the end it goes straight on, as
// path::Path does.
export class Track {
  constructor(path) {
    this.path = path || null;
    this.drawn = Boolean(path);
    if (!path) return;
    const n = path.samples.length / 2;
    this.x = new Float64Array(n);
    this.z = new Float64Array(n);
    for (let k = 0; k < n; k++) {
      this.x[k] = path.samples[2 * k + 1];
      this.z[k] = path.samples[2 * k];
    }
    this.spacing = path.spacing;
    this.length = path.length;
  }

  // The point `s` metres along and the unit direction there, into `out`.
  at(s, out = { x: 0, z: 0, dx: 1, dz: 0 }) {
    if (!this.drawn || this.x.length < 2) {
      out.x = s;
      out.z = 0;
      out.dx = 1;
      out.dz = 0;
      return out;
    }
    const last = this.x.length - 1;
    const i = Math.min(Math.max(Math.floor(s / this.spacing), 0), last - 1);
    const from = i * this.spacing;
    const to = Math.min((i + 1) * this.spacing, this.length);
    const ex = this.x[i + 1] - this.x[i];
    const ez = this.z[i + 1] - this.z[i];
    const chord = Math.hypot(ex, ez) || 1;
    out.dx = ex / chord;
    out.dz = ez / chord;
    const along = s <= 0 ? s : s >= this.length ? s - this.length : 0;
    const base = s <= 0 ? 0 : s >= this.length ? last : -1;
    if (base >= 0) {
      out.x = this.x[base] + out.dx * along;
      out.z = this.z[base] + out.dz * along;
    } else {
      const u = to > from ? (s - from) / (to - from) : 0;
      out.x = this.x[i] + ex * u;
      out.z = this.z[i] + ez * u;
    }
    return out;
  }
}

// A ground point [x, z] as the API has it (the library's axes) in the body's axes, and back.
export const bodyOf = ([x, z]) => ({ x: z, z: x });
export const apiOf = ({ x, z }) => [z, x];

export function makePose() {
  const leg = () => POINTS.map(() => ({ x: 0, y: 0 }));
  return { pelvis: { x: 0, y: 0, tilt: 0 }, legs: [leg(), leg()], contact: [false, false] };
}

// The clock both views play by: real time scaled by `speed`, looping over the walk.
export class Clock {
  constructor() {
    this.speed = 1;
    this.playing = true;
    this.t = 0;
    this.last = performance.now();
  }
  tick(duration) {
    const now = performance.now();
    if (this.playing) this.t += ((now - this.last) / 1000) * this.speed;
    this.last = now;
    if (duration > 0) this.t %= duration;
    return this.t;
  }
}

// The ground's height at x, from its profile ([[x, y], ...], x increasing; a riser is two points
// close together); level beyond the ends.
export function heightAt(ground, x) {
  if (x <= ground[0][0]) return ground[0][1];
  for (let i = 0; i + 1 < ground.length; i++) {
    const [x0, y0] = ground[i];
    const [x1, y1] = ground[i + 1];
    if (x <= x1) return x1 > x0 ? y0 + ((y1 - y0) * (x - x0)) / (x1 - x0) : y1;
  }
  return ground[ground.length - 1][1];
}
