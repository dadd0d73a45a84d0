// The 3D view: owns the WebGL2 context, the camera and the renderers; takes the latest messages
// from the socket handler, uploads them on the next animation frame (unless paused) and redraws
// only when something changed.

import { ArmRenderer } from './arm.js';
import { OrbitCamera } from './camera.js';
import { LineRenderer, axes } from './lines.js';
import { MeshRenderer } from './meshes.js';
import { Picker } from './picking.js';
import { PointRenderer } from './points.js';

export const BACKGROUND = [0.06, 0.075, 0.095];
const SURROGATE_SIDES = ['upper', 'lower'];
const MAX_DEVICE_PIXEL_RATIO = 2;

const union = (a, b) => ({
  min: a.min.map((value, axis) => Math.min(value, b.min[axis])),
  max: a.max.map((value, axis) => Math.max(value, b.max[axis])),
});

export class SceneView {
  // `freshVerdict(arm)` is the arm's latest verdict while it is fresh, else null.
  constructor(canvas, { freshVerdict }) {
    const gl = canvas.getContext('webgl2', { antialias: true });
    if (!gl) throw new Error('this browser has no WebGL2: the 3D view is off, the panels work');
    this.gl = gl;
    this.canvas = canvas;
    this.freshVerdict = freshVerdict;
    this.camera = new OrbitCamera();
    this.createRenderers();
    this.options = {
      pointSize: 2, colorMode: 'height', paused: false,
      visible: { clouds: true, upper: true, lower: true, smooth: true, arm: true, axes: true },
    };
    this.pending = { clouds: new Map(), surrogates: new Map(), smooths: new Map(), arms: new Map() };
    this.shown = { clouds: new Map(), surrogates: new Map(), smooths: new Map() }; // uploaded, by stream
    this.armMessages = new Map();
    this.armFreshness = new Map(); // arm -> whether its colours were made from a fresh verdict
    this.fittedBounds = null; // the box the camera was last fitted to
    this.followData = true; // refit when the data outgrow that box, until the user moves the camera
    this.needsDraw = true;
    this.inFlight = null; // fence after the last frame drawn
    this.contextLost = false;
    new ResizeObserver(() => this.requestDraw()).observe(canvas);
    canvas.addEventListener('webglcontextlost', (event) => this.onContextLost(event));
    canvas.addEventListener('webglcontextrestored', () => this.onContextRestored());
  }

  // Every GL object lives in these; a restored context needs them all anew.
  createRenderers() {
    const { gl } = this;
    this.points = new PointRenderer(gl);
    this.meshes = new MeshRenderer(gl);
    this.arms = new ArmRenderer(gl);
    this.lines = new LineRenderer(gl);
    this.picker = new Picker(gl);
    this.axes = axes(gl, 0.25);
  }

  // preventDefault asks the browser to restore the context (a GPU reset, a driver update).
  onContextLost(event) {
    event.preventDefault();
    this.contextLost = true;
    this.inFlight = null;
  }

  // Rebuilds the renderers and uploads the latest of everything again (unless newer is pending).
  onContextRestored() {
    this.contextLost = false;
    this.createRenderers();
    for (const kind of ['clouds', 'surrogates', 'smooths']) {
      for (const [key, message] of this.shown[kind]) if (!this.pending[kind].has(key)) this.pending[kind].set(key, message);
    }
    for (const [name, arm] of this.armMessages) if (!this.pending.arms.has(name)) this.pending.arms.set(name, arm);
    this.requestDraw();
  }

  setCloud(cloud) { this.pending.clouds.set(cloud.stream, cloud); }
  setSurrogate(surrogate) { this.pending.surrogates.set(surrogate.stream, surrogate); }
  setSmooth(smooth) { this.pending.smooths.set(smooth.stream, smooth); }
  setArm(arm) { this.pending.arms.set(arm.arm, arm); }
  verdictArrived(armName) {
    const arm = this.armMessages.get(armName);
    if (arm && !this.pending.arms.has(armName)) this.pending.arms.set(armName, arm);
  }

  requestDraw() { this.needsDraw = true; }

  setOption(name, value) {
    this.options[name] = value;
    this.requestDraw();
  }

  setVisible(layer, on) {
    this.options.visible[layer] = on;
    this.requestDraw();
  }

  // "reset" also re-centres on the data; "top", "front" and "side" turn about the same target.
  setView(name) {
    this.camera.setView(name);
    if (name === 'reset') {
      this.followData = true;
      this.fitToData();
    }
    this.requestDraw();
  }

  // The user orbits, pans or zooms: the camera is theirs until the next reset.
  cameraMovedByUser() {
    this.followData = false;
    this.requestDraw();
  }

  fitToData() {
    const bounds = this.points.bounds();
    if (bounds) this.fitTo(bounds);
  }

  fitTo(bounds) {
    this.camera.fit(bounds.min, bounds.max);
    this.fittedBounds = bounds;
  }

  // True when `bounds` reach out of the fitted box by more than a tenth of its size: the view
  // follows a scene that grows (a second stream arrives) but not each move of a moving object.
  outgrowsFit(bounds) {
    const fitted = this.fittedBounds;
    if (!fitted) return true;
    const slack = 0.1 * Math.max(...fitted.max.map((max, axis) => max - fitted.min[axis]));
    return bounds.min.some((min, axis) => min < fitted.min[axis] - slack) ||
      bounds.max.some((max, axis) => max > fitted.max[axis] + slack);
  }

  start() {
    const frame = () => {
      if (!this.contextLost && this.gpuIsIdle()) {
        this.uploadPending();
        this.recolourArmsWhoseVerdictAged();
        if (this.resize() || this.needsDraw) {
          this.draw();
          this.inFlight = this.gl.fenceSync(this.gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
        }
      }
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }

  // At most one frame in flight: while the GPU (or a software rasteriser) still draws the last
  // one, uploading and drawing more would block this thread on a full command buffer and delay
  // the socket's messages, the banner's clock among them. The fence is polled, never waited on.
  gpuIsIdle() {
    const { gl } = this;
    if (!this.inFlight) return true;
    if (gl.getSyncParameter(this.inFlight, gl.SYNC_STATUS) !== gl.SIGNALED) return false;
    gl.deleteSync(this.inFlight);
    this.inFlight = null;
    return true;
  }

  uploadPending() {
    if (this.options.paused) return;
    const { clouds, surrogates, smooths, arms } = this.pending;
    for (const cloud of clouds.values()) this.points.upload(cloud);
    for (const s of surrogates.values()) {
      const meshes = Object.fromEntries(s.surfaces.map((surface) => [surface.side, surface.mesh]));
      this.meshes.upload(s.stream, SURROGATE_SIDES, meshes);
    }
    for (const s of smooths.values()) this.meshes.upload(s.stream, ['smooth'], { smooth: s.mesh });
    for (const arm of arms.values()) this.uploadArm(arm);
    if (clouds.size + surrogates.size + smooths.size + arms.size > 0) this.requestDraw();
    if (this.followData && clouds.size > 0) {
      const bounds = this.points.bounds();
      if (bounds && this.outgrowsFit(bounds)) this.fitTo(this.fittedBounds ? union(this.fittedBounds, bounds) : bounds);
    }
    for (const kind of ['clouds', 'surrogates', 'smooths']) {
      for (const [key, message] of this.pending[kind]) this.shown[kind].set(key, message);
      this.pending[kind].clear();
    }
    arms.clear();
  }

  uploadArm(arm) {
    const verdict = this.freshVerdict(arm.arm);
    this.arms.upload(arm, verdict);
    this.armMessages.set(arm.arm, arm);
    this.armFreshness.set(arm.arm, verdict !== null);
  }

  // A verdict that goes stale turns its arm grey even when no new message arrives.
  recolourArmsWhoseVerdictAged() {
    if (this.options.paused) return;
    for (const [name, wasFresh] of this.armFreshness) {
      if (wasFresh && this.freshVerdict(name) === null) {
        this.uploadArm(this.armMessages.get(name));
        this.requestDraw();
      }
    }
  }

  // Matches the drawing buffer to the canvas's size on screen; true when it changed.
  resize() {
    const ratio = Math.min(window.devicePixelRatio || 1, MAX_DEVICE_PIXEL_RATIO);
    const width = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
    if (width === this.canvas.width && height === this.canvas.height) return false;
    this.canvas.width = width;
    this.canvas.height = height;
    return true;
  }

  viewProjection() {
    return this.camera.viewProjection(this.canvas.width / this.canvas.height);
  }

  devicePointSize() {
    return this.options.pointSize * Math.min(window.devicePixelRatio || 1, MAX_DEVICE_PIXEL_RATIO);
  }

  // Draws the scene with `visible` (default: the page's toggles).
  draw(visible = this.options.visible) {
    const { gl } = this;
    this.needsDraw = false;
    const viewProjection = this.viewProjection();
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(...BACKGROUND, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    if (visible.axes) this.lines.draw(viewProjection, this.axes);
    if (visible.clouds) {
      this.points.draw(viewProjection, { pointSize: this.devicePointSize(), colorMode: this.options.colorMode });
    }
    if (visible.arm) this.arms.draw(viewProjection);
    this.meshes.draw(viewProjection, visible); // transparent: after the opaque layers
    if (visible.arm) this.lines.draw(viewProjection, this.arms.chains(), { onTop: true });
  }

  // The cloud point under the CSS pixel (clientX, clientY), as {stream, position}, or null.
  pickPoint(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    const x = Math.round(((clientX - rect.left) / rect.width) * this.canvas.width);
    const y = Math.round(((clientY - rect.top) / rect.height) * this.canvas.height);
    if (x < 0 || y < 0 || x >= this.canvas.width || y >= this.canvas.height) return null;
    this.picker.resize(this.canvas.width, this.canvas.height);
    const viewProjection = this.viewProjection();
    const hit = this.picker.pick(x, y, () => this.points.drawIds(viewProjection, Math.max(3, this.devicePointSize())));
    this.requestDraw();
    return hit && this.points.point(hit.slot, hit.index);
  }
}
