// The 3D view's colours in one place, so the legends in the page and the renderers agree.
// RGB components in 0..1.

// Streams coloured "by source" take these in order of arrival.
export const STREAM_COLORS = [
  [0.40, 0.76, 1.00], [1.00, 0.72, 0.30], [0.55, 0.90, 0.45], [0.95, 0.50, 0.85],
  [0.95, 0.90, 0.40], [0.55, 0.60, 1.00],
];

// A blend output cloud's intensity: 0 parent, 1 part, 2 transition (docs/dashboard-protocol.md, `cloud`).
export const BLEND_SOURCE_COLORS = [[0.55, 0.62, 0.72], [0.25, 0.80, 1.00], [1.00, 0.45, 0.15]];
export const BLEND_SOURCE_NAMES = ['parent', 'part', 'transition'];

export const SURFACE_COLORS = {
  upper: [1.00, 0.62, 0.25, 0.35],
  lower: [0.30, 0.60, 1.00, 0.35],
  smooth: [0.45, 0.95, 0.60, 0.45],
};

// Per-link clearance band of a verdict (docs/dashboard-protocol.md, `verdict`), plus the two the page adds:
// the link a stop names, and links of an arm with no verdict yet.
export const BAND_COLORS = {
  stop: [0.95, 0.22, 0.22],
  near: [1.00, 0.70, 0.15],
  clear: [0.25, 0.85, 0.45],
  unobserved: [0.62, 0.45, 0.95],
  stopping: [1.00, 0.10, 0.55],
  unknown: [0.55, 0.58, 0.62],
};

export const LINK_LINE_COLOR = [0.85, 0.88, 0.92];

export const cssColor = ([r, g, b]) => `rgb(${Math.round(r * 255)}, ${Math.round(g * 255)}, ${Math.round(b * 255)})`;
