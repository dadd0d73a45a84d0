// The hooks the browser tests use (tests/browser/): window.__shroud.hello is the latest hello,
// and window.__shroud.snapshot(visible) draws
// the 3D view at once with the given layers and counts the pixels that differ from the
// background, so a test can tell that points and surfaces reach the screen. Reading the canvas
// right after drawing needs no preserveDrawingBuffer. It changes nothing the user sees.

import { BACKGROUND } from './scene/view.js';

const LIT_THRESHOLD = 12; // of 255, on any channel: antialiased edges of the background are not lit

function countLit(gl, width, height) {
  const pixels = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const background = BACKGROUND.map((c) => Math.round(c * 255));
  let lit = 0;
  for (let i = 0; i < pixels.length; i += 4) {
    if (Math.abs(pixels[i] - background[0]) > LIT_THRESHOLD || Math.abs(pixels[i + 1] - background[1]) > LIT_THRESHOLD ||
      Math.abs(pixels[i + 2] - background[2]) > LIT_THRESHOLD) lit++;
  }
  return lit;
}

// `latestHello()` is the current connection's hello, or null.
export function installTestHooks(view, latestHello) {
  window.__shroud = {
    get hello() {
      return latestHello();
    },
    // visible: {clouds, upper, lower, smooth, arm, axes} (missing layers are off).
    snapshot(visible) {
      if (!view) return { error: 'no WebGL2' };
      view.resize();
      view.draw({ ...visible });
      const litPixels = countLit(view.gl, view.canvas.width, view.canvas.height);
      view.requestDraw(); // back to the page's own toggles on the next frame
      return {
        width: view.canvas.width, height: view.canvas.height, litPixels,
        points: view.points.pointCounts(), blendSources: view.points.blendSourceCounts(), triangles: view.meshes.triangleCounts(), arms: view.arms.shapeCounts(),
      };
    },
  };
}
