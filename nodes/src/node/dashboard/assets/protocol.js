// Splits one binary frame of the dashboard protocol (docs/dashboard-protocol.md, "Server to browser: binary
// frames") into its JSON header and typed-array views of its bulk arrays, without copying.
// Every way a frame can be malformed is a FrameError naming the field or byte offset at fault.

export class FrameError extends Error {}

// The protocol version this page speaks (the hello's "protocol"); version 2 added the verdict's
// speed_scale, limiting_link and protective_distance.
export const PROTOCOL_VERSION = 2;

const ELEMENT_TYPES = {
  f32: { view: Float32Array, bytes: 4 },
  u32: { view: Uint32Array, bytes: 4 },
  u8: { view: Uint8Array, bytes: 1 },
};

// Typed arrays read in the machine's byte order; the protocol is little-endian.
const MACHINE_IS_LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

const utf8 = new TextDecoder('utf-8', { fatal: true });

const alignTo4 = (offset) => (offset + 3) & ~3;

function readHeader(buffer) {
  if (buffer.byteLength < 4) {
    throw new FrameError(`frame of ${buffer.byteLength} bytes has no 4-byte header length`);
  }
  const headerLength = new DataView(buffer).getUint32(0, true);
  if (headerLength > buffer.byteLength - 4) {
    throw new FrameError(
      `header length ${headerLength} at offset 0 runs past the frame's ${buffer.byteLength} bytes`);
  }
  let header;
  try {
    header = JSON.parse(utf8.decode(new Uint8Array(buffer, 4, headerLength)));
  } catch (error) {
    throw new FrameError(`header at offset 4 is not UTF-8 JSON (${error.message})`);
  }
  if (header === null || typeof header !== 'object' || Array.isArray(header)) {
    throw new FrameError('header is not a JSON object');
  }
  if (typeof header.type !== 'string') {
    throw new FrameError('header has no "type" string');
  }
  return { header, bodyOffset: alignTo4(4 + headerLength) };
}

function readArraySpec(spec, index) {
  const where = `arrays[${index}]`;
  if (spec === null || typeof spec !== 'object') throw new FrameError(`${where} is not an object`);
  if (typeof spec.name !== 'string') throw new FrameError(`${where} has no "name" string`);
  const element = ELEMENT_TYPES[spec.type];
  if (!element) throw new FrameError(`${where} ("${spec.name}") has unknown type ${JSON.stringify(spec.type)}`);
  if (!Number.isSafeInteger(spec.count) || spec.count < 0) {
    throw new FrameError(`${where} ("${spec.name}") has count ${JSON.stringify(spec.count)}, not a count`);
  }
  return { name: spec.name, element, count: spec.count };
}

// Returns {header, arrays}: arrays maps each name to a typed array over `buffer`.
export function decodeFrame(buffer) {
  if (!(buffer instanceof ArrayBuffer)) throw new FrameError('a text frame: the server sends binary frames');
  if (!MACHINE_IS_LITTLE_ENDIAN) throw new FrameError('this machine is big-endian; the protocol is little-endian');
  const { header, bodyOffset } = readHeader(buffer);
  const specs = header.arrays === undefined ? [] : header.arrays;
  if (!Array.isArray(specs)) throw new FrameError('"arrays" is not a list');
  const arrays = new Map();
  let offset = bodyOffset;
  specs.forEach((rawSpec, index) => {
    const { name, element, count } = readArraySpec(rawSpec, index);
    const end = offset + count * element.bytes;
    if (end > buffer.byteLength) {
      throw new FrameError(`array "${name}" (${count} x ${rawSpec.type}) at offset ${offset} ` +
        `runs past the frame's ${buffer.byteLength} bytes`);
    }
    if (arrays.has(name)) throw new FrameError(`array "${name}" appears twice`);
    arrays.set(name, new element.view(buffer, offset, count));
    offset = alignTo4(end);
  });
  return { header, arrays };
}
