// Every controller of the set as an animator reads it: each input's terms as membership functions
// labelled with their words, with a handle on every knot of a strong triangular partition to drag;
// the output words as sliders; the controller's output over its inputs (a curve for one input, a
// map for two); the rules in plain text and, for a partition, as a grid of words.
import GUI from 'lil-gui';
import { escapeHtml } from './curves.js';

const SVG = 'http://www.w3.org/2000/svg';
const WIDTH = 330;
const HEIGHT = 118;
const MARGIN = { left: 10, right: 10, top: 27, bottom: 22 };
const LABEL_GAP = 34; // px between two words' labels on one row
const TERM_COLOURS = ['#2f6db5', '#c0504d', '#4e9a4e', '#8064a2', '#d08a2c', '#3a9aa5', '#7a7a7a'];

function svg(tag, attributes = {}, parent = null) {
  const element = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attributes)) element.setAttribute(k, v);
  if (parent) parent.append(element);
  return element;
}

function readable(word) {
  return word.replaceAll('_', ' ');
}

function niceNumber(v) {
  const a = Math.abs(v);
  if (a >= 100) return v.toFixed(0);
  if (a >= 10) return v.toFixed(1);
  if (a >= 1) return v.toFixed(2);
  return v.toFixed(3);
}

// A term's membership at x for the shapes drawn exactly (Triangle); others come as samples.
function trianglePoints(parameters, height) {
  const [a, b, c] = parameters;
  return [[a, 0], [b, height], [c, 0]];
}

// The knots of a strong triangular partition moved as the server moves them (set_view.cpp): the
// neighbours' feet follow a middle knot; an end knot carries the range and its outer foot.
export function moveKnot(input, index, value) {
  const terms = input.terms;
  const n = terms.length;
  const p = terms[index].parameters;
  const shift = value - p[1];
  p[1] = value;
  if (index > 0) terms[index - 1].parameters[2] = value;
  else {
    p[0] += shift;
    input.range[0] = value;
  }
  if (index + 1 < n) terms[index + 1].parameters[0] = value;
  else {
    p[2] += shift;
    input.range[1] = value;
  }
  input.knots[index] = value;
}

class MembershipPlot {
  // `onDrag(index, value, phase, event)` is called as a knot is dragged (phase 'move', then 'end');
  // `onType(index, value, refused)` when a knot's value is typed into its field (`refused(text)`
  // shows the server's reason beside the fields).
  constructor(parent, controllerId, input, onDrag, onType, terms = null) {
    this.controllerId = controllerId;
    this.input = input;
    this.onDrag = onDrag;
    this.onType = onType;
    this.terms = terms; // {onTerm(change, refused), shapes()} for the term tools, or null
    this.figure = document.createElement('figure');
    this.figure.className = 'mf';
    parent.append(this.figure);
    this.svg = svg('svg', { viewBox: `0 0 ${WIDTH} ${HEIGHT}`, class: 'mf-plot' }, this.figure);
    this.shapes = svg('g', {}, this.svg);
    this.now = svg('g', { class: 'mf-now' }, this.svg);
    this.handles = svg('g', {}, this.svg);
    const caption = document.createElement('figcaption');
    caption.innerHTML = `<b>${escapeHtml(input.name)}</b> ${escapeHtml(input.description || '')}`;
    this.figure.append(caption);
    this.fields = document.createElement('div');
    this.fields.className = 'knot-fields';
    this.figure.append(this.fields);
    if (this.terms) this.tools = termTools(this.figure, this);
    // The x span is fixed while the card lives, so a drag maps the pointer steadily.
    const [low, high] = input.domain;
    const pad = (high - low) * 0.06;
    this.domain = [low - pad, high + pad];
    this.ghost = null;
    this.dragging = -1;
    this.draw();
  }

  x(value) {
    const [a, b] = this.domain;
    return MARGIN.left + ((value - a) / (b - a)) * (WIDTH - MARGIN.left - MARGIN.right);
  }
  y(degree) {
    return HEIGHT - MARGIN.bottom - degree * (HEIGHT - MARGIN.top - MARGIN.bottom);
  }
  value(clientX) {
    const box = this.svg.getBoundingClientRect();
    const px = ((clientX - box.left) / box.width) * WIDTH;
    const [a, b] = this.domain;
    return a + ((px - MARGIN.left) / (WIDTH - MARGIN.left - MARGIN.right)) * (b - a);
  }

  termPath(term) {
    if (term.shape === 'Triangle') {
      return trianglePoints(term.parameters, term.height).map(([x, y]) => `${this.x(x)},${this.y(y)}`);
    }
    if (term.samples) {
      const [low, high] = this.input.domain;
      return term.samples.map((y, i) => `${this.x(low + ((high - low) * i) / (term.samples.length - 1))},${this.y(y)}`);
    }
    return [];
  }

  draw() {
    const input = this.input;
    this.shapes.replaceChildren();
    svg('rect', {
      x: this.x(input.range[0] ?? this.domain[0]), y: MARGIN.top,
      width: Math.max(0, this.x(input.range[1] ?? this.domain[1]) - this.x(input.range[0] ?? this.domain[0])),
      height: HEIGHT - MARGIN.top - MARGIN.bottom, class: 'mf-range',
    }, this.shapes);
    svg('line', { x1: MARGIN.left, x2: WIDTH - MARGIN.right, y1: this.y(0), y2: this.y(0), class: 'mf-axis' }, this.shapes);
    if (this.ghost) {
      for (const term of this.ghost.terms) {
        svg('polyline', { points: this.termPath(term).join(' '), class: 'mf-ghost' }, this.shapes);
      }
    }
    // Words over their peaks, on a second row where two would overlap.
    const rowEnds = [-Infinity, -Infinity];
    const labels = input.terms.map((term, i) => {
      const peak = term.shape === 'Triangle' ? term.parameters[1] : peakOfSamples(term, input.domain);
      return { term, i, x: peak === null ? null : this.x(Math.min(Math.max(peak, this.domain[0]), this.domain[1])) };
    });
    input.terms.forEach((term, i) => {
      const colour = TERM_COLOURS[i % TERM_COLOURS.length];
      svg('polyline', { points: this.termPath(term).join(' '), stroke: colour, class: 'mf-term' }, this.shapes);
    });
    for (const { term, i, x } of [...labels].sort((a, b) => a.x - b.x)) {
      if (x === null) continue;
      const row = x - rowEnds[0] >= LABEL_GAP ? 0 : 1;
      rowEnds[row] = x;
      const label = svg('text', { x, y: row === 0 ? 10 : 21, fill: TERM_COLOURS[i % TERM_COLOURS.length], class: 'mf-word' }, this.shapes);
      label.textContent = readable(term.name);
    }
    // Axis ticks: the range's ends and the knots' values, those too close to the last left out.
    const ticks = input.partition ? input.knots : [input.range[0], input.range[1]].filter((v) => v !== null);
    let lastTick = -Infinity;
    for (const v of ticks) {
      if (this.x(v) - lastTick < 28) continue;
      lastTick = this.x(v);
      const t = svg('text', { x: this.x(v), y: HEIGHT - 6, class: 'mf-tick' }, this.shapes);
      t.textContent = niceNumber(v);
    }
    this.drawHandles();
    this.drawFields();
    if (this.tools) this.tools.show(input);
  }

  // A field a knot: its exact value typed, taken on Enter or leaving the field. The server keeps
  // the partition's order: a value past a neighbour's knot is refused with the reason, shown
  // under the fields, and the field shows the knot where it is.
  drawFields() {
    const knots = this.input.partition ? this.input.knots : [];
    if (this.fields.querySelectorAll('input').length !== knots.length) {
      this.fields.innerHTML = knots.map((_, i) => `<label title="${escapeHtml(this.input.terms[i].name)} peaks at">
        <span>${escapeHtml(readable(this.input.terms[i].name))}</span>
        <input type="number" step="any" class="knot-value" data-controller="${escapeHtml(this.controllerId)}"
          data-variable="${escapeHtml(this.input.name)}" data-knot="${i}"></label>`).join('') +
        '<p class="knot-error" role="alert"></p>';
      this.fields.querySelectorAll('input').forEach((field, i) => {
        field.addEventListener('keydown', (event) => event.stopPropagation());
        field.addEventListener('change', () => {
          const error = this.fields.querySelector('.knot-error');
          const value = Number(field.value);
          if (field.value.trim() === '' || !Number.isFinite(value)) {
            error.textContent = `${readable(this.input.terms[i].name)}: "${field.value}" is not a number`;
            field.value = Number(this.input.knots[i].toPrecision(12));
            return;
          }
          error.textContent = '';
          if (value === this.input.knots[i]) return;
          this.onType(i, value, (text) => {
            error.textContent = text;
            field.value = Number(this.input.knots[i].toPrecision(12));
            field.select();
          });
        });
      });
    }
    this.fields.querySelectorAll('input').forEach((field, i) => {
      if (document.activeElement !== field) field.value = Number(knots[i].toPrecision(12));
    });
  }

  // The input's value at the frame shown: a line across the terms, a dot where it meets each.
  setNow(value) {
    this.now.replaceChildren();
    if (value === null || value === undefined) return;
    const [low, high] = this.domain;
    const x = this.x(Math.min(Math.max(value, low), high));
    svg('line', { x1: x, x2: x, y1: MARGIN.top - 2, y2: HEIGHT - MARGIN.bottom, class: 'mf-now-line' }, this.now);
    const label = svg('text', { x: x + 3, y: HEIGHT - MARGIN.bottom - 3, class: 'mf-now-value' }, this.now);
    label.textContent = niceNumber(value);
    this.now.dataset.value = value;
  }

  drawHandles() {
    if (!this.input.partition) {
      this.handles.replaceChildren();
      return;
    }
    const knots = this.input.knots;
    while (this.handles.children.length > knots.length) this.handles.lastChild.remove();
    while (this.handles.children.length < knots.length) this.addHandle(this.handles.children.length);
    knots.forEach((k, i) => {
      const handle = this.handles.children[i];
      handle.setAttribute('cx', this.x(k));
      handle.setAttribute('cy', this.y(1));
      handle.classList.toggle('dragging', i === this.dragging);
    });
  }

  addHandle(index) {
    const handle = svg('circle', { r: 5.5, class: 'knot', tabindex: 0 }, this.handles);
    handle.dataset.controller = this.controllerId;
    handle.dataset.variable = this.input.name;
    handle.dataset.knot = index;
    const title = svg('title', {}, handle);
    handle.addEventListener('pointerenter', () => {
      title.textContent = `${readable(this.input.terms[index].name)} peaks at ${niceNumber(this.input.knots[index])}: ` +
        'drag, or focus and press the arrow keys (Shift: finer)';
    });
    handle.addEventListener('pointerdown', (event) => {
      event.preventDefault();
      handle.setPointerCapture(event.pointerId);
      handle.focus();
      this.dragging = index;
      this.moved = false;
      this.drawHandles();
    });
    handle.addEventListener('pointermove', (event) => {
      if (this.dragging !== index) return;
      this.move(index, this.value(event.clientX), 'move', event);
    });
    const end = (event) => {
      if (this.dragging !== index) return;
      this.dragging = -1;
      this.drawHandles();
      // A click that moved nothing changes nothing.
      if (this.moved) this.onDrag(index, this.input.knots[index], 'end', event);
    };
    handle.addEventListener('pointerup', end);
    handle.addEventListener('pointercancel', end);
    // A nudge a key press, each one step of the history: for knots too close to drag apart.
    handle.addEventListener('keydown', (event) => {
      if (event.key !== 'ArrowLeft' && event.key !== 'ArrowRight') return;
      event.preventDefault();
      const span = this.domain[1] - this.domain[0];
      const step = (event.shiftKey ? 0.001 : 0.01) * span * (event.key === 'ArrowLeft' ? -1 : 1);
      this.move(index, this.input.knots[index] + step, 'end', event);
    });
  }

  move(index, wanted, phase, event) {
    const value = this.clamp(index, wanted);
    if (value === this.input.knots[index]) return;
    moveKnot(this.input, index, value);
    this.moved = true;
    this.draw();
    this.onDrag(index, value, phase, event);
  }

  // Between the neighbouring knots (a hair inside them), and within the plot.
  clamp(index, value) {
    const knots = this.input.knots;
    const span = this.domain[1] - this.domain[0];
    const gap = span * 0.004;
    const low = index > 0 ? knots[index - 1] + gap : this.domain[0];
    const high = index + 1 < knots.length ? knots[index + 1] - gap : this.domain[1];
    const clamped = Math.min(Math.max(value, low), high);
    // Three significant decimals of the span: values a person reads, as the tuner writes them.
    const unit = 10 ** (Math.floor(Math.log10(span)) - 3);
    return Number((Math.round(clamped / unit) * unit).toPrecision(12));
  }

  // New data from the server; a knot being dragged keeps the pointer's value.
  update(input) {
    if (this.dragging >= 0) {
      const held = this.input.knots[this.dragging];
      this.input = input;
      if (input.partition && input.knots[this.dragging] !== held) moveKnot(this.input, this.dragging, held);
    } else {
      this.input = input;
    }
    this.draw();
  }
}

function peakOfSamples(term, domain) {
  if (!term.samples) return null;
  let best = 0;
  term.samples.forEach((y, i) => {
    if (y > term.samples[best]) best = i;
  });
  return domain[0] + ((domain[1] - domain[0]) * best) / (term.samples.length - 1);
}

// The controller's output over its inputs.
function drawResponse(element, controller) {
  const r = controller.response;
  const unit = controller.outputs[0] ? controller.outputs[0].name : 'output';
  if (!r.z) {
    const s = svg('svg', { viewBox: `0 0 ${WIDTH} 70`, class: 'response-plot' });
    const low = Math.min(...r.y);
    const high = Math.max(...r.y);
    const span = high - low || 1;
    // Aligned with the membership plots above, whose span is the input's padded by 6 % a side.
    const plotWidth = WIDTH - MARGIN.left - MARGIN.right;
    const x = (i) => MARGIN.left + ((0.06 + i / (r.x.length - 1)) / 1.12) * plotWidth;
    const y = (v) => 60 - ((v - low) / span) * 48;
    if (low < 0 && high > 0) svg('line', { x1: MARGIN.left, x2: WIDTH - MARGIN.right, y1: y(0), y2: y(0), class: 'mf-axis' }, s);
    svg('polyline', { points: r.y.map((v, i) => `${x(i)},${y(v)}`).join(' '), class: 'response-line' }, s);
    const label = svg('text', { x: MARGIN.left, y: 10, class: 'mf-tick start' }, s);
    label.textContent = `${unit} over ${controller.inputs[0].name}: ${niceNumber(low)} to ${niceNumber(high)}`;
    element.replaceChildren(s);
    return;
  }
  // Two inputs: a map, rows the second input upward, columns the first; blue negative, red positive.
  const canvas = document.createElement('canvas');
  canvas.width = r.x.length;
  canvas.height = r.y.length;
  canvas.className = 'response-map';
  const ctx = canvas.getContext('2d');
  let extent = 1e-9;
  for (const row of r.z) for (const v of row) extent = Math.max(extent, Math.abs(v));
  const image = ctx.createImageData(r.x.length, r.y.length);
  r.z.forEach((row, j) => {
    row.forEach((v, i) => {
      const k = ((r.y.length - 1 - j) * r.x.length + i) * 4;
      const t = v / extent;
      const [red, green, blue] = t >= 0 ? [255, 255 * (1 - t), 255 * (1 - t)] : [255 * (1 + t), 255 * (1 + t), 255];
      image.data.set([red, green, blue, 255], k);
    });
  });
  ctx.putImageData(image, 0, 0);
  const caption = document.createElement('div');
  caption.className = 'response-caption';
  caption.textContent = `${unit}: ${controller.inputs[0].name} across, ${controller.inputs[1].name} up; ` +
    `red +${niceNumber(extent)}, blue −${niceNumber(extent)}`;
  element.replaceChildren(canvas, caption);
}

function rulesHtml(controller) {
  const rules = controller.rules;
  let grid = '';
  if (rules.grid && controller.inputs.length === 2) {
    const words = Object.fromEntries(controller.outputs[0].words.map((w) => [w.name, w.value]));
    const extent = Math.max(1e-9, ...Object.values(words).map(Math.abs));
    const cell = (word) => {
      const t = (words[word] ?? 0) / extent;
      const colour = t >= 0 ? `rgba(220,80,70,${(0.55 * t).toFixed(2)})` : `rgba(60,110,200,${(-0.55 * t).toFixed(2)})`;
      return `<td style="background:${colour}">${escapeHtml(readable(word))}</td>`;
    };
    const [a, b] = controller.inputs;
    grid = `<table class="rule-grid"><tr><th>${escapeHtml(a.name)} \\ ${escapeHtml(b.name)}</th>${b.terms.map((t) => `<th>${escapeHtml(readable(t.name))}</th>`).join('')}</tr>
      ${rules.grid.map((row, i) => `<tr><th>${escapeHtml(readable(a.terms[i].name))}</th>${row.map(cell).join('')}</tr>`).join('')}</table>`;
  }
  return grid;
}

// Under an input's plot: a term picked, its shape and parameters shown; Shape gives it the shape
// chosen (from its feet and peak, or the parameters as typed when they were changed), Remove takes
// it away (the server refuses while rules read it, naming them), Add puts a new term of the shape
// chosen in the middle of the input's span. Each is one step of the history; a refusal is shown
// under the tools.
function termTools(figure, plot) {
  const box = document.createElement('div');
  box.className = 'term-tools';
  const id = `${plot.controllerId}/${plot.input.name}`;
  box.dataset.controller = plot.controllerId;
  box.dataset.variable = plot.input.name;
  box.innerHTML = `<select class="term-pick" aria-label="term of ${escapeHtml(id)}"></select>
    <select class="term-shape" aria-label="shape"></select>
    <input class="term-parameters" type="text" spellcheck="false" aria-label="parameters"
      title="the term's parameters, separated by spaces">
    <button type="button" class="term-reshape" title="give the term this shape">Shape</button>
    <button type="button" class="term-remove" title="remove the term (not while rules read it)">Remove</button>
    <input class="term-new-name" type="text" spellcheck="false" placeholder="new term" aria-label="new term's name">
    <button type="button" class="term-add" title="add a term of the shape chosen">Add</button>
    <p class="term-error" role="alert"></p>`;
  figure.append(box);
  const pick = box.querySelector('.term-pick');
  const shape = box.querySelector('.term-shape');
  const parameters = box.querySelector('.term-parameters');
  const error = box.querySelector('.term-error');
  const newName = box.querySelector('.term-new-name');
  for (const field of box.querySelectorAll('input, select')) {
    field.addEventListener('keydown', (event) => event.stopPropagation());
  }
  let typed = false; // the parameters field changed since the term was shown
  const picked = () => plot.input.terms.find((t) => t.name === pick.value);
  const showTerm = () => {
    const term = picked();
    if (!term) return;
    const shapes = plot.terms.shapes();
    const options = shapes.includes(term.shape) ? shapes : [term.shape, ...shapes];
    if (shape.dataset.options !== options.join(' ')) {
      shape.innerHTML = options.map((s) => `<option>${escapeHtml(s)}</option>`).join('');
      shape.dataset.options = options.join(' ');
    }
    shape.value = term.shape;
    if (document.activeElement !== parameters) parameters.value = term.parameters.map((p) => Number(p.toPrecision(12))).join(' ');
    typed = false;
  };
  const send = (change) => {
    error.textContent = '';
    plot.terms.onTerm(change, (text) => {
      error.textContent = text;
    });
  };
  pick.addEventListener('change', showTerm);
  parameters.addEventListener('input', () => {
    typed = true;
  });
  box.querySelector('.term-reshape').addEventListener('click', () => {
    const change = { action: 'shape', term: pick.value, shape: shape.value };
    if (typed) {
      const values = parameters.value.trim().split(/\s+/).map(Number);
      if (values.some((v) => !Number.isFinite(v))) {
        error.textContent = `"${parameters.value}" is not a list of numbers`;
        return;
      }
      change.parameters = values;
    }
    send(change);
  });
  box.querySelector('.term-remove').addEventListener('click', () => send({ action: 'remove', term: pick.value }));
  box.querySelector('.term-add').addEventListener('click', () => {
    const name = newName.value.trim();
    if (!name) {
      error.textContent = 'type the new term\'s name first';
      return;
    }
    send({ action: 'add', term: name, shape: shape.value });
  });
  return {
    show: (input) => {
      const names = input.terms.map((t) => t.name);
      if (pick.dataset.names !== names.join(' ')) {
        const was = pick.value;
        pick.innerHTML = names.map((n) => `<option value="${escapeHtml(n)}">${escapeHtml(readable(n))}</option>`).join('');
        pick.dataset.names = names.join(' ');
        // A term just added is the one shown; otherwise the one picked before, if still there.
        const added = names.find((n) => n === newName.value.trim());
        pick.value = added || (names.includes(was) ? was : names[0]);
        if (added) newName.value = '';
      }
      showTerm();
    },
  };
}

// The rules as text to edit, one a line as FLL writes them. Apply sends them to the server, which
// reads them with the library's own rule parser: a rule it cannot read comes back as a refusal
// naming the rule's number and the word, shown under the text, which stays as typed.
function ruleEditor(element, controller, onRules) {
  element.innerHTML = `<div class="rule-grid-box"></div><div class="fired"></div>
    <textarea class="rule-edit" spellcheck="false" aria-label="rules of ${escapeHtml(controller.title)}"></textarea>
    <div class="rule-actions"><button type="button" class="apply-rules" disabled>Apply rules</button>
    <button type="button" class="revert-rules" disabled>Revert</button>
    <span class="rule-help">one rule a line: if INPUT is TERM [and …] then OUTPUT is WORD [with W]</span></div>
    <p class="rule-error" role="alert"></p>`;
  const text = element.querySelector('.rule-edit');
  const apply = element.querySelector('.apply-rules');
  const revert = element.querySelector('.revert-rules');
  const editor = {
    shown: '',
    sent: false,
    dirty: () => text.value !== editor.shown,
    sync: () => {
      apply.disabled = revert.disabled = !editor.dirty();
    },
    show: (rules) => {
      const value = rules.text.join('\n');
      // An edit being typed stays until it is applied or reverted.
      if (!editor.dirty() || editor.sent) {
        text.value = value;
        element.querySelector('.rule-error').textContent = '';
      }
      editor.shown = value;
      editor.sent = false;
      text.rows = Math.min(36, 2 * rules.text.length + 1);
      editor.sync();
    },
    refused: (message) => {
      editor.sent = false;
      element.querySelector('.rule-error').textContent = message;
      // The rule refused, selected: "rule N" counts the lines that are not blank.
      const match = /^rule (\d+)/.exec(message);
      if (!match) return;
      let n = Number(match[1]);
      let start = 0;
      for (const line of text.value.split('\n')) {
        if (line.trim() !== '' && --n === 0) {
          text.focus();
          text.setSelectionRange(start, start + line.length);
          return;
        }
        start += line.length + 1;
      }
    },
  };
  text.addEventListener('input', editor.sync);
  text.addEventListener('keydown', (event) => {
    if (event.key === 'Enter' && (event.ctrlKey || event.metaKey)) {
      event.preventDefault();
      apply.click();
    }
    event.stopPropagation(); // the page's keys (space: play, arrows: step) are not the text's
  });
  apply.addEventListener('click', () => {
    const rules = text.value.split('\n').map((line) => line.trim()).filter((line) => line !== '');
    editor.sent = true;
    element.querySelector('.rule-error').textContent = '';
    onRules(controller.id, rules, editor.refused);
  });
  revert.addEventListener('click', () => {
    text.value = editor.shown;
    element.querySelector('.rule-error').textContent = '';
    editor.sync();
  });
  return editor;
}

class ControllerCard {
  constructor(parent, controller, handlers) {
    this.handlers = handlers;
    this.element = document.createElement('article');
    this.element.className = 'controller';
    this.element.dataset.controller = controller.id;
    parent.append(this.element);
    this.element.innerHTML = `<header><h3>${escapeHtml(controller.title)}</h3>
      <p class="description">${escapeHtml(controller.description || '')}</p></header>
      <div class="inputs"></div><div class="response"></div><div class="words"></div>
      <details class="rules"><summary>${controller.rules.text.length} rules</summary><div></div></details>`;
    this.data = controller;
    this.plots = controller.inputs.map((input) => new MembershipPlot(
      this.element.querySelector('.inputs'), controller.id, structuredClone(input),
      (index, value, phase, event) => handlers.onKnot(controller.id, input.name, index, value, phase, event),
      (index, value, refused) => handlers.onKnotTyped(controller.id, input.name, index, value, refused),
      handlers.onTerm ? {
        onTerm: (change, refused) => handlers.onTerm(controller.id, input.name, change, refused),
        shapes: () => (handlers.termShapes ? handlers.termShapes() : ['Triangle']),
      } : null));
    this.rules = ruleEditor(this.element.querySelector('.rules > div'), controller,
      (id, rules, refused) => handlers.onRules(id, rules, refused));
    this.buildWords(controller, null);
    this.refresh(controller);
  }

  buildWords(controller, compared) {
    if (this.gui) this.gui.destroy();
    const out = controller.outputs[0];
    this.words = {};
    this.controllers = {};
    if (!out || out.words.length === 0) return;
    const box = this.element.querySelector('.words');
    box.replaceChildren();
    const caption = document.createElement('p');
    caption.className = 'words-caption';
    caption.innerHTML = `<b>${escapeHtml(out.name)}</b> ${escapeHtml(out.description || '')}`;
    box.append(caption);
    this.gui = new GUI({ container: box, title: `the words of ${out.name}`, width: WIDTH });
    const finite = out.range.filter((v) => v !== null).map(Math.abs);
    for (const word of out.words) {
      this.words[word.name] = word.value;
      const wide = Math.max(1, ...finite, ...out.words.map((w) => Math.abs(w.value) * 1.3));
      const step = 10 ** (Math.floor(Math.log10(wide)) - 3);
      // lil-gui counts steps from the slider's minimum: a whole number of steps keeps them round.
      const base = Math.ceil(wide / step) * step;
      const was = compared ? compared.outputs[0].words.find((w) => w.name === word.name) : null;
      const label = readable(word.name) + (was && was.value !== word.value ? ` (was ${niceNumber(was.value)})` : '');
      const c = this.gui.add(this.words, word.name, -base, base, step).name(label);
      c.domElement.dataset.word = word.name;
      c.onChange((value) => this.handlers.onWord(controller.id, out.name, word.name, value, 'move'));
      c.onFinishChange((value) => this.handlers.onWord(controller.id, out.name, word.name, value, 'end'));
      if (this.handlers.onClamped) sayWhenClamped(c, readable(word.name), this.handlers.onClamped);
      exactWhenTyped(c);
      this.controllers[word.name] = c;
    }
  }

  refresh(controller) {
    this.data = controller;
    drawResponse(this.element.querySelector('.response'), controller);
    this.element.querySelector('.rule-grid-box').innerHTML = rulesHtml(controller);
    this.rules.show(controller.rules);
    this.element.querySelector('.rules > summary').textContent = `${controller.rules.text.length} rules`;
  }

  // Which rules fire at the frame shown (the server's answer for this controller, or null): the
  // inputs marked on their plots, each rule's strength as a bar under its text.
  showFired(now, time) {
    const box = this.element.querySelector('.fired');
    if (now && now.leg === null) {  // no leg in this controller's phase at this frame
      this.plots.forEach((plot) => plot.setNow(null));
      box.innerHTML = `<p class="fired-caption">At ${time.toFixed(2)} s no leg is in this controller's phase: it drives nothing.</p>`;
      return;
    }
    if (!now || now.rules.length !== this.data.rules.text.length) {
      this.plots.forEach((plot) => plot.setNow(null));
      box.replaceChildren();
      return;
    }
    this.plots.forEach((plot, i) => plot.setNow(now.inputs[i]));
    const strongest = Math.max(...now.rules);
    const inputs = this.data.inputs.map((input, i) => `${escapeHtml(input.name)} ${niceNumber(now.inputs[i])}`).join(', ');
    // An upper body controller answers for a side (the left), read from a leg.
    const reader = now.side ? `the ${now.side} side, from the ${now.leg} leg` : `the ${now.leg} leg`;
    box.innerHTML = `<p class="fired-caption">At ${time.toFixed(2)} s, ${reader}: ${inputs} → ${niceNumber(now.output)}</p>
      <ol class="fired-rules">${this.data.rules.text.map((text, r) => {
        const w = now.rules[r];
        return `<li class="${w > 0 && w === strongest ? 'strongest' : ''}${w === 0 ? ' idle' : ''}" data-strength="${w}">
          <span class="fired-bar" style="width:${(100 * Math.min(1, w)).toFixed(1)}%"></span>
          <span class="fired-text">${escapeHtml(text)}</span><span class="fired-value">${w.toFixed(2)}</span></li>`;
      }).join('')}</ol>`;
  }

  // The server's new view of this controller.
  update(controller) {
    controller.inputs.forEach((input, i) => this.plots[i].update(structuredClone(input)));
    const out = controller.outputs[0];
    if (out) {
      for (const word of out.words) {
        const c = this.controllers[word.name];
        if (c && this.words[word.name] !== word.value && document.activeElement?.closest('.lil-gui') !== c.domElement.closest('.lil-gui')) {
          this.words[word.name] = word.value;
          c.updateDisplay();
        }
      }
    }
    this.refresh(controller);
  }

  setCompared(compared) {
    this.plots.forEach((plot, i) => {
      plot.ghost = compared ? compared.inputs[i] : null;
      plot.draw();
    });
    this.buildWords(this.data, compared);
  }
}

export class ControllerPanel {
  constructor(container, handlers) {
    this.container = container;
    this.handlers = handlers;
    this.cards = new Map();
  }

  render(set, compareSet) {
    this.container.replaceChildren();
    this.cards.clear();
    const slots = set.controllers.filter((c) => !c.ground && !c.part);
    const upperBody = set.controllers.filter((c) => c.part);
    const terrain = set.controllers.filter((c) => c.ground);
    for (const c of slots) this.cards.set(c.id, new ControllerCard(this.container, c, this.handlers));
    if (upperBody.length) {
      const group = document.createElement('details');
      group.className = 'upper-body';
      group.innerHTML = `<summary>Upper body: ${upperBody.length} controllers (arms, pelvis and chest; each side read from a leg)</summary>`;
      this.container.append(group);
      for (const c of upperBody) this.cards.set(c.id, new ControllerCard(group, c, this.handlers));
    }
    if (terrain.length) {
      const group = document.createElement('details');
      group.className = 'terrain-words';
      const words = set.terrain.map((g) => `${g.ground}: ${g.words.map((w) => `${w.word} ${w.incline_deg}°`).join(', ')}`).join('; ');
      group.innerHTML = `<summary>Terrain words: ${terrain.length} controllers (${escapeHtml(words)})</summary>`;
      this.container.append(group);
      for (const c of terrain) this.cards.set(c.id, new ControllerCard(group, c, this.handlers));
    }
    this.setCompared(compareSet);
  }

  update(controller) {
    const card = this.cards.get(controller.id);
    if (card) card.update(controller);
  }

  // POST /api/fired's answer: the slots' and the upper body's controllers show it; the terrain
  // words' show nothing.
  showFired(answer) {
    for (const [id, card] of this.cards) card.showFired(answer ? answer.controllers[id] || null : null, answer ? answer.time : 0);
  }

  setCompared(compareSet) {
    for (const [id, card] of this.cards) {
      const other = compareSet ? compareSet.controllers.find((c) => c.id === id) : null;
      card.setCompared(other || null);
    }
  }
}

// lil-gui rounds a number typed into a slider's field to the slider's step (37.625 became 38 on
// a slider of whole numbers): typed, a number is taken as it is; dragged, the slider keeps its
// round steps. 'beforeinput' comes before lil-gui's own 'input' handler, which snaps.
export function exactWhenTyped(control) {
  const input = control.$input;
  if (!input || typeof control._snap !== 'function') return;
  const snap = control._snap.bind(control);
  let typing = false;
  input.addEventListener('beforeinput', () => {
    typing = true;
  });
  input.addEventListener('blur', () => {
    typing = false;
  });
  control._snap = (value) => (typing ? value : snap(value));
}

// lil-gui puts a number typed into a slider's field within the slider's range without a word
// (880 typed as 5000 became the slider's end, 1144): this says so through `say`, naming the
// control, the number typed and the one taken.
export function sayWhenClamped(control, label, say) {
  const input = control.$input;
  if (!input) return;
  let typed = null;
  input.addEventListener('input', () => {
    typed = Number.parseFloat(input.value);
  });
  input.addEventListener('blur', () => {
    const [low, high] = [control._min, control._max];
    if (Number.isFinite(typed) && ((low !== undefined && typed < low) || (high !== undefined && typed > high))) {
      say(`${label}: ${typed} is outside the slider's ${low} to ${high}; it was set to ${control.getValue()}`);
    }
    typed = null;
  });
}
