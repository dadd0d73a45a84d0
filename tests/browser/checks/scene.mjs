// scene: the 3D view really draws. Renders the canvas with one layer at a time through
// window.__shroud.snapshot and counts pixels that differ from the background: nothing with every
// layer off, points with the clouds, surface pixels with the surfaces, arm pixels with the arm
// (when the hello names an arm), and more pixels with clouds and surfaces than clouds alone.
// Then loses and restores the WebGL context (WEBGL_lose_context) and waits for the points again.

import { CheckFailed, snapshot, waitForCloudsOnCanvas, waitForHello, waitForSnapshot } from '../lib/page.mjs';
const hasSurfaces = (s) => Object.values(s.triangles).some((n) => n > 0) && s.litPixels > 0;
const hasArm = (s) => Object.keys(s.arms).length > 0 && s.litPixels > 0;

async function loseAndRestoreContext(page, timeoutMs) {
  await page.evaluate(() => new Promise((resolve) => {
    const canvas = document.getElementById('scene');
    const extension = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    canvas.addEventListener('webglcontextlost', () => setTimeout(() => extension.restoreContext(), 100), { once: true });
    canvas.addEventListener('webglcontextrestored', () => resolve(), { once: true });
    extension.loseContext();
  }));
  return waitForSnapshot(page, 'cloud points on the canvas after the context was restored', { clouds: true, upper: true, lower: true },
    (s) => Object.values(s.points).some((n) => n > 0) && Object.values(s.triangles).some((n) => n > 0) && s.litPixels > 0, timeoutMs);
}

export async function run({ page, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  const clouds = await waitForCloudsOnCanvas(page, timeoutMs);
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
  const restored = await loseAndRestoreContext(page, timeoutMs);
  return {
    canvas: [both.width, both.height], lit_pixels_after_context_restored: restored.litPixels,
    lit_pixels: { clouds: clouds.litPixels, surfaces: surfaces.litPixels, arm: arm?.litPixels ?? null,
      clouds_and_surfaces: both.litPixels, clouds_alone: alone.litPixels, none: nothing.litPixels },
    points: both.points, triangles: both.triangles, arms: both.arms,
  };
}
