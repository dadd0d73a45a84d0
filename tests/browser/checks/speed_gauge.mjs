// speed_gauge: waits for the speed gauge beside the STOP banner to show an arm moving below full
// speed (a row in state "scaled", after the hello, on an open socket) whose text contains --expect,
// and reports that row: its arm, state, scale, text and how much of the bar is filled (0 to 1).

import { waitForHello, waitInPage } from '../lib/page.mjs';

export async function run({ page, options, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  const expect = options.expect ?? '';
  const what = `the speed gauge below full speed${expect ? ` saying "${expect}"` : ''}`;
  return waitInPage(page, what, (needle) => {
    if (document.getElementById('connection').dataset.state !== 'open') return null;
    const rows = [...document.querySelectorAll('#speed-gauge .gauge-row')];
    const row = rows.find((r) => r.dataset.state === 'scaled' && r.innerText.includes(needle));
    if (!row) return null;
    const bar = row.querySelector('.gauge-bar');
    const fill = row.querySelector('.gauge-fill');
    return {
      arm: row.dataset.arm,
      state: row.dataset.state,
      scale: Number(row.dataset.scale),
      text: row.innerText.replace(/\s+/g, ' ').trim(),
      filled: fill.getBoundingClientRect().width / bar.clientWidth,
      banner: document.getElementById('stop-banner').dataset.state,
    };
  }, expect, timeoutMs);
}
