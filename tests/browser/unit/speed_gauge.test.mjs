// Unit tests of the speed gauge's judgement (assets/speed_gauge.js): what each arm's row says for
// verdicts read from frames as the page reads them (protocol.js, messages.js), and that only a
// fresh clear moves the bar off 0.
// Run: node --test tests/browser/unit/

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { importAsset } from './assets.mjs';
import { encodeFrame } from './frames.mjs';

const { decodeFrame } = await importAsset('protocol.js');
const { readMessage } = await importAsset('messages.js');
const { percent, speedGaugeState } = await importAsset('speed_gauge.js');
const { VerdictBook } = await importAsset('verdicts.js');

const verdict = (fields) => readMessage(decodeFrame(encodeFrame({ type: 'verdict', arm: 'arm', ...fields }))).message;
const SCALED = { verdict: 'clear', stop: false, speed_scale: 0.42, limiting_link: 'forearm', protective_distance: 0.84 };

// A book that heard `fields` at time 0, for an arm the hello names.
function bookWith(fields) {
  const book = new VerdictBook();
  book.onHello({ arms: ['arm'], stopBannerAfterMs: 500 });
  if (fields) book.record(verdict(fields), 0);
  return book;
}

const rows = (book, nowMs = 100, socket = { socketOpen: true, helloReceived: true }) =>
  speedGaugeState({ ...socket, book, nowMs }).rows;

test('a scaled clear shows its percentage, the link that limits it and its S_p', () => {
  const [row] = rows(bookWith(SCALED));
  assert.deepEqual(row, {
    arm: 'arm', state: 'scaled', scale: 0.42, text: '42 % speed', detail: 'limited by forearm (S_p 0.840 m)',
  });
  const [rising] = rows(bookWith({ ...SCALED, speed_scale: 0.9, limiting_link: null }));
  assert.deepEqual([rising.state, rising.text, rising.detail], ['scaled', '90 % speed', 'rise-limited (speeding up)']);
  const [full] = rows(bookWith({ ...SCALED, speed_scale: 1, limiting_link: null, protective_distance: 0.05 }));
  assert.deepEqual([full.state, full.scale, full.text], ['full', 1, 'full speed']);
});

test('a stop, a stale verdict, no verdict and a closed socket are stopped at 0 %', () => {
  const stopped = (row) => assert.deepEqual([row.state, row.scale, row.text], ['stopped', 0, 'stopped'], JSON.stringify(row));
  const [stop] = rows(bookWith({ verdict: 'stop', stop: true, speed_scale: 0, limiting_link: 'tool' }));
  stopped(stop);
  assert.equal(stop.detail, 'verdict stop');
  const [stale] = rows(bookWith(SCALED), 1500);
  stopped(stale);
  assert.equal(stale.detail, 'no verdict for 1.5 s');
  const [none] = rows(bookWith(null));
  stopped(none);
  assert.equal(none.detail, 'no verdict yet');
  for (const socket of [{ socketOpen: false, helloReceived: true }, { socketOpen: true, helloReceived: false }]) {
    const state = speedGaugeState({ ...socket, book: bookWith(SCALED), nowMs: 100 });
    assert.equal(state.state, 'stopped');
    stopped(state.rows[0]);
  }
  const empty = new VerdictBook();
  assert.deepEqual(speedGaugeState({ socketOpen: true, helloReceived: true, book: empty, nowMs: 0 }), { state: 'none', rows: [] });
});

test('every arm has its own row', () => {
  const book = bookWith(SCALED);
  book.record({ ...verdict({ verdict: 'clear', speed_scale: 1 }), arm: 'other' }, 0);
  assert.deepEqual(rows(book).map((row) => [row.arm, row.state]), [['arm', 'scaled'], ['other', 'full']]);
});

test('percentages round down, so that a slowed arm never reads 100 %', () => {
  assert.deepEqual([0.999, 0.625, 0.29, 0.5, 0.004, 0, 1 - 1e-12, 1].map(percent),
    ['99 %', '62 %', '29 %', '50 %', '<1 %', '0 %', '99 %', '100 %']);
});
