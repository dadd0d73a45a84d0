// node_dies: the row of node --node turns red (state gone or silent, painted in a red
// background). Reports the time from the kill to the red row. The kill time comes from
// --killed-at-ms, or, without it, the check first waits for the row to be alive, prints
// "ready <node>" on stderr and reads the kill time (ms since the Unix epoch) from stdin.

import readline from 'node:readline';
import { CheckFailed, waitForHello, waitInPage } from '../lib/page.mjs';

// The row is red when its computed background is red: the CSS, not just the class, is checked.
function rowIsRed(name) {
  const row = document.querySelector(`#nodes-table tbody[data-node="${CSS.escape(name)}"]`);
  if (!row) return null;
  const [r, g, b] = getComputedStyle(row).backgroundColor.match(/\d+/g).map(Number);
  const red = r >= 80 && r > 2 * g && r > 2 * b;
  return red && ['gone', 'silent'].includes(row.dataset.state) ? { state: row.dataset.state, seen_at_ms: Date.now() } : null;
}

async function killTimeFromStdin(page, node, timeoutMs) {
  await waitInPage(page, `node ${node} alive in the table`, (name) =>
    document.querySelector(`#nodes-table tbody[data-node="${CSS.escape(name)}"]`)?.dataset.state === 'alive', node, timeoutMs);
  process.stderr.write(`ready ${node}\n`);
  const lines = readline.createInterface({ input: process.stdin });
  const line = await new Promise((resolve, reject) => {
    lines.once('line', resolve);
    lines.once('close', () => reject(new CheckFailed('stdin closed before the kill time arrived')));
  });
  lines.close();
  const killedAtMs = Number(line.trim());
  if (!Number.isFinite(killedAtMs)) throw new CheckFailed(`kill time on stdin is ${JSON.stringify(line)}, not a number`);
  return killedAtMs;
}

export async function run({ page, options, timeoutMs }) {
  const node = options.node;
  if (!node) throw new CheckFailed('node_dies needs --node NAME');
  await waitForHello(page, timeoutMs);
  const killedAtMs = options['killed-at-ms'] ?? await killTimeFromStdin(page, node, timeoutMs);
  const red = await waitInPage(page, `the row of node ${node} to turn red`, rowIsRed, node, timeoutMs);
  return { node, state: red.state, killed_at_ms: killedAtMs, red_at_ms: red.seen_at_ms, elapsed_ms: red.seen_at_ms - killedAtMs };
}
