// screenshot: waits until the page shows data (points on the canvas, the node list, a few
// seconds of plot lines); the full-page PNG every check leaves in --out (here screenshot.png, at
// 1600 x 1000) is then the README's picture (copy it to docs/images/dashboard.png).

import { waitForCloudsOnCanvas, waitForHello, waitInPage } from '../lib/page.mjs';
const PLOT_HISTORY_MS = 5000; // let the plots draw a few seconds of lines

export async function run({ page, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  await waitForCloudsOnCanvas(page, timeoutMs);
  await waitInPage(page, 'the node list', () => document.querySelector('#nodes-table tbody') !== null, undefined, timeoutMs);
  await page.waitForTimeout(PLOT_HISTORY_MS);
  return {};
}
