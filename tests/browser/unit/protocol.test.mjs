// Property tests of the page's frame decoder and message readers (assets/protocol.js,
// fields.js, messages.js): valid frames read back exactly; truncated, corrupted, mistyped or
// absurd frames are refused with a FrameError naming the problem, never another exception.
// Run: node --test tests/browser/unit/

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { importAsset } from './assets.mjs';
import { encodeFrame, random } from './frames.mjs';

const { decodeFrame, FrameError } = await importAsset('protocol.js');
const { readMessage } = await importAsset('messages.js');

const f32 = (values) => new Float32Array(values);
const u32 = (values) => new Uint32Array(values);

// One valid frame of each message type the page reads.
const EXAMPLES = {
  hello: () => encodeFrame({ type: 'hello', protocol: 2, namespace: 'demo', node: 'dashboard', point_budget: 60000,
    blend: { stream: 'blend', parts: ['hemisphere', 'half-cylinder'] }, arms: ['demo_arm'], stop_banner_after_ms: 500 }),
  cloud: () => encodeFrame({ type: 'cloud', stream: 'spheres', sequence: 4, age_ms: 3.1, points_total: 9, points_sent: 3,
    intensity: true, blend_sources: true }, [['positions', 'f32', f32([0, 0, 0, 1, 1, 1, 2, 2, 2])], ['intensity', 'f32', f32([0, 1, 2])]]),
  surrogate: () => encodeFrame({ type: 'surrogate', stream: 'spheres', sequence: 4, fit_ms: 2.7, direction: [0, 0, -1],
    surfaces: [{ side: 'upper', certificate: { points_checked: 3, violations: 0, min_gap: 1e-15, max_gap: 1, mean_gap: 0.5 } }] },
  [['upper.positions', 'f32', f32([0, 0, 0, 1, 0, 0, 0, 1, 0])], ['upper.indices', 'u32', u32([0, 1, 2])]]),
  smooth: () => encodeFrame({ type: 'smooth', stream: 'terrain', kind: 'graph', fit_ms: 80 },
    [['positions', 'f32', f32([0, 0, 0, 1, 0, 0, 0, 1, 0])], ['indices', 'u32', u32([0, 1, 2])]]),
  arm: () => encodeFrame({ type: 'arm', arm: 'demo_arm', joints_sequence: 1, links: ['base', 'tip'] }, [
    ['link_origins', 'f32', f32([0, 0, 0, 0, 0, 1])], ['spheres', 'f32', f32([0, 0, 0, 0.1])], ['sphere_links', 'u32', u32([0])],
    ['capsules', 'f32', f32([0, 0, 0, 0, 0, 1, 0.05])], ['capsule_links', 'u32', u32([1])]]),
  verdict: () => encodeFrame({ type: 'verdict', arm: 'demo_arm', verdict: 'stop', stop: true, reason: 'link tip at 0.000 m',
    min_clearance: 0, closest_link: 'tip', stop_distance: 0.05, speed_scale: 0, limiting_link: 'tip', protective_distance: 0.14,
    links: [{ link: 'tip', clearance: 0, unobserved: false, band: 'stop' }] }),
  'verdict (scaled clear)': () => encodeFrame({ type: 'verdict', arm: 'demo_arm', verdict: 'clear', stop: false, reason: '',
    min_clearance: 0.6, closest_link: 'base', stop_distance: 0.05, speed_scale: 0.42, limiting_link: 'forearm',
    protective_distance: 0.84, links: [{ link: 'forearm', clearance: 0.9, unobserved: false, band: 'clear' }] }),
  nodes: () => encodeFrame({ type: 'nodes', uptime_s: 1, nodes: [{ name: 'fit', kind: 'fit', state: 'alive', pid: 7, uptime_s: 1,
    status_age_s: 0.2, restarts: 0, counters: { received: 3, dropped_backlog: 1 }, gauges: { fit_p50_ms: 2.1 } }],
  topics: [{ topic: 'cloud/spheres', rate_hz: 10 }], dashboard: { clients: 1 } }),
  blend_result: () => encodeFrame({ type: 'blend_result', id: 7, ok: false, error: 'the drop point is off the surface' }),
  error: () => encodeFrame({ type: 'error', message: 'not JSON' }),
};

// The message type of an example: its name up to the first space ("verdict (scaled clear)").
const typeOf = (name) => name.split(' ')[0];

// Decodes and reads; returns the message, or the FrameError. Anything else thrown fails the test.
function readOrRefuse(buffer, context) {
  try {
    return readMessage(decodeFrame(buffer));
  } catch (error) {
    if (!(error instanceof FrameError)) assert.fail(`${context}: ${error.name} escaped: ${error.message}`);
    return error;
  }
}

test('every example message reads', () => {
  for (const [type, make] of Object.entries(EXAMPLES)) {
    const read = readOrRefuse(make(), type);
    assert.ok(!(read instanceof FrameError), `${type}: ${read.message}`);
    assert.equal(read.type, typeOf(type));
  }
  const cloud = readMessage(decodeFrame(EXAMPLES.cloud())).message;
  assert.deepEqual([...cloud.positions], [0, 0, 0, 1, 1, 1, 2, 2, 2]);
  assert.equal(cloud.blendSources, true);
  const arm = readMessage(decodeFrame(EXAMPLES.arm())).message;
  assert.deepEqual([...arm.capsules.owners], [1]);
});

test('random valid frames decode to exactly the arrays encoded', () => {
  const rng = random(1);
  const makers = { f32: (n) => f32(Array.from({ length: n }, () => rng.next() * 2e6 - 1e6)),
    u32: (n) => u32(Array.from({ length: n }, () => rng.int(2 ** 32))), u8: (n) => new Uint8Array(Array.from({ length: n }, () => rng.int(256))) };
  for (let trial = 0; trial < 500; trial++) {
    const arrays = Array.from({ length: rng.int(5) }, (_, i) => {
      const type = rng.pick(['f32', 'u32', 'u8']);
      return [`a${i}`, type, makers[type](rng.int(40))];
    });
    const header = { type: 'x', note: 'é'.repeat(rng.int(7)) }; // multi-byte UTF-8 shifts the padding
    const frame = decodeFrame(encodeFrame(header, arrays));
    assert.equal(frame.header.note, header.note);
    for (const [name, , values] of arrays) assert.deepEqual([...frame.arrays.get(name)], [...values], `trial ${trial} ${name}`);
  }
});

test('truncated frames are refused with a FrameError, never read past their end', () => {
  for (const [type, make] of Object.entries(EXAMPLES)) {
    const full = make();
    const { header } = decodeFrame(full);
    const sizes = { f32: 4, u32: 4, u8: 1 };
    let dataEnd = 4 + new DataView(full).getUint32(0, true);
    for (const spec of header.arrays) dataEnd = ((dataEnd + 3) & ~3) + spec.count * sizes[spec.type];
    for (let cut = 0; cut < full.byteLength; cut++) {
      const read = readOrRefuse(full.slice(0, cut), `${type} cut at ${cut}`);
      if (cut < dataEnd) assert.ok(read instanceof FrameError, `${type} cut at ${cut} of ${dataEnd} bytes was accepted`);
    }
  }
});

test('corrupted bytes are either read or refused with a FrameError', () => {
  const rng = random(2);
  const types = Object.keys(EXAMPLES);
  for (let trial = 0; trial < 4000; trial++) {
    const bytes = new Uint8Array(EXAMPLES[rng.pick(types)]());
    for (let flips = 1 + rng.int(4); flips > 0; flips--) bytes[rng.int(bytes.length)] = rng.int(256);
    readOrRefuse(bytes.buffer, `trial ${trial}`);
  }
});

test('mistyped fields are refused naming the field, or ignored when the page does not use them', () => {
  const wrong = [null, 'text', -1, 1.5, 2 ** 53, true, [], [1, 2], {}, { nested: [] }];
  for (const [type, make] of Object.entries(EXAMPLES)) {
    const { header, arrays } = decodeFrame(make());
    const arrayList = header.arrays.map((spec) => [spec.name, spec.type, arrays.get(spec.name)]);
    for (const field of Object.keys(header).filter((name) => name !== 'arrays' && name !== 'type')) {
      for (const value of wrong) {
        const read = readOrRefuse(encodeFrame({ ...header, [field]: value }, arrayList), `${type}.${field} = ${JSON.stringify(value)}`);
        if (read instanceof FrameError) assert.match(read.message, new RegExp(`${typeOf(type)}|${field}`), read.message);
      }
    }
  }
});

test('a wrongly typed field names itself', () => {
  const cases = [
    [{ type: 'cloud', stream: 5 }, [['positions', 'f32', f32([0, 0, 0])]], /cloud: field "stream" is not a string/],
    [{ type: 'cloud', stream: 's' }, [['positions', 'f32', f32([0, 0])]], /"positions" has 2 elements, not a multiple of 3/],
    [{ type: 'cloud', stream: 's' }, [['positions', 'u32', u32([0, 0, 0])]], /"positions" is u32, not f32/],
    [{ type: 'cloud', stream: 's', intensity: true }, [['positions', 'f32', f32([0, 0, 0])]], /array "intensity" is missing/],
    [{ type: 'verdict', arm: 'a', verdict: 'clear', speed_scale: 1, links: [{ link: 3 }] }, [], /verdict links\[0\]: field "link" is not a string/],
    [{ type: 'nodes', nodes: [{ name: 'fit', pid: 'x' }] }, [], /nodes nodes\[0\]: field "pid"/],
    [{ type: 'smooth', stream: 's' }, [['positions', 'f32', f32([0, 0, 0])], ['indices', 'u32', u32([0, 0, 1])]], /"indices"\[2\] = 1 is not below 1/],
    [{ type: 'arm', arm: 'a', links: ['one'] }, [['spheres', 'f32', f32([0, 0, 0, 1])], ['sphere_links', 'u32', u32([1])]], /"sphere_links"\[0\] = 1 is not below 1/],
    [{ type: 'arm', arm: 'a', links: ['one'] }, [['spheres', 'f32', f32([0, 0, 0, 1])]], /1 spheres but 0 sphere_links/],
  ];
  for (const [header, arrays, expected] of cases) {
    const read = readOrRefuse(encodeFrame(header, arrays), JSON.stringify(header));
    assert.ok(read instanceof FrameError, `${JSON.stringify(header)} was accepted`);
    assert.match(read.message, expected);
  }
});

test('absurd lengths are refused before anything is allocated', () => {
  const header = new TextEncoder().encode(JSON.stringify({ type: 'cloud', arrays: [{ name: 'positions', type: 'f32', count: 2 ** 40 }] }));
  const bytes = new Uint8Array(4 + header.length + 8);
  new DataView(bytes.buffer).setUint32(0, header.length, true);
  bytes.set(header, 4);
  assert.throws(() => decodeFrame(bytes.buffer), /array "positions" \(1099511627776 x f32\) at offset \d+ runs past the frame's \d+ bytes/);
  const huge = new Uint8Array(8);
  new DataView(huge.buffer).setUint32(0, 0xffffffff, true);
  assert.throws(() => decodeFrame(huge.buffer), /header length 4294967295 at offset 0 runs past the frame's 8 bytes/);
  assert.throws(() => decodeFrame(encodeFrame({ type: 'x' }, [['a', 'f32', f32([1])], ['a', 'f32', f32([1])]])), /array "a" appears twice/);
  const negative = new TextEncoder().encode(JSON.stringify({ type: 'x', arrays: [{ name: 'a', type: 'f32', count: -1 }] }));
  const frame = new Uint8Array(4 + negative.length);
  new DataView(frame.buffer).setUint32(0, negative.length, true);
  frame.set(negative, 4);
  assert.throws(() => decodeFrame(frame.buffer), /arrays\[0\] \("a"\) has count -1, not a count/);
});

test('unknown types and unknown fields are ignored', () => {
  assert.equal(readMessage(decodeFrame(encodeFrame({ type: 'from_the_future', x: 1 }))), null);
  const { header } = decodeFrame(EXAMPLES.verdict());
  const read = readMessage(decodeFrame(encodeFrame({ ...header, new_field: { deep: [1] } })));
  assert.equal(read.message.verdict, 'stop');
});

test('a verdict the page does not know, or a clear that says stop, is not clear', () => {
  const verdict = (fields) => readMessage(decodeFrame(encodeFrame({ type: 'verdict', arm: 'a', ...fields }))).message;
  assert.equal(verdict({ verdict: 'maybe', stop: false }).stop, true);
  assert.equal(verdict({ verdict: 'clear', stop: true }).stop, true);
  assert.equal(verdict({ verdict: 'clear', speed_scale: 1 }).stop, false);
});

test('a verdict carries its speed scale, the link that limits it and its S_p', () => {
  const scaled = readMessage(decodeFrame(EXAMPLES['verdict (scaled clear)']())).message;
  assert.deepEqual([scaled.stop, scaled.speedScale, scaled.limitingLink, scaled.protectiveDistance], [false, 0.42, 'forearm', 0.84]);
  const stop = readMessage(decodeFrame(EXAMPLES.verdict())).message;
  assert.deepEqual([stop.stop, stop.speedScale, stop.limitingLink], [true, 0, 'tip']);
  // A stop without the fields moves at 0; a silent guard's numbers travel as null.
  const verdict = (fields) => readMessage(decodeFrame(encodeFrame({ type: 'verdict', arm: 'a', ...fields }))).message;
  const bare = verdict({ verdict: 'no-verdict', stop: true, limiting_link: null, protective_distance: null });
  assert.deepEqual([bare.speedScale, bare.limitingLink, bare.protectiveDistance], [0, '', null]);
  assert.equal(verdict({ verdict: 'clear', speed_scale: 1 }).speedScale, 1);
  assert.equal(verdict({ verdict: 'clear', speed_scale: Number.MIN_VALUE }).speedScale, Number.MIN_VALUE);
});

test('a speed scale out of range or against its verdict, or a negative S_p, is refused by name', () => {
  const cases = [
    [{ verdict: 'clear' }, /verdict: field "speed_scale" is missing/],
    [{ verdict: 'clear', speed_scale: null }, /verdict: field "speed_scale" is missing/],
    [{ verdict: 'clear', speed_scale: 0 }, /verdict: field "speed_scale" is 0, not in \(0, 1\] for a clear/],
    [{ verdict: 'clear', speed_scale: 1.5 }, /verdict: field "speed_scale" is 1.5, not in \(0, 1\] for a clear/],
    [{ verdict: 'clear', speed_scale: -0.25 }, /field "speed_scale" is -0.25/],
    [{ verdict: 'clear', speed_scale: '0.5' }, /verdict: field "speed_scale" is "0.5", not a finite number/],
    [{ verdict: 'stop', stop: true, speed_scale: 0.5 }, /verdict: field "speed_scale" is 0.5 with a stop, not 0/],
    [{ verdict: 'clear', stop: true, speed_scale: 1 }, /field "speed_scale" is 1 with a stop/],
    [{ verdict: 'stale', speed_scale: -1 }, /field "speed_scale" is -1 with a stop/],
    [{ verdict: 'clear', speed_scale: 0.5, protective_distance: -0.01 }, /verdict: field "protective_distance" is -0.01, not a distance >= 0/],
    [{ verdict: 'clear', speed_scale: 0.5, limiting_link: 3 }, /verdict: field "limiting_link" is not a string/],
  ];
  for (const [fields, expected] of cases) {
    const read = readOrRefuse(encodeFrame({ type: 'verdict', arm: 'a', ...fields }), JSON.stringify(fields));
    assert.ok(read instanceof FrameError, `${JSON.stringify(fields)} was accepted`);
    assert.match(read.message, expected);
  }
});
