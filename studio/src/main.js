// The studio's page: builds the views from the server's state and walk, sends each edit as it is
// made and redraws the curves, the figures and the character from the answer. docs/studio.md.
import GUI from 'lil-gui';
import * as api from './api.js';
import { Clock, Motion } from './motion.js';
import { View3D } from './view3d.js';
import { SideView } from './sideview.js';
import { Curves, renderFigures } from './curves.js';
import { ControllerPanel, sayWhenClamped } from './controllers.js';
import { PathPanel } from './pathpanel.js';

// What the page holds, and what the browser test reads: the latencies of edits from the input
// event to the frame that shows their walk, the requests in flight, the errors shown.
const studio = {
  state: null,
  walk: null,
  compare: null, // {id, label, walk, set}
  latencies: [],
  errors: [],
  redraws: 0,
  ready: false,
  away: false, // the server does not answer: the page retries and shows a notice
  reconnects: 0, // times it came back, after which the page showed the server's state again
};
window.studio = studio;
// Stops the playback at t seconds (the browser test compares pictures at one instant); `play`
// starts it again.
studio.seek = (t) => {
  clock.playing = false;
  clock.t = t;
};
studio.play = () => {
  clock.playing = true;
};

const $ = (selector) => document.querySelector(selector);
const clock = new Clock();
let view3d;
let side;
let curves;
let panel;
let pathPanel;
let settingsGui;
let motion = null;
let compareMotion = null;

// ---- requests: one at a time, in order; a newer value of the same gesture replaces one waiting -

let busy = false;
const queue = []; // {path, body, apply, startedAt, key, refused}
const idleWaiters = [];

// Resolves when no request is in flight or waiting (the browser test awaits it).
studio.idle = () => new Promise((resolve) => {
  if (!busy && queue.length === 0) resolve();
  else idleWaiters.push(resolve);
});

let requestCount = 0;
// `key` says which waiting request this one may replace: the same drag's edits, settings (merged).
// `refused(error)`, when given, may handle a refusal (returning true) instead of showing it.
function request(path, body, apply, startedAt = performance.now(), key = `${path}#${++requestCount}`,
  refused = null) {
  const last = queue[queue.length - 1];
  if (last && last.key === key) {
    last.body = path === '/api/settings' ? { ...last.body, ...body } : body;
    last.startedAt = startedAt;
    return;
  }
  queue.push({ path, body, apply, startedAt, key, refused });
  if (!busy) next();
}

async function next() {
  const item = queue.shift();
  if (!item) {
    while (idleWaiters.length) idleWaiters.shift()();
    return;
  }
  busy = true;
  const sent = performance.now();
  let reconnected = false;
  let refusedEdit = false;
  try {
    const { result: answer, retried } = await untilAnswered(() => api.post(item.path, item.body));
    reconnected = retried;
    const received = performance.now();
    item.apply(answer);
    const applied = performance.now();
    if (item.path === '/api/edit' && !retried) {
      requestAnimationFrame(() => {
        studio.latencies.push({
          total: performance.now() - item.startedAt,
          server: answer.serverMs,
          request: received - sent,
          apply: applied - received,
          cycles: studio.state.settings.cycles,
        });
      });
    }
  } catch (error) {
    reconnected = Boolean(error.retried);
    refusedEdit = item.path === '/api/edit';
    if (!(item.refused && error instanceof api.RequestError && item.refused(error))) showError(error);
  }
  // Back from an absence the server may be another one (restarted): the page shows its state
  // whole. After a refused edit, the controllers as the server has them.
  try {
    if (reconnected) await reload();
    else if (refusedEdit) await resync();
  } catch (error) {
    showError(error);
  }
  busy = false;
  next();
}

// ---- the server away: retry until it answers, then show its state ------------------------------

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// Calls `call` (a request) until the server answers it: a refusal is an answer (it throws, as
// always), a failure to reach the server is not, nor a 503 (the server serving as many
// connections as it can refused the request unread, so nothing was done): the page shows that the server is away and tries again, 0.25 s later
// at first, then every 2 s. `retried` says whether it was away.
async function untilAnswered(call) {
  for (let attempt = 0; ; attempt++) {
    try {
      const result = await call();
      if (attempt > 0) back();
      return { result, retried: attempt > 0 };
    } catch (error) {
      if (error instanceof api.RequestError && error.status !== 503) {
        if (attempt > 0) back();
        error.retried = attempt > 0;
        throw error;
      }
      away();
      await sleep(Math.min(250 * 2 ** attempt, 2000));
    }
  }
}

function away() {
  if (studio.away) return;
  studio.away = true;
  studio.awaySeen = (studio.awaySeen || 0) + 1;
  const notice = $('#connection');
  notice.textContent = 'The server is away: reconnecting…';
  notice.className = 'visible';
}

function back() {
  if (!studio.away) return;
  studio.away = false;
  studio.reconnects++;
  $('#connection').className = '';
}

let messageTimer = 0;
function showMessage(text, kind = 'info') {
  const box = $('#message');
  box.textContent = text;
  box.className = `visible ${kind}`;
  clearTimeout(messageTimer);
  messageTimer = setTimeout(() => (box.className = ''), kind === 'error' ? 7000 : 3500);
}

function showError(error) {
  const text = error.field ? `${error.field}: ${error.message}` : error.message;
  studio.errors.push(text);
  showMessage(text, 'error');
}

// After a refused edit, the page shows the server's set again.
async function resync() {
  const { result: state, retried } = await untilAnswered(() => api.get('/api/state'));
  if (retried) {
    await reload();
    return;
  }
  studio.state = state;
  for (const c of state.set.controllers) panel.update(c);
  refreshParameters();
  updateHistory(state.history);
}

// The server's whole state and walk, shown anew (at start, and when the server is back).
async function reload() {
  const [{ result: state }, { result: walk }] = await Promise.all([
    untilAnswered(() => api.get('/api/state')), untilAnswered(() => api.get('/api/walk'))]);
  show(state, walk);
  if (studio.ready) showMessage('Reconnected: the page shows the server’s set as it has it');
}

function show(state, walk) {
  studio.state = state;
  studio.compare = walk.compare || null;
  curves.setReference(state.reference);
  updateHistory(state.history);
  renderSet();
  buildSettings();
  buildCompareChoices();
  setWalk(walk.walk, walk.compare);
}

// ---- applying answers ------------------------------------------------------------------------

function setWalk(walk, compare) {
  studio.walk = walk;
  motion = new Motion(walk);
  if (compare !== undefined) {
    studio.compare = compare ? { ...studio.compare, ...compare } : null;
  }
  compareMotion = studio.compare && studio.compare.walk ? new Motion(studio.compare.walk) : null;
  view3d.setWalks(motion, compareMotion);
  side.setWalks(motion, compareMotion);
  pathPanel.show(studio.state.settings, motion);
  curves.update(walk, compareMotion ? studio.compare.walk : null);
  renderFigures($('#figures'), walk, compareMotion ? studio.compare.walk : null);
  studio.redraws++;
}

function updateHistory(history) {
  studio.state.history = history;
  $('#undo').disabled = history.undo === 0;
  $('#redo').disabled = history.redo === 0;
  $('#undo').title = history.undo ? `Undo: ${history.undo_label}` : 'Nothing to undo';
  $('#redo').title = history.redo ? `Redo: ${history.redo_label}` : 'Nothing to redo';
  $('#history-label').textContent = history.undo ? `last: ${history.undo_label}` : 'history';
  // The list: the start, then every step (those undone greyed); the set stands after `undo`.
  const steps = history.steps || [];
  const items = ['start: the set before these steps', ...steps].map((label, to) => {
    const li = document.createElement('li');
    li.dataset.to = to;
    li.className = to === history.undo ? 'current' : to > history.undo ? 'undone' : '';
    const button = document.createElement('button');
    button.type = 'button';
    button.textContent = to === 0 ? label : `${to}. ${label}`;
    button.title = label;
    button.addEventListener('click', () => {
      $('#history').open = false;
      if (to !== studio.state.history.undo) request('/api/history', { to }, applySet);
    });
    li.append(button);
    return li;
  });
  $('#history-steps').replaceChildren(...items);
  $('#unsaved').hidden = !history.unsaved;
}

function replaceController(controller) {
  const list = studio.state.set.controllers;
  const i = list.findIndex((c) => c.id === controller.id);
  if (i >= 0) list[i] = controller;
  panel.update(controller);
}

function applyEdit(answer) {
  if (answer.controller) replaceController(answer.controller);
  if (answer.parameters) {
    studio.state.set.parameters = answer.parameters;
    refreshParameters();
  }
  updateHistory(answer.history);
  setWalk(answer.walk);
}

// Open, undo and redo change the whole set.
function applySet(answer) {
  studio.state.set = answer.set;
  const openedBefore = studio.state.opened.id;
  if (answer.opened) studio.state.opened = answer.opened;
  // The set as opened changed (an open, or its undo): a comparison with it draws its terms anew.
  if (studio.compare && studio.compare.id === 'opened' && studio.state.opened.id !== openedBefore) {
    compareWith('opened');
  }
  if (answer.settings) studio.state.settings = answer.settings;
  updateHistory(answer.history);
  renderSet();
  setWalk(answer.walk, answer.compare === undefined ? undefined : answer.compare);
  buildSettings();
}

function renderSet() {
  const set = studio.state.set;
  const opened = studio.state.opened.label;
  $('#set-name').textContent = opened.startsWith(set.name) ? opened : `${set.name}: ${opened}`;
  $('#set-description').textContent = set.description;
  panel.render(set, studio.compare && studio.compare.set ? studio.compare.set : null);
}

// ---- edits -----------------------------------------------------------------------------------

// A drag, a slide: one gesture, one step of the history. Its edits go out as the value moves; its
// end sends the last value unless it went out already.
let gestureCount = 0;
const gestures = new Map(); // key -> {id, sent}
function editInGesture(key, body, value, phase, startedAt) {
  if (!gestures.has(key)) gestures.set(key, { id: `g${++gestureCount}`, sent: undefined });
  const g = gestures.get(key);
  if (phase === 'end') gestures.delete(key);
  if (value === g.sent) return;
  g.sent = value;
  request('/api/edit', { ...body, value, gesture: g.id }, applyEdit, startedAt, g.id);
}

function onKnot(controller, variable, knot, value, phase, event) {
  editInGesture(`${controller}/${variable}/${knot}`, { controller, variable, knot }, value, phase,
    event ? event.timeStamp : performance.now());
}

function onWord(controller, variable, term, value, phase) {
  editInGesture(`${controller}/${variable}/${term}`, { controller, variable, term }, value, phase,
    performance.now());
}

// A knot's value typed: one step of the history; a refusal (past a neighbour) is shown beside the
// fields through `refused`, and the page shows the server's controllers again.
function onKnotTyped(controller, variable, knot, value, refused) {
  request('/api/edit', { controller, variable, knot, value }, applyEdit, performance.now(), undefined,
    (error) => {
      refused(error.message);
      showError(error);
      return true;
    });
}

// What keeps rules from being sent: more of them, a longer one or a larger request than the server
// reads (state's rule_limits: Limits::kMostRules, kLongestRule, kLargestRulesBody), said as the
// server would say it, or '' when they may go.
function rulesPastLimits(controller, rules) {
  const limits = studio.state && studio.state.rule_limits;
  if (!limits) return '';
  const bytes = (text) => new TextEncoder().encode(text).length;
  if (rules.length > limits.rules) {
    return `${rules.length} rules: a controller takes at most ${limits.rules}; nothing was sent`;
  }
  const long = rules.findIndex((rule) => bytes(rule) > limits.rule_bytes);
  if (long >= 0) {
    return `rule ${long + 1} is longer than ${limits.rule_bytes} bytes; nothing was sent`;
  }
  const size = bytes(JSON.stringify({ controller, rules }));
  if (size > limits.body_bytes) {
    return `the rules are ${size} bytes as sent, more than the server reads (${limits.body_bytes}); nothing was sent`;
  }
  return '';
}

// Rules typed in a controller's card: one step of the history; a refusal (a word the parser
// does not know) is shown under the text through `refused`, which keeps the text as typed.
function onRules(controller, rules, refused) {
  const tooMuch = rulesPastLimits(controller, rules);
  if (tooMuch) {
    refused(tooMuch);
    showMessage(tooMuch, 'error');
    return;
  }
  request('/api/rules', { controller, rules }, applyEdit, performance.now(), undefined, (error) => {
    refused(error.message);
    showError(error);
    return true;
  });
}

// A term added, removed or reshaped from an input's term tools (POST /api/term): one step of the
// history; a refusal (a rule reads the term, a shape the input cannot hold) is shown under the
// tools through `refused`.
function onTerm(controller, variable, change, refused) {
  request('/api/term', { controller, variable, ...change }, applyEdit, performance.now(), undefined, (error) => {
    refused(error.message);
    showError(error);
    return true;
  });
}

function onSetParameter(name, value, phase) {
  editInGesture(`set/${name}`, { set: name }, value, phase, performance.now());
}

function applySettings(answer) {
  studio.state.settings = answer.settings;
  if (answer.reference) {
    studio.state.reference = answer.reference;
    curves.setReference(answer.reference);
  }
  if (answer.compare_dropped) showMessage(answer.compare_dropped, 'error');
  setWalk(answer.walk, answer.compare);
  refreshSettings();
}

function changeSettings(change) {
  request('/api/settings', change, applySettings, performance.now(), 'settings');
}

// A path drawn, cleared or its corners' radius changed (POST /api/settings, as the other
// settings): a refusal (a corner too sharp, a radius under 0.5 m) is said under the path panel.
function changePath(change, refused) {
  request('/api/settings', change, applySettings, performance.now(), 'path', (error) => {
    refused(error.message);
    showError(error);
    return true;
  });
}

function open(id) {
  request('/api/open', { set: id }, (answer) => {
    applySet(answer);
    showMessage(`Opened ${answer.opened.label}`);
  });
}

function compareWith(id) {
  request('/api/compare', { with: id || null }, (answer) => {
    studio.compare = answer.compare;
    renderSet();
    setWalk(studio.walk, answer.compare);
  });
}

// ---- the settings panel (lil-gui) ------------------------------------------------------------

const settingsModel = {};
function buildSettings() {
  if (settingsGui) settingsGui.destroy();
  const state = studio.state;
  const s = state.settings;
  settingsGui = new GUI({ container: $('#settings'), title: 'Walk and set', width: 300 });
  Object.assign(settingsModel, {
    step: s.step,
    bySpeed: s.speed > 0,
    walkSpeed: s.speed > 0 ? s.speed : 1.3,
    stature: s.stature,
    terrain: s.terrain,
    cycles: s.cycles,
    reference: s.reference,
    speed: clock.speed,
    playing: clock.playing,
    set: state.opened.id,
    style: 'default',
  });
  const walk = settingsGui.addFolder('Walk');
  // lil-gui counts steps from the slider's minimum: a round minimum keeps the values round.
  const [low, high] = roundedInward(s.limits.step, 0.005);
  walk.add(settingsModel, 'step', low, high, 0.005).name('step length (m)')
    .onChange((v) => changeSettings({ step: v }));
  // Walking by speed, the set's stride gives the step and the cadence follows.
  if (s.limits.speed) {
    const [slow, fast] = roundedInward(s.limits.speed, 0.01);
    settingsModel.walkSpeed = Math.min(Math.max(settingsModel.walkSpeed, slow), fast);
    walk.add(settingsModel, 'bySpeed').name('walk at a speed')
      .onChange((v) => changeSettings(v ? { speed: settingsModel.walkSpeed } : { step: settingsModel.step }));
    walk.add(settingsModel, 'walkSpeed', slow, fast, 0.01).name('speed (m/s)')
      .onChange((v) => { settingsModel.bySpeed = true; changeSettings({ speed: v }); });
  }
  walk.add(settingsModel, 'stature', ...s.limits.stature, 0.01).name('stature (m)')
    .onChange((v) => changeSettings({ stature: v }));
  const terrains = Object.fromEntries(state.terrains.map((t) => [t.label, t.spec]));
  if (!Object.values(terrains).includes(s.terrain)) terrains[s.terrain] = s.terrain;
  walk.add(settingsModel, 'terrain', terrains).name('terrain')
    .onChange((v) => changeSettings({ terrain: v }));
  // Along a drawn path the walk goes to its end, whatever the cycles.
  walk.add(settingsModel, 'cycles', ...s.limits.cycles, 1).name('gait cycles')
    .onFinishChange((v) => changeSettings({ cycles: v })).disable(Boolean(s.path));
  walk.add(settingsModel, 'reference', state.references).name('people (reference)')
    .onChange((v) => changeSettings({ reference: v }));
  walk.add(settingsModel, 'speed', 0.1, 2, 0.05).name('playback speed')
    .onChange((v) => (clock.speed = v));
  walk.add(settingsModel, 'playing').name('play').onChange((v) => (clock.playing = v));

  const set = settingsGui.addFolder('Set');
  const sets = Object.fromEntries(state.sets.map((x) => [x.label, x.id]));
  if (!Object.values(sets).includes(state.opened.id)) sets[state.opened.label] = state.opened.id;
  set.add(settingsModel, 'set', sets).name('open').onChange((v) => open(v));
  const styles = state.sets.filter((x) => x.kind === 'style').map((x) => x.id.slice(6));
  set.add(settingsModel, 'style', styles).name('shipped style');
  set.add({ reset: () => open(`style:${settingsModel.style}`) }, 'reset').name('reset to the shipped style');
  parameterGui = set.addFolder('The set’s own numbers');
  buildParameters();
  parameterGui.close();
  for (const c of settingsGui.controllersRecursive()) {
    if (c._min !== undefined) sayWhenClamped(c, c._name, (text) => showMessage(text, 'error'));
  }
}

let parameterGui = null;
const parameterModel = {};
const PARAMETER_LABELS = {
  inertia_s: 'inertia (s)',
  pelvis_tilt_deg: 'pelvic tilt (deg)',
  swing_knee_reference_sweep_deg: 'knee reference sweep (deg)',
  shortest_step_leg_lengths: 'shortest step (leg lengths)',
  cadence_steps_per_min: 'cadence it is written for (steps/min)',
  acceleration_m_s2: 'acceleration (m/s²)',
  first_step_share: 'first step (share of a step)',
  first_step_s: 'first step swing (s)',
  start_tempo_share: 'starting tempo (share)',
  start_easing_s: 'start easing (s)',
  placed_step_lift_leg_lengths: 'first and closing step lift (leg lengths)',
  settle_rate_per_s: 'settling rate (1/s)',
};
function buildParameters() {
  for (const c of [...parameterGui.controllers]) c.destroy();
  for (const p of studio.state.set.parameters) {
    parameterModel[p.name] = p.value;
    const span = p.range[1] - p.range[0];
    parameterGui.add(parameterModel, p.name, p.range[0], p.range[1], 10 ** (Math.floor(Math.log10(span)) - 3))
      .name(PARAMETER_LABELS[p.name] || p.name)
      .onChange((v) => onSetParameter(p.name, v, 'move'))
      .onFinishChange((v) => onSetParameter(p.name, v, 'end'));
  }
}
function refreshParameters() {
  for (const p of studio.state.set.parameters) parameterModel[p.name] = p.value;
  for (const c of parameterGui.controllers) c.updateDisplay();
}
// [low, high] moved inward to multiples of `unit`.
function roundedInward([low, high], unit) {
  return [Math.ceil(low / unit - 1e-9) * unit, Math.floor(high / unit + 1e-9) * unit]
    .map((v) => Number(v.toFixed(6)));
}

function refreshSettings() {
  const s = studio.state.settings;
  settingsModel.step = s.step;
  settingsModel.stature = s.stature;
  settingsModel.bySpeed = s.speed > 0;
  if (s.speed > 0) settingsModel.walkSpeed = s.speed;
  const step = settingsGui.folders[0].controllers[0];
  const [low, high] = roundedInward(s.limits.step, 0.005);
  step.min(low).max(high);
  const speed = settingsGui.folders[0].controllers.find((c) => c.property === 'walkSpeed');
  if (speed && s.limits.speed) {
    const [slow, fast] = roundedInward(s.limits.speed, 0.01);
    speed.min(slow).max(fast);
  }
  const cycles = settingsGui.folders[0].controllers.find((c) => c.property === 'cycles');
  if (cycles) cycles.disable(Boolean(s.path));
  for (const folder of settingsGui.folders) for (const c of folder.controllers) c.updateDisplay();
}

// ---- the toolbar -----------------------------------------------------------------------------

function buildCompareChoices() {
  const select = $('#compare');
  const current = studio.compare ? studio.compare.id : '';
  const options = [['', 'nothing'], ['opened', 'this set as opened (before its edits)'],
    ...studio.state.sets.map((s) => [s.id, s.label])];
  select.replaceChildren(...options.map(([id, label]) => new Option(label, id, false, id === current)));
}

function wireToolbar() {
  $('#undo').addEventListener('click', () => request('/api/undo', {}, applySet));
  $('#redo').addEventListener('click', () => request('/api/redo', {}, applySet));
  document.addEventListener('keydown', (event) => {
    if (!(event.ctrlKey || event.metaKey) || event.key.toLowerCase() !== 'z') return;
    if (event.target.closest('input')) return;
    event.preventDefault();
    if (event.shiftKey) $('#redo').click();
    else $('#undo').click();
  });
  $('#compare').addEventListener('change', (event) => compareWith(event.target.value));
  $('#save-form').addEventListener('submit', (event) => {
    event.preventDefault();
    save($('#save-name').value.trim());
  });
}

// Saves the set as `name`; where another set is saved under it, asks before replacing it.
function save(name, overwrite = false) {
  request('/api/save', overwrite ? { name, overwrite } : { name }, (answer) => {
    studio.state.sets = answer.sets;
    updateHistory(answer.history);
    buildCompareChoices();
    buildSettings();
    showMessage(`Saved to ${answer.folder}`);
    studio.saved = answer.saved;
  }, performance.now(), undefined, (error) => {
    if (error.status !== 409 || error.field !== 'name' || overwrite) return false;
    if (window.confirm(`${error.message.split(': save with')[0]}.\n\nReplace it with this set?`)) {
      save(name, true);
    } else {
      showMessage(`Not saved: '${name}' holds another set`, 'error');
    }
    return true;
  });
}

// ---- start -----------------------------------------------------------------------------------

// The time each view takes to draw a frame (ms), the last 120 frames: docs/studio.md quotes it.
studio.frameMs = { view3d: [], side: [] };
function timed(list, draw) {
  const start = performance.now();
  draw();
  list.push(performance.now() - start);
  if (list.length > 120) list.shift();
}

let pathDrawn = 0;
function frame() {
  const t = motion ? clock.tick(motion.duration) : 0;
  // Drawn in software, the views wait while a request is out: the rasteriser would take the
  // processor from its answer, and they would only draw the walk it replaces (docs/studio.md,
  // "Latency").
  if (motion && !(busy && view3d.software)) {
    timed(studio.frameMs.view3d, () => view3d.render(t));
    timed(studio.frameMs.side, () => side.render(t));
    curves.showCycle(motion.cyclePercent(t));
    if (pathPanel.details.open && performance.now() - pathDrawn > 100) {
      pathDrawn = performance.now();
      pathPanel.draw(t);
    }
    askFired(t);
  }
  requestAnimationFrame(frame);
}

// ---- which rules fire now --------------------------------------------------------------------

// The server sends, for the frame asked, each slot controller's inputs and each rule's firing
// strength as the library evaluates them (POST /api/fired): the page computes none itself, so the
// bars are the library's numbers at the inputs marked, whatever the terms' shapes, hedges or
// operators (a second evaluator in the page could drift from the engine's). One frame's answer is
// about 2 KB; the page asks only while a controller's rules are open, one request at a time, for
// the frame shown when the last answer came (at most one a frame while playing).
// A refusal (4xx) is the server's answer for these inputs, the frame and the walk: the page asks
// again only when one of them changes (`refused`), not every frame; `asked` counts the requests.
const fired = { frame: -1, walk: null, out: false, shown: null, refused: null, asked: 0 };
studio.fired = fired;
function askFired(t) {
  if (fired.out || busy || !document.querySelector('.controller details.rules[open]')) return;
  const index = Math.round(t * 30);
  if (index === fired.frame && fired.walk === studio.walk) return;
  if (fired.refused && fired.refused.frame === index && fired.refused.walk === studio.walk) return;
  fired.out = true;
  fired.asked++;
  const walk = studio.walk;
  api.post('/api/fired', { time: index / 30 }).then((answer) => {
    fired.frame = index;
    fired.walk = walk;
    fired.shown = answer;
    fired.refused = null;
    if (walk === studio.walk) panel.showFired(answer);
  }).catch((error) => {
    fired.frame = -1;
    if (error instanceof api.RequestError && error.status >= 400 && error.status < 500) {
      fired.refused = { frame: index, walk };
      if (walk === studio.walk) panel.showFired(null);
    }
    // Otherwise the server away or failing: the next frame asks again.
  }).finally(() => {
    fired.out = false;
  });
}

// Scrubbing: drag across the side view to move through the walk (it pauses); a double click, or
// the space bar, plays it again; with the walk paused the arrow keys step a frame (1/30 s).
function wirePlayback() {
  const canvas = $('#side-canvas');
  let from = null;
  canvas.addEventListener('pointerdown', (event) => {
    canvas.setPointerCapture(event.pointerId);
    from = { x: event.clientX, t: clock.t };
    clock.playing = false;
    syncPlaying();
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!from || !motion) return;
    // A pixel is as much time as the pelvis takes to cross it at the walk's speed.
    const speed = (studio.walk.gait && studio.walk.gait.speed) || 1.3;
    const t = from.t + (event.clientX - from.x) / side.scale / speed;
    clock.t = Math.min(Math.max(t, 0), motion.duration);
  });
  const end = () => (from = null);
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('dblclick', () => {
    clock.playing = true;
    syncPlaying();
  });
  document.addEventListener('keydown', (event) => {
    if (event.target.closest('input, select, textarea, .knot')) return;
    if (event.key === ' ') {
      event.preventDefault();
      clock.playing = !clock.playing;
      syncPlaying();
    } else if (!clock.playing && (event.key === 'ArrowLeft' || event.key === 'ArrowRight') && motion) {
      event.preventDefault();
      clock.t = Math.min(Math.max(clock.t + (event.key === 'ArrowLeft' ? -1 : 1) / 30, 0), motion.duration);
    }
  });
}

function syncPlaying() {
  settingsModel.playing = clock.playing;
  for (const folder of settingsGui.folders) for (const c of folder.controllers) c.updateDisplay();
}

async function start() {
  view3d = new View3D($('#view3d'), $('#settings'));
  side = new SideView($('#side-canvas'));
  pathPanel = new PathPanel($('#view3d'), changePath);
  studio.pathPanel = pathPanel;
  studio.view3d = view3d;
  curves = new Curves($('#curves'));
  panel = new ControllerPanel($('#controller-list'), {
    onKnot, onKnotTyped, onWord, onRules, onTerm, termShapes: () => studio.state.term_shapes || ['Triangle'],
    onClamped: (text) => showMessage(text, 'error'),
  });
  wireToolbar();
  wirePlayback();
  await reload();
  requestAnimationFrame(frame);
  studio.ready = true;
}

start().catch((error) => {
  showError(error);
  console.error(error);
});
