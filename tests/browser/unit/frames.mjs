// Builds protocol frames (docs/dashboard-protocol.md, "Server to browser: binary frames") for the unit tests,
// written from the spec independently of the page's decoder, and a seeded random source.

const pad4 = (n) => (n + 3) & ~3;

// arrays: [[name, "f32" | "u32" | "u8", TypedArray]]; header gets its "arrays" list here.
export function encodeFrame(header, arrays = []) {
  const full = { ...header, arrays: arrays.map(([name, type, values]) => ({ name, type, count: values.length })) };
  const json = new TextEncoder().encode(JSON.stringify(full));
  let size = pad4(4 + json.length);
  const offsets = arrays.map(([, , values]) => {
    const offset = size;
    size = pad4(size + values.byteLength);
    return offset;
  });
  const bytes = new Uint8Array(size);
  new DataView(bytes.buffer).setUint32(0, json.length, true);
  bytes.set(json, 4);
  bytes.fill(0x20, 4 + json.length, pad4(4 + json.length));
  arrays.forEach(([, , values], i) => bytes.set(new Uint8Array(values.buffer, values.byteOffset, values.byteLength), offsets[i]));
  return bytes.buffer;
}

// mulberry32: a small seeded generator, so a failing case can be replayed from its seed.
export function random(seed) {
  let state = seed >>> 0;
  const next = () => {
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  return {
    next,
    int: (n) => Math.floor(next() * n),
    pick: (values) => values[Math.floor(next() * values.length)],
  };
}
