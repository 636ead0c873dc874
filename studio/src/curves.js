// The joint curves over the gait cycle (uPlot): the walk's mean left-leg curve against the
// normative mean and its band of two standard deviations, with RMSE and Pearson r in the title;
// a compared set's curve dashed.
import uPlot from 'uplot';

const JOINTS = [
  { key: 'thigh', title: 'Thigh', long: 'thigh inclination (hip flexion less pelvic tilt), forward +' },
  { key: 'knee', title: 'Knee', long: 'knee flexion' },
  { key: 'ankle', title: 'Ankle', long: 'ankle dorsiflexion' },
];
const PERCENT = Array.from({ length: 51 }, (_, i) => i * 2);

function options(title, width, height) {
  return {
    title,
    width,
    height,
    cursor: { drag: { x: false, y: false } },
    legend: { show: false },
    scales: { x: { time: false, range: [0, 100] } },
    axes: [
      { label: '% of gait cycle', size: 34, labelSize: 14, labelFont: '11px system-ui', font: '11px system-ui' },
      { label: 'deg', size: 40, labelSize: 14, labelFont: '11px system-ui', font: '11px system-ui' },
    ],
    series: [
      {},
      { label: '-2 SD', stroke: 'rgba(90,130,190,0.35)', width: 1 },
      { label: '+2 SD', stroke: 'rgba(90,130,190,0.35)', width: 1 },
      { label: 'people', stroke: '#5a82be', width: 1.5, dash: [5, 4] },
      { label: 'this set', stroke: '#1f3b63', width: 2.5 },
      { label: 'compared', stroke: '#e8892b', width: 2, dash: [7, 4] },
    ],
    bands: [{ series: [2, 1], fill: 'rgba(90,130,190,0.14)' }],
  };
}

function scoreText(score) {
  if (!score) return '';
  return ` · RMSE ${score.rmse.toFixed(1)}° · r ${score.pearson.toFixed(2)}`;
}

export class Curves {
  constructor(container) {
    this.container = container;
    this.plots = [];
    this.reference = null;
    for (const joint of JOINTS) {
      const box = document.createElement('div');
      box.className = 'curve';
      box.dataset.joint = joint.key;
      container.append(box);
      const plot = new uPlot(options(joint.title, 300, 170), [PERCENT, [], [], [], [], []], box);
      this.plots.push({ joint, box, plot });
    }
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    for (const { box, plot } of this.plots) {
      const w = box.clientWidth;
      const h = box.clientHeight;
      if (w > 0 && h > 0) plot.setSize({ width: w, height: h - 34 });
    }
  }

  // A line at `percent` of the gait cycle on each chart: where the character is now.
  showCycle(percent) {
    for (const entry of this.plots) {
      if (!entry.cursor) {
        entry.cursor = document.createElement('div');
        entry.cursor.className = 'cycle-cursor';
        entry.plot.over.append(entry.cursor);
      }
      entry.cursor.style.display = percent === null ? 'none' : 'block';
      if (percent !== null) entry.cursor.style.left = `${entry.plot.valToPos(percent, 'x')}px`;
    }
  }

  setReference(reference) {
    this.reference = reference;
  }

  // The walk's view (and the compared one's, or null): new curves and titles.
  update(walk, compare) {
    for (const { joint, box, plot } of this.plots) {
      const ref = this.reference[joint.key];
      const lower = ref.mean.map((m, i) => m - 2 * ref.sd[i]);
      const upper = ref.mean.map((m, i) => m + 2 * ref.sd[i]);
      const none = PERCENT.map(() => null);
      const mine = walk.curves ? walk.curves[joint.key].mean : none;
      const theirs = compare && compare.curves ? compare.curves[joint.key].mean : none;
      plot.setData([PERCENT, lower, upper, ref.mean, mine, theirs]);
      const title = box.querySelector('.u-title');
      let text = joint.title + (walk.scores ? scoreText(walk.scores[joint.key]) : ' · not measured');
      if (compare && compare.scores) text += ` · other ${compare.scores[joint.key].rmse.toFixed(1)}°`;
      if (title) {
        title.textContent = text;
        title.title = `Mean left-leg ${joint.long} over the gait cycle against ${this.reference.name} ` +
          '(dashed, band ±2 SD); RMSE and Pearson r of the means';
      }
    }
  }
}

// The contact figures with their bounds, a warning for each bound missed, and the walk's gait.
export function renderFigures(element, walk, compare) {
  const rows = walk.figures.map((f, i) => {
    const other = compare ? compare.figures[i] : null;
    const value = (v) => (v === null || v === undefined ? '–' : v.toFixed(2));
    return `<tr class="${f.missed ? 'missed' : 'met'}">
      <td>${f.missed ? '⚠' : '✓'}</td><td>${f.name}</td>
      <td class="num">${value(f.value)} ${f.unit.replace(' a frame', '/frame')}</td><td class="bound">${f.bound}</td>
      ${compare ? `<td class="num compared">${other ? value(other.value) : '–'}</td>` : ''}</tr>`;
  });
  const g = walk.gait;
  const gait = g
    ? `<p class="gait">${g.cadence.toFixed(0)} steps/min · ${g.speed.toFixed(2)} m/s · stance
       ${g.stance_percent.toFixed(1)} % · step ${g.step_length.toFixed(3)} m · knee peak
       ${g.knee_peak.toFixed(0)}° at ${g.knee_peak_percent.toFixed(0)} %</p>`
    : `<p class="gait">Not measured: ${escapeHtml(walk.not_measured || '')}</p>`;
  // The first few bounds missed, the rest in the element's tooltip.
  const shown = walk.warnings.slice(0, 3);
  const more = walk.warnings.length - shown.length;
  const warnings = walk.warnings.length
    ? `<ul class="warnings" title="${escapeHtml(walk.warnings.join('\n'))}">${shown.map((w) => `<li>⚠ ${escapeHtml(w)}</li>`).join('')}
       ${more > 0 ? `<li>⚠ and ${more} more</li>` : ''}</ul>`
    : '<p class="ok">Every contact bound met.</p>';
  element.innerHTML = `<h3>Contact</h3>
    <table><thead><tr><th></th><th></th><th class="num">this set</th><th>bound</th>
    ${compare ? '<th class="num">other</th>' : ''}</tr></thead><tbody>${rows.join('')}</tbody></table>
    ${warnings}${gait}`;
  element.classList.toggle('has-warnings', walk.warnings.length > 0);
}

export function escapeHtml(text) {
  return String(text).replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' })[c]);
}
