// scene: the 3D view really draws. Renders the canvas with one layer at a time through
// window.__shroud.snapshot and counts pixels that differ from the background: nothing with every
// layer off, points with the clouds, surface pixels with the surfaces, arm pixels with the arm
// (when the hello names an arm), and more pixels with clouds and surfaces than clouds alone.

import { CheckFailed, snapshot, waitForHello, waitForSnapshot } from '../lib/page.mjs';

const hasPoints = (s) => Object.values(s.points).some((n) => n > 0) && s.litPixels > 0;
const hasSurfaces = (s) => Object.values(s.triangles).some((n) => n > 0) && s.litPixels > 0;
const hasArm = (s) => Object.keys(s.arms).length > 0 && s.litPixels > 0;

export async function run({ page, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  const clouds = await waitForSnapshot(page, 'cloud points on the canvas', { clouds: true }, hasPoints, timeoutMs);
  const surfaces = await waitForSnapshot(page, 'surrogate surfaces on the canvas', { upper: true, lower: true }, hasSurfaces, timeoutMs);
  const armsAnnounced = await page.evaluate(() => window.__shroud.hello?.arms.length ?? 0);
  const arm = armsAnnounced > 0
    ? await waitForSnapshot(page, 'the arm on the canvas', { arm: true }, hasArm, timeoutMs) : null;
  const nothing = await snapshot(page, {});
  const both = await snapshot(page, { clouds: true, upper: true, lower: true });
  const alone = await snapshot(page, { clouds: true });
  if (nothing.litPixels !== 0) throw new CheckFailed(`${nothing.litPixels} pixels lit with every layer off`);
  if (both.litPixels <= alone.litPixels) {
    throw new CheckFailed(`surfaces add no pixels: ${both.litPixels} lit with clouds and surfaces, ${alone.litPixels} with clouds alone`);
  }
  return {
    canvas: [both.width, both.height],
    lit_pixels: { clouds: clouds.litPixels, surfaces: surfaces.litPixels, arm: arm?.litPixels ?? null,
      clouds_and_surfaces: both.litPixels, clouds_alone: alone.litPixels, none: nothing.litPixels },
    points: both.points, triangles: both.triangles, arms: both.arms,
  };
}
