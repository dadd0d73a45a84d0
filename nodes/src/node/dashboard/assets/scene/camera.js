// An orbit camera around a target point in a z-up world (REP-103): azimuth about +z, elevation
// above the xy plane, distance from the target. Orbit, pan, zoom, fit to bounds, preset views.

import { add, cross, lookAt, multiply, normalize, perspective, scale } from './mat4.js';

const Z_UP = [0, 0, 1];
const MAX_ELEVATION = Math.PI / 2 - 1e-3; // straight down would leave "up on screen" undefined

// Preset views: azimuth and elevation of the eye seen from the target.
const VIEWS = {
  reset: { azimuth: -Math.PI / 3, elevation: Math.PI / 6 },
  top: { azimuth: -Math.PI / 2, elevation: MAX_ELEVATION },
  front: { azimuth: 0, elevation: 0 }, // eye on +x looking back along -x
  side: { azimuth: -Math.PI / 2, elevation: 0 }, // eye on -y looking along +y
};

export class OrbitCamera {
  constructor() {
    this.target = [0, 0, 0];
    this.distance = 5;
    this.sceneRadius = 1;
    this.setView('reset');
  }

  setView(name) {
    Object.assign(this, VIEWS[name]);
  }

  // Centres on the box [min, max] and backs off until it fits the field of view.
  fit(min, max) {
    this.target = scale(add(min, max), 0.5);
    this.sceneRadius = Math.max(1e-3, 0.5 * Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]));
    this.distance = this.sceneRadius * 2.6;
  }

  orbit(dxRadians, dyRadians) {
    this.azimuth -= dxRadians;
    this.elevation = Math.max(-MAX_ELEVATION, Math.min(MAX_ELEVATION, this.elevation + dyRadians));
  }

  // Moves the target in the screen plane by a fraction of the visible height.
  pan(dxFraction, dyFraction) {
    const { right, up } = this.screenAxes();
    const span = this.distance * 0.8;
    this.target = add(this.target, add(scale(right, -dxFraction * span), scale(up, dyFraction * span)));
  }

  zoom(factor) {
    this.distance = Math.max(this.sceneRadius * 1e-3, Math.min(this.sceneRadius * 100, this.distance * factor));
  }

  eye() {
    const c = Math.cos(this.elevation);
    const offset = [c * Math.cos(this.azimuth), c * Math.sin(this.azimuth), Math.sin(this.elevation)];
    return add(this.target, scale(offset, this.distance));
  }

  screenAxes() {
    const forward = normalize(scale(add(this.eye(), scale(this.target, -1)), -1));
    const right = normalize(cross(forward, Z_UP));
    return { right, up: cross(right, forward) };
  }

  // Projection times view, with near and far planes around the scene for depth precision.
  viewProjection(aspect) {
    const near = Math.max(this.distance - this.sceneRadius * 4, this.distance * 1e-3);
    const far = this.distance + this.sceneRadius * 4;
    return multiply(perspective(Math.PI / 4, aspect, near, far), lookAt(this.eye(), this.target, Z_UP));
  }
}
