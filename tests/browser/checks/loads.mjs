// loads: the page loads without console errors, warnings, page errors or failed requests; the
// WebSocket connects; the hello arrives; frames then flow and none of them is malformed.

import { CheckFailed, malformedFrames, waitForHello, waitInPage } from '../lib/page.mjs';

const FRAMES_TO_SEE = 20;
const SETTLE_MS = 1500; // let late console messages (from drawing the first frames) arrive

export async function run({ page, problems, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  await waitInPage(page, `${FRAMES_TO_SEE} frames and a node list`, (n) =>
    Number((document.getElementById('frames').textContent.match(/^[\d,]+/) || ['0'])[0].replace(/,/g, '')) >= n &&
    document.querySelector('#nodes-table tbody') !== null, FRAMES_TO_SEE, timeoutMs);
  await page.waitForTimeout(SETTLE_MS);
  const malformed = await malformedFrames(page);
  if (malformed) throw new CheckFailed(`the page counted malformed frames: ${malformed.text}, last: ${malformed.last}`);
  if (problems.length > 0) throw new CheckFailed(`the page reported ${problems.length} problem(s): ${problems.join(' | ')}`);
  const frames = await page.textContent('#frames');
  return { connected: true, hello: true, frames };
}
