// The colour key under the 3D view, built from the same colour tables the renderers use: the
// point colouring in force (height range, intensity, or each stream and blend source), surfaces
// and the arm's clearance bands.

import { BAND_COLORS, BLEND_SOURCE_COLORS, BLEND_SOURCE_NAMES, SURFACE_COLORS, cssColor } from './scene/colors.js';
import { fixed } from './format.js';

const BAND_LABELS = {
  stop: 'stop band', near: 'near (< 2× stop distance)', clear: 'clear', unobserved: 'unobserved',
  stopping: 'link that stops', unknown: 'no fresh verdict',
};

function swatch(color, label) {
  const item = document.createElement('span');
  item.className = 'legend-item';
  const box = document.createElement('i');
  box.style.background = color;
  item.append(box, label);
  return item;
}

// A colour ramp (drawn by the CSS class) with its label.
function ramp(className, label) {
  const item = document.createElement('span');
  item.className = 'legend-item';
  const box = document.createElement('i');
  box.className = className;
  item.append(box, label);
  return item;
}

export class Legend {
  constructor(element) {
    this.points = document.createElement('div');
    this.points.className = 'legend-row';
    const surfaces = document.createElement('div');
    surfaces.className = 'legend-row';
    surfaces.append(...Object.entries(SURFACE_COLORS).map(([kind, c]) => swatch(cssColor(c), `${kind} surface`)));
    const bands = document.createElement('div');
    bands.className = 'legend-row';
    bands.append(...Object.entries(BAND_LABELS).map(([band, label]) => swatch(cssColor(BAND_COLORS[band]), label)));
    element.append(this.points, surfaces, bands);
    this.shown = '';
  }

  // mode: the colour mode; streams: [{stream, color}]; heightRange: [zMin, zMax].
  update(mode, streams, heightRange) {
    const key = JSON.stringify([mode, streams, heightRange.map((z) => fixed(z, 2))]);
    if (key === this.shown) return;
    this.shown = key;
    const items = [];
    if (mode === 'height') {
      items.push(ramp('height-ramp', `height z ${fixed(heightRange[0], 2)} → ${fixed(heightRange[1], 2)} m`));
    } else if (mode === 'intensity') {
      items.push(ramp('intensity-ramp', 'intensity, low → high per cloud'));
    } else {
      streams.forEach(({ stream, color }) => items.push(swatch(cssColor(color), stream)));
      BLEND_SOURCE_NAMES.forEach((name, i) => items.push(swatch(cssColor(BLEND_SOURCE_COLORS[i]), `blend ${name}`)));
    }
    this.points.replaceChildren(...items);
  }
}
