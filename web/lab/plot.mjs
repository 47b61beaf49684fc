// A live uPlot chart of a lab block's plot: traces against simulation time over the
// last `window` seconds, dashed where asked.
import uPlot from '../node_modules/uplot/dist/uPlot.esm.js';

const kHeight = 200;
const kColors = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b'];

// A text as one CSV field: quoted, its quotes doubled.
export function csvText(text) {
  return `"${String(text).replaceAll('"', '""')}"`;
}

// The texts of an axis's ticks, with as many decimals as their spacing needs (so that
// ticks 0.01 apart do not all read "0").
export function tickTexts(chart, ticks) {
  const spacing = ticks.length > 1 ? Math.abs(ticks[1] - ticks[0]) : 1;
  const decimals = spacing > 0 ? Math.min(12, Math.max(0, -Math.floor(Math.log10(spacing) + 1e-9))) : 0;
  return ticks.map((v) => {
    const text = v.toFixed(decimals);
    return /^-0(\.0*)?$/.test(text) ? text.slice(1) : text;  // (no "-0")
  });
}

export class LivePlot {
  // spec: {ylabel, window, traces: [{label, dash}]}; width in pixels.
  constructor(container, spec, width) {
    this.window = Number(spec.window) > 0 ? Number(spec.window) : 5;
    this.columns = [[], ...spec.traces.map(() => [])];
    this.labels = ['time', ...spec.traces.map((trace, i) => trace.label ?? `trace ${i}`)];
    this.xScale = { min: 0, max: this.window };
    this.redraw = () => {
      this.chart.setData(this.columns, false);
      this.chart.setScale('x', this.xScale);
    };
    const series = [{ label: 't (s)' }, ...spec.traces.map((trace, i) => ({
      label: trace.label ?? `trace ${i}`,
      stroke: kColors[i % kColors.length],
      width: 1.5,
      dash: trace.dash ? [6, 4] : undefined,
      points: { show: false },
      value: (u, v) => (v == null ? '-' : v.toFixed(3)),
    }))];
    this.chart = new uPlot({
      width, height: kHeight, series, legend: { live: false },
      cursor: { show: false },
      scales: { x: { time: false } },
      axes: [{ label: 'time (s)' }, { label: spec.ylabel ?? '', size: 55, values: tickTexts }],
    }, this.columns, container);
  }

  // Appends one sample (values may be NaN where a trace failed) and drops old ones; a
  // sample at the same time as the last one (nothing stepped) is skipped.
  push(time, values) {
    const last = this.columns[0].length ? this.columns[0][this.columns[0].length - 1] : NaN;
    if (time === last) return;
    if (time < last) this.clear();
    this.columns[0].push(time);
    for (let i = 0; i < values.length; i++) this.columns[i + 1].push(Number.isFinite(values[i]) ? values[i] : null);
    let drop = 0;
    while (drop < this.columns[0].length && this.columns[0][drop] < time - this.window) drop++;
    if (drop) for (const column of this.columns) column.splice(0, drop);
  }

  // Redraws with the x axis spanning the window that ends now (the scale object is
  // reused from frame to frame).
  draw() {
    const t = this.columns[0];
    const end = t.length ? t[t.length - 1] : 0;
    this.xScale.min = Math.max(0, end - this.window);
    this.xScale.max = Math.max(this.window, end);
    this.chart.batch(this.redraw);
  }

  // The samples kept (the last `window` seconds) as CSV lines: a header of the traces'
  // labels, then one row per sample (empty where a trace had no value).
  csvLines() {
    const lines = [this.labels.map(csvText).join(',')];
    for (let i = 0; i < this.columns[0].length; i++) {
      lines.push(this.columns.map((column) => (column[i] == null ? '' : String(column[i]))).join(','));
    }
    return lines;
  }

  // Drops the samples after `time` (the simulation stepped on from an earlier state).
  dropAfter(time) {
    let keep = this.columns[0].length;
    while (keep > 0 && this.columns[0][keep - 1] > time) keep--;
    for (const column of this.columns) column.length = keep;
  }

  clear() {
    for (const column of this.columns) column.length = 0;
  }

  dispose() {
    this.chart.destroy();
  }

  setWidth(width) {
    this.chart.setSize({ width, height: kHeight });
  }
}
