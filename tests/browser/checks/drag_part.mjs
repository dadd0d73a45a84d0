// drag_part: drags the first part of the Blending palette onto the 3D view's centre with an HTML5
// drag and drop, and waits for the node's blend_result; an error result fails. Then waits for the
// composed cloud (blend_sources) to come back and reports its parent, part and transition counts.

import { CheckFailed, waitForCloudsOnCanvas, waitForHello, waitForSnapshot, waitInPage } from '../lib/page.mjs';

export async function run({ page, timeoutMs }) {
  await waitForHello(page, timeoutMs);
  const blend = await page.evaluate(() => window.__shroud.hello?.blend ?? null);
  if (!blend) throw new CheckFailed('the hello names no blend stream: nothing to drag');
  await waitForCloudsOnCanvas(page, timeoutMs);
  await page.click('[data-view="reset"]'); // the clouds centred in the view
  const part = page.locator('#palette .part').first();
  const partName = await part.getAttribute('data-part');
  const canvas = page.locator('#scene');
  const box = await canvas.boundingBox();
  const target = { x: Math.round(box.width / 2), y: Math.round(box.height / 2) };
  await part.dragTo(canvas, { targetPosition: target });
  const result = await waitInPage(page, 'the blend_result of the drop', () => {
    const element = document.getElementById('blend-result');
    return ['ok', 'error'].includes(element.dataset.state) ? { state: element.dataset.state, text: element.textContent, id: element.dataset.id } : null;
  }, undefined, timeoutMs);
  if (result.state !== 'ok') throw new CheckFailed(`the drop failed: ${result.text}`);
  const composed = await waitForSnapshot(page, `a composed cloud with transition points on stream ${blend.stream}`, {},
    new Function('s', `return (s.blendSources[${JSON.stringify(blend.stream)}] || [0, 0, 0])[2] > 0;`), timeoutMs);
  const [parent, partPoints, transition] = composed.blendSources[blend.stream];
  return { part: partName, target, blend_result: result, composed: { stream: blend.stream, parent, part: partPoints, transition } };
}
