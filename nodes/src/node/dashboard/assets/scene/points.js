// Draws the latest cloud of each stream as round GL points coloured by height, intensity or
// source, and draws the same points as ids into the picking framebuffer (picking.js).

import { BLEND_SOURCE_COLORS, STREAM_COLORS } from './colors.js';
import { GrowingBuffer, createProgram, floatAttribute } from './gl_util.js';

export const COLOR_MODES = ['height', 'intensity', 'source'];

const VERTEX = `#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in float intensity;
uniform mat4 viewProjection;
uniform float pointSize;
uniform int colorMode;          // index into COLOR_MODES
uniform vec2 heightRange;
uniform vec2 intensityRange;
uniform vec3 streamColor;
uniform bool blendSources;
uniform vec3 sourceColors[3];
out vec3 color;

vec3 heightRamp(float t) {       // dark blue, cyan, green, yellow, red
  vec3 a = mix(vec3(0.15, 0.25, 0.75), vec3(0.10, 0.80, 0.90), smoothstep(0.0, 0.33, t));
  vec3 b = mix(a, vec3(0.35, 0.90, 0.35), smoothstep(0.33, 0.6, t));
  vec3 c = mix(b, vec3(1.00, 0.85, 0.20), smoothstep(0.6, 0.85, t));
  return mix(c, vec3(0.95, 0.30, 0.20), smoothstep(0.85, 1.0, t));
}

float unit(float value, vec2 range) {
  return clamp((value - range.x) / max(range.y - range.x, 1e-12), 0.0, 1.0);
}

void main() {
  gl_Position = viewProjection * vec4(position, 1.0);
  gl_PointSize = pointSize;
  if (colorMode == 0) {
    color = heightRamp(unit(position.z, heightRange));
  } else if (colorMode == 1) {
    color = mix(vec3(0.12, 0.16, 0.25), vec3(1.0, 0.96, 0.85), unit(intensity, intensityRange));
  } else {
    color = blendSources ? sourceColors[clamp(int(intensity + 0.5), 0, 2)] : streamColor;
  }
}`;

const FRAGMENT = `#version 300 es
precision mediump float;
in vec3 color;
out vec4 outColor;
void main() {
  vec2 d = gl_PointCoord * 2.0 - 1.0;
  if (dot(d, d) > 1.0) discard;
  outColor = vec4(color, 1.0);
}`;

// Point ids: 24 bits of (index + 1) in rgb, 0 meaning "no point"; the cloud's slot in alpha.
const PICK_VERTEX = `#version 300 es
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
uniform float pointSize;
uniform float slot;
flat out vec4 id;
void main() {
  gl_Position = viewProjection * vec4(position, 1.0);
  gl_PointSize = pointSize;
  uint n = uint(gl_VertexID) + 1u;
  id = vec4(float(n & 255u), float((n >> 8) & 255u), float((n >> 16) & 255u), slot) / 255.0;
}`;

const PICK_FRAGMENT = `#version 300 es
precision highp float;
flat in vec4 id;
out vec4 outColor;
void main() { outColor = id; }`;

const MAX_PICKABLE_POINTS = (1 << 24) - 2;

// min and max of the finite values of `values` taken every `stride` from `offset`.
function finiteRange(values, stride, offset) {
  let min = Infinity;
  let max = -Infinity;
  for (let i = offset; i < values.length; i += stride) {
    const v = values[i];
    if (!Number.isFinite(v)) continue;
    if (v < min) min = v;
    if (v > max) max = v;
  }
  return min <= max ? [min, max] : null;
}

class CloudLayer {
  constructor(gl, slot) {
    this.slot = slot;
    this.color = STREAM_COLORS[slot % STREAM_COLORS.length];
    this.vao = gl.createVertexArray();
    this.positions = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
    this.intensity = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
    this.count = 0;
    this.cloud = null;
  }

  upload(gl, cloud) {
    this.cloud = cloud;
    this.count = Math.min(cloud.positions.length / 3, MAX_PICKABLE_POINTS);
    this.positions.upload(cloud.positions);
    gl.bindVertexArray(this.vao);
    floatAttribute(gl, 0, this.positions, 3);
    if (cloud.intensity) {
      this.intensity.upload(cloud.intensity);
      floatAttribute(gl, 1, this.intensity, 1);
    } else {
      gl.disableVertexAttribArray(1);
    }
    gl.bindVertexArray(null);
    this.bounds = { x: finiteRange(cloud.positions, 3, 0), y: finiteRange(cloud.positions, 3, 1),
      z: finiteRange(cloud.positions, 3, 2) };
    this.intensityRange = cloud.intensity ? finiteRange(cloud.intensity, 1, 0) : null;
  }
}

export class PointRenderer {
  constructor(gl) {
    this.gl = gl;
    ({ program: this.program, uniforms: this.uniforms } = createProgram(gl, VERTEX, FRAGMENT));
    ({ program: this.pickProgram, uniforms: this.pickUniforms } = createProgram(gl, PICK_VERTEX, PICK_FRAGMENT));
    this.layers = new Map(); // stream -> CloudLayer
  }

  upload(cloud) {
    let layer = this.layers.get(cloud.stream);
    if (!layer) {
      layer = new CloudLayer(this.gl, this.layers.size);
      this.layers.set(cloud.stream, layer);
    }
    layer.upload(this.gl, cloud);
  }

  // The z range over every cloud, for a height colouring that agrees across streams.
  heightRange() {
    const ranges = [...this.layers.values()].map((layer) => layer.bounds.z).filter(Boolean);
    if (ranges.length === 0) return [0, 1];
    return [Math.min(...ranges.map((r) => r[0])), Math.max(...ranges.map((r) => r[1]))];
  }

  draw(viewProjection, { pointSize, colorMode }) {
    const { gl, uniforms: u } = this;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(u.viewProjection, false, viewProjection);
    gl.uniform1f(u.pointSize, pointSize);
    gl.uniform1i(u.colorMode, COLOR_MODES.indexOf(colorMode));
    gl.uniform2fv(u.heightRange, this.heightRange());
    gl.uniform3fv(u['sourceColors[0]'], BLEND_SOURCE_COLORS.flat());
    for (const layer of this.layers.values()) {
      gl.uniform2fv(u.intensityRange, layer.intensityRange ?? [0, 1]);
      gl.uniform3fv(u.streamColor, layer.color);
      gl.uniform1i(u.blendSources, layer.cloud.blendSources ? 1 : 0);
      gl.vertexAttrib1f(1, 0);
      gl.bindVertexArray(layer.vao);
      gl.drawArrays(gl.POINTS, 0, layer.count);
    }
    gl.bindVertexArray(null);
  }

  drawIds(viewProjection, pointSize) {
    const { gl, pickUniforms: u } = this;
    gl.useProgram(this.pickProgram);
    gl.uniformMatrix4fv(u.viewProjection, false, viewProjection);
    gl.uniform1f(u.pointSize, pointSize);
    for (const layer of this.layers.values()) {
      gl.uniform1f(u.slot, layer.slot);
      gl.bindVertexArray(layer.vao);
      gl.drawArrays(gl.POINTS, 0, layer.count);
    }
    gl.bindVertexArray(null);
  }

  // The stream name and world position of point `index` of the cloud in `slot`.
  point(slot, index) {
    for (const [stream, layer] of this.layers) {
      if (layer.slot === slot && index < layer.count) {
        const p = layer.cloud.positions;
        return { stream, position: [p[3 * index], p[3 * index + 1], p[3 * index + 2]] };
      }
    }
    return null;
  }

  // The box around every cloud's points, or null before the first cloud.
  bounds() {
    const boxes = [...this.layers.values()].map((layer) => layer.bounds).filter((b) => b.x && b.y && b.z);
    if (boxes.length === 0) return null;
    const axis = (name, pick, f) => f(...boxes.map((b) => b[name][pick]));
    return {
      min: ['x', 'y', 'z'].map((a) => axis(a, 0, Math.min)),
      max: ['x', 'y', 'z'].map((a) => axis(a, 1, Math.max)),
    };
  }

  // Per blend output cloud: how many of its points are parent, part and transition.
  blendSourceCounts() {
    const counts = {};
    for (const [stream, layer] of this.layers) {
      if (!layer.cloud.blendSources) continue;
      const tally = [0, 0, 0];
      for (const source of layer.cloud.intensity) tally[Math.max(0, Math.min(2, Math.round(source)))]++;
      counts[stream] = tally;
    }
    return counts;
  }

  // The streams coloured by their own colour under "source" (all but blend outputs), in order.
  streamColors() {
    return [...this.layers].filter(([, layer]) => !layer.cloud.blendSources).map(([stream, layer]) => ({ stream, color: layer.color }));
  }

  pointCounts() {
    return Object.fromEntries([...this.layers].map(([stream, layer]) => [stream, layer.count]));
  }
}
