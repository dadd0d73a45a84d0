// Checked reads of header fields and bulk arrays: each refuses a missing or mistyped value with a
// FrameError naming the message type and field, so a malformed frame is reported, never trusted.

import { FrameError } from './protocol.js';

const where = (header, name) => `${header.type}: field "${name}"`;

export function string(header, name) {
  const value = header[name];
  if (typeof value !== 'string') throw new FrameError(`${where(header, name)} is not a string`);
  return value;
}

export function optionalString(header, name, fallback = '') {
  return header[name] === undefined || header[name] === null ? fallback : string(header, name);
}

// A finite number, or `fallback` when the field is absent or null (the protocol's "no value").
export function optionalNumber(header, name, fallback = null) {
  const value = header[name];
  if (value === undefined || value === null) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value)) {
    throw new FrameError(`${where(header, name)} is ${JSON.stringify(value)}, not a finite number`);
  }
  return value;
}

export function number(header, name) {
  const value = optionalNumber(header, name);
  if (value === null) throw new FrameError(`${where(header, name)} is missing`);
  return value;
}

export function optionalBoolean(header, name, fallback) {
  const value = header[name];
  if (value === undefined || value === null) return fallback;
  if (typeof value !== 'boolean') throw new FrameError(`${where(header, name)} is not true or false`);
  return value;
}

export function list(header, name, fallback = []) {
  const value = header[name];
  if (value === undefined || value === null) return fallback;
  if (!Array.isArray(value)) throw new FrameError(`${where(header, name)} is not a list`);
  return value;
}

export function object(header, name, fallback = {}) {
  const value = header[name];
  if (value === undefined || value === null) return fallback;
  if (typeof value !== 'object' || Array.isArray(value)) {
    throw new FrameError(`${where(header, name)} is not an object`);
  }
  return value;
}

export function stringList(header, name) {
  const values = list(header, name);
  values.forEach((value, index) => {
    if (typeof value !== 'string') throw new FrameError(`${where(header, name)}[${index}] is not a string`);
  });
  return values;
}

// A fixed-length list of finite numbers, e.g. a direction [x, y, z]; null when absent.
export function vector(header, name, length) {
  const value = header[name];
  if (value === undefined || value === null) return null;
  const ok = Array.isArray(value) && value.length === length &&
    value.every((x) => typeof x === 'number' && Number.isFinite(x));
  if (!ok) throw new FrameError(`${where(header, name)} is not ${length} finite numbers`);
  return value;
}

// The bulk array `name` of element type `type`; its count must be a multiple of `stride`.
// Absent arrays read as empty when `optional`.
export function array(frame, name, type, { stride = 1, optional = false } = {}) {
  const values = frame.arrays.get(name);
  if (values === undefined) {
    if (optional) return emptyOf(type);
    throw new FrameError(`${frame.header.type}: array "${name}" is missing`);
  }
  const spec = frame.header.arrays.find((entry) => entry.name === name);
  if (spec.type !== type) throw new FrameError(`${frame.header.type}: array "${name}" is ${spec.type}, not ${type}`);
  if (values.length % stride !== 0) {
    throw new FrameError(`${frame.header.type}: array "${name}" has ${values.length} elements, not a multiple of ${stride}`);
  }
  return values;
}

function emptyOf(type) {
  return type === 'u32' ? new Uint32Array(0) : type === 'u8' ? new Uint8Array(0) : new Float32Array(0);
}

// Every index must name an existing element: WebGL refuses out-of-range indices, and a
// link index past the links list would colour nothing.
export function checkIndices(frame, name, indices, limit) {
  for (let i = 0; i < indices.length; i++) {
    if (indices[i] >= limit) {
      throw new FrameError(`${frame.header.type}: array "${name}"[${i}] = ${indices[i]} is not below ${limit}`);
    }
  }
}

// A nested JSON object (a list entry or sub-object) under `label`, for the reads above to name
// in their errors, e.g. "verdict links[2]: field "link" is not a string".
export function entry(value, label) {
  if (value === null || typeof value !== 'object' || Array.isArray(value)) {
    throw new FrameError(`${label} is not an object`);
  }
  return { ...value, type: label };
}
