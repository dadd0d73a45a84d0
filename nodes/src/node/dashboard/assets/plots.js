// A hand-written canvas 2D plot of named time series over a sliding window: axes with ticks, one
// line per series, an optional horizontal reference line, and an HTML legend with each series'
// latest value. The canvas carries data-last-sample-ms and data-samples for tests.

const SERIES_COLORS = ['#5ab0ff', '#ffb74d', '#81e07a', '#f48fb1', '#fff176', '#b39ddb', '#4dd0e1', '#ff8a65'];
const AXIS_COLOR = '#8a94a3';
const GRID_COLOR = 'rgba(138, 148, 163, 0.18)';

// Round tick steps (1, 2, 5 times a power of ten) giving about `count` ticks over `span`.
function tickStep(span, count) {
  const raw = span / count;
  const power = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * power).find((step) => step >= raw);
}

const formatValue = (value) => (Math.abs(value) >= 100 ? value.toFixed(0) : Math.abs(value) >= 1 ? value.toFixed(1) : value.toPrecision(2));

export class TimeSeriesPlot {
  constructor(canvas, legend, { unit, windowS = 60 }) {
    this.canvas = canvas;
    this.legend = legend;
    this.unit = unit;
    this.windowMs = windowS * 1000;
    this.series = new Map(); // name -> {color, samples: [[tMs, value]], legendValue}
    this.reference = null; // {value, label}
    this.lastSampleMs = null;
  }

  push(name, tMs, value) {
    if (!Number.isFinite(value)) return;
    let series = this.series.get(name);
    if (!series) series = this.addSeries(name);
    series.samples.push([tMs, value]);
    series.legendValue.textContent = `${formatValue(value)} ${this.unit}`;
    this.lastSampleMs = tMs;
    this.canvas.dataset.lastSampleMs = String(tMs);
  }

  setReference(value, label) {
    this.reference = Number.isFinite(value) ? { value, label } : null;
  }

  addSeries(name) {
    const color = SERIES_COLORS[this.series.size % SERIES_COLORS.length];
    const item = document.createElement('span');
    item.className = 'legend-item';
    const swatch = document.createElement('i');
    swatch.style.background = color;
    const value = document.createElement('b');
    item.append(swatch, `${name} `, value);
    this.legend.append(item);
    const series = { color, samples: [], legendValue: value };
    this.series.set(name, series);
    return series;
  }

  // Drops samples that left the window and redraws at the canvas's on-screen size.
  draw(nowMs) {
    const start = nowMs - this.windowMs;
    let sampleCount = 0;
    for (const series of this.series.values()) {
      const firstKept = series.samples.findIndex(([t]) => t >= start);
      series.samples.splice(0, firstKept === -1 ? series.samples.length : firstKept);
      sampleCount += series.samples.length;
    }
    this.canvas.dataset.samples = String(sampleCount);
    const prepared = this.prepareCanvas();
    if (!prepared) return;
    const { context, width, height } = prepared;
    const frame = { left: 44, right: width - 8, top: 8, bottom: height - 20 };
    const range = this.valueRange();
    const x = (t) => frame.left + ((t - start) / this.windowMs) * (frame.right - frame.left);
    const y = (v) => frame.bottom - ((v - range.min) / (range.max - range.min)) * (frame.bottom - frame.top);
    this.drawAxes(context, frame, range, y);
    this.drawReference(context, frame, y);
    for (const series of this.series.values()) this.drawSeries(context, series, x, y);
  }

  // Sizes the backing store to the on-screen size; the returned context draws in CSS pixels.
  prepareCanvas() {
    const ratio = window.devicePixelRatio || 1;
    const width = this.canvas.clientWidth;
    const height = this.canvas.clientHeight;
    if (width === 0 || height === 0) return null; // panel collapsed
    const backingWidth = Math.round(width * ratio);
    const backingHeight = Math.round(height * ratio);
    if (this.canvas.width !== backingWidth || this.canvas.height !== backingHeight) {
      this.canvas.width = backingWidth;
      this.canvas.height = backingHeight;
    }
    const context = this.canvas.getContext('2d');
    context.setTransform(ratio, 0, 0, ratio, 0, 0);
    context.clearRect(0, 0, width, height);
    return { context, width, height };
  }

  // From zero (or the lowest sample, when negative) to a little above the highest.
  valueRange() {
    let min = 0;
    let max = this.reference ? this.reference.value : 0;
    for (const series of this.series.values()) {
      for (const [, v] of series.samples) {
        if (v < min) min = v;
        if (v > max) max = v;
      }
    }
    if (max - min < 1e-9) max = min + 1;
    return { min, max: max + (max - min) * 0.08 };
  }

  drawAxes(context, frame, range, y) {
    context.font = '10px system-ui, sans-serif';
    context.fillStyle = AXIS_COLOR;
    context.strokeStyle = GRID_COLOR;
    context.lineWidth = 1;
    context.textAlign = 'right';
    context.textBaseline = 'middle';
    const step = tickStep(range.max - range.min, 4);
    for (let v = Math.ceil(range.min / step) * step; v <= range.max; v += step) {
      const py = Math.round(y(v)) + 0.5;
      context.beginPath();
      context.moveTo(frame.left, py);
      context.lineTo(frame.right, py);
      context.stroke();
      context.fillText(formatValue(v), frame.left - 4, py);
    }
    context.textBaseline = 'top';
    const seconds = this.windowMs / 1000;
    for (let s = 0; s <= seconds; s += seconds / 4) {
      const px = frame.left + (s / seconds) * (frame.right - frame.left);
      context.textAlign = s === seconds ? 'right' : 'center';
      context.fillText(s === seconds ? 'now' : `-${seconds - s} s`, px, frame.bottom + 5);
    }
  }

  drawReference(context, frame, y) {
    if (!this.reference) return;
    const py = Math.round(y(this.reference.value)) + 0.5;
    context.save();
    context.strokeStyle = '#ff5252';
    context.setLineDash([4, 3]);
    context.beginPath();
    context.moveTo(frame.left, py);
    context.lineTo(frame.right, py);
    context.stroke();
    context.restore();
    context.fillStyle = '#ff8a80';
    context.textAlign = 'left';
    context.textBaseline = 'bottom';
    context.fillText(this.reference.label, frame.left + 4, py - 2);
  }

  drawSeries(context, series, x, y) {
    if (series.samples.length === 0) return;
    context.strokeStyle = series.color;
    context.lineWidth = 1.5;
    context.beginPath();
    series.samples.forEach(([t, v], i) => (i === 0 ? context.moveTo(x(t), y(v)) : context.lineTo(x(t), y(v))));
    context.stroke();
  }
}
