// What the checks read from the dashboard page, through its DOM and its one test hook
// (window.__shroud.snapshot, nodes/src/node/dashboard/assets/test_hooks.js).

export class CheckFailed extends Error {}

// Waits for `predicate(arg)` to hold in the page; on timeout fails with `what`.
export async function waitInPage(page, what, predicate, arg, timeoutMs) {
  try {
    return await (await page.waitForFunction(predicate, arg, { timeout: timeoutMs, polling: 100 })).jsonValue();
  } catch (error) {
    if (error.name === 'TimeoutError') throw new CheckFailed(`timed out after ${timeoutMs} ms waiting for ${what}`);
    throw error;
  }
}

export function waitForHello(page, timeoutMs) {
  return waitInPage(page, 'the socket to open and the node\'s hello',
    () => document.body.dataset.hello === 'received' &&
      document.getElementById('connection').dataset.state === 'open', null, timeoutMs);
}

// Waits until a snapshot with layers `visible` satisfies `ready` (a function of the snapshot,
// sent to the page as source text); returns that snapshot.
export function waitForSnapshot(page, what, visible, ready, timeoutMs) {
  const expression = `(() => { const s = window.__shroud.snapshot(${JSON.stringify(visible)}); ` +
    `return (${ready.toString()})(s) ? s : null; })()`;
  return waitInPage(page, what, expression, undefined, timeoutMs);
}

// Waits for cloud points drawn on the canvas; returns that snapshot (clouds alone).
export function waitForCloudsOnCanvas(page, timeoutMs) {
  return waitForSnapshot(page, 'cloud points on the canvas', { clouds: true },
    (s) => Object.values(s.points).some((n) => n > 0) && s.litPixels > 0, timeoutMs);
}

export const snapshot = (page, visible) => page.evaluate((layers) => window.__shroud.snapshot(layers), visible);

export async function malformedFrames(page) {
  return page.evaluate(() => {
    const badge = document.getElementById('malformed');
    return badge.hidden ? null : { text: badge.textContent, last: badge.dataset.last };
  });
}
