// GPU picking: WebGL2 cannot read a depth buffer back, so the clouds are drawn as point ids into an
// offscreen RGBA8 framebuffer (with its own depth buffer, nearest point wins) and the pixels
// around the cursor are read; the id nearest the cursor names the point under it.

const SEARCH_RADIUS_PX = 8; // points are sparse: look this far around the cursor, device pixels

export class Picker {
  constructor(gl) {
    this.gl = gl;
    this.framebuffer = gl.createFramebuffer();
    this.color = gl.createRenderbuffer();
    this.depth = gl.createRenderbuffer();
    this.width = 0;
    this.height = 0;
  }

  resize(width, height) {
    if (width === this.width && height === this.height) return;
    const { gl } = this;
    gl.bindRenderbuffer(gl.RENDERBUFFER, this.color);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, width, height);
    gl.bindRenderbuffer(gl.RENDERBUFFER, this.depth);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, width, height);
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, this.color);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, this.depth);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.width = width;
    this.height = height;
  }

  // Draws ids with `drawIds()` and returns {slot, index} of the point nearest the device pixel
  // (x, y) (origin top left), or null when no point is within SEARCH_RADIUS_PX.
  pick(x, y, drawIds) {
    const { gl } = this;
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
    gl.viewport(0, 0, this.width, this.height);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    drawIds();
    const glY = this.height - 1 - y;
    const left = Math.max(0, x - SEARCH_RADIUS_PX);
    const bottom = Math.max(0, glY - SEARCH_RADIUS_PX);
    const width = Math.min(this.width, x + SEARCH_RADIUS_PX + 1) - left;
    const height = Math.min(this.height, glY + SEARCH_RADIUS_PX + 1) - bottom;
    const pixels = new Uint8Array(Math.max(0, width * height * 4));
    if (width > 0 && height > 0) gl.readPixels(left, bottom, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return nearestId(pixels, width, x - left, glY - bottom);
  }
}

function nearestId(pixels, width, centreX, centreY) {
  let best = null;
  let bestDistance = Infinity;
  for (let i = 0; i < pixels.length; i += 4) {
    const id = pixels[i] | (pixels[i + 1] << 8) | (pixels[i + 2] << 16);
    if (id === 0) continue;
    const px = (i / 4) % width;
    const py = Math.floor(i / 4 / width);
    const distance = (px - centreX) ** 2 + (py - centreY) ** 2;
    if (distance < bestDistance) {
      bestDistance = distance;
      best = { slot: pixels[i + 3], index: id - 1 };
    }
  }
  return bestDistance <= SEARCH_RADIUS_PX ** 2 ? best : null;
}
