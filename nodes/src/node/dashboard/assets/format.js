// Number formatting shared by the tables and banners: a dash for "no value".

export const DASH = '–';

export function fixed(value, digits) {
  return value === null || value === undefined ? DASH : value.toFixed(digits);
}

// A duration in seconds as "42 s", "3 min 20 s" or "2 h 5 min".
export function duration(seconds) {
  if (seconds === null || seconds === undefined) return DASH;
  if (seconds < 60) return `${seconds.toFixed(seconds < 10 ? 1 : 0)} s`;
  if (seconds < 3600) return `${Math.floor(seconds / 60)} min ${Math.floor(seconds % 60)} s`;
  return `${Math.floor(seconds / 3600)} h ${Math.floor((seconds % 3600) / 60)} min`;
}

// A gap or distance that may be tiny (certificates report 1e-15): exponent form below 1e-3.
export function metres(value) {
  if (value === null || value === undefined) return DASH;
  return value !== 0 && Math.abs(value) < 1e-3 ? value.toExponential(1) : value.toFixed(4);
}

export function count(value) {
  return value === null || value === undefined ? DASH : Math.round(value).toLocaleString('en-US');
}

// A table cell with `text`, and `className` when given.
export function cell(text, className) {
  const td = document.createElement('td');
  td.textContent = text;
  if (className) td.className = className;
  return td;
}
