// screenshot: the whole page once it shows data (points on the canvas, the node list, a plot
// sample), as dashboard.png in --out, for the README.

import path from 'node:path';
import { waitForHello, waitForSnapshot, waitInPage } from '../lib/page.mjs';

const hasPoints = (s) => Object.values(s.points).some((n) => n > 0) && s.litPixels > 0;
const PLOT_HISTORY_MS = 5000; // let the plots draw a few seconds of lines

export async function run({ page, out, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  await waitForSnapshot(page, 'cloud points on the canvas', { clouds: true }, hasPoints, timeoutMs);
  await waitInPage(page, 'the node list', () => document.querySelector('#nodes-table tbody') !== null, undefined, timeoutMs);
  await page.waitForTimeout(PLOT_HISTORY_MS);
  const file = path.join(out, 'dashboard.png');
  await page.screenshot({ path: file, fullPage: true });
  return { file };
}
