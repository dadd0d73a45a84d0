// Draws each arm posed at its latest joint state: its collision spheres and capsules coloured by
// the clearance band of their link in the latest fresh verdict (the link a stop names in its own
// colour, every link grey without a fresh verdict), and the chain of link origins on top.

import { BAND_COLORS, LINK_LINE_COLOR } from './colors.js';
import { GrowingBuffer, createProgram, floatAttribute } from './gl_util.js';
import { LineSet } from './lines.js';
import { LIGHTING_GLSL } from './shading.js';
import { unitCylinder, unitSphere } from './shapes.js';

const SHAPE_VERTEX = `#version 300 es
layout(location = 0) in vec3 vertex;        // on the unit shape
layout(location = 1) in vec4 startRadius;   // sphere centre or capsule start, radius
layout(location = 2) in vec3 end;           // capsule end (unused by spheres)
layout(location = 3) in vec3 instanceColor;
uniform mat4 viewProjection;
uniform bool cylinder;
out vec3 normal;
out vec3 color;
void main() {
  vec3 start = startRadius.xyz;
  vec3 world;
  if (cylinder) {
    vec3 axis = end - start;
    vec3 w = length(axis) > 1e-9 ? normalize(axis) : vec3(0.0, 0.0, 1.0);
    vec3 helper = abs(w.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(helper, w));
    normal = u * vertex.x + cross(w, u) * vertex.y;
    world = start + axis * vertex.z + startRadius.w * normal;
  } else {
    normal = vertex;
    world = start + startRadius.w * vertex;
  }
  color = instanceColor;
  gl_Position = viewProjection * vec4(world, 1.0);
}`;

const SHAPE_FRAGMENT = `#version 300 es
precision mediump float;
in vec3 normal;
in vec3 color;
out vec4 outColor;
${LIGHTING_GLSL}
void main() { outColor = vec4(lit(color, normal), 1.0); }`;

const FLOATS_PER_INSTANCE = 10; // startRadius (4), end (3), colour (3)

// The colour of link `name` under `verdict` (null: no fresh verdict).
function linkColor(name, verdict) {
  if (!verdict) return BAND_COLORS.unknown;
  if (verdict.stop && verdict.closestLink === name) return BAND_COLORS.stopping;
  const entry = verdict.links.find((link) => link.link === name);
  return entry ? BAND_COLORS[entry.band] : BAND_COLORS.unknown;
}

// Instance data of an arm: spheres (capsule ends included) and capsule bodies.
function instances(arm, verdict) {
  const colors = arm.links.map((name) => linkColor(name, verdict));
  const { spheres, capsules } = arm;
  const sphereCount = spheres.owners.length + 2 * capsules.owners.length;
  const sphereData = new Float32Array(sphereCount * FLOATS_PER_INSTANCE);
  const capsuleData = new Float32Array(capsules.owners.length * FLOATS_PER_INSTANCE);
  const put = (data, index, start, radius, end, color) => {
    data.set([...start, radius, ...end, ...color], index * FLOATS_PER_INSTANCE);
  };
  spheres.owners.forEach((link, i) => {
    const c = spheres.values.subarray(4 * i, 4 * i + 3);
    put(sphereData, i, c, spheres.values[4 * i + 3], c, colors[link]);
  });
  capsules.owners.forEach((link, i) => {
    const a = capsules.values.subarray(7 * i, 7 * i + 3);
    const b = capsules.values.subarray(7 * i + 3, 7 * i + 6);
    const r = capsules.values[7 * i + 6];
    put(capsuleData, i, a, r, b, colors[link]);
    put(sphereData, spheres.owners.length + 2 * i, a, r, a, colors[link]);
    put(sphereData, spheres.owners.length + 2 * i + 1, b, r, b, colors[link]);
  });
  return { sphereData, capsuleData };
}

class InstancedShape {
  constructor(gl, shape) {
    this.vao = gl.createVertexArray();
    this.instances = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
    const vertices = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
    const indices = new GrowingBuffer(gl, gl.ELEMENT_ARRAY_BUFFER);
    vertices.upload(shape.positions);
    gl.bindVertexArray(this.vao);
    floatAttribute(gl, 0, vertices, 3);
    indices.upload(shape.indices);
    const stride = FLOATS_PER_INSTANCE * 4;
    this.instances.upload(new Float32Array(0));
    floatAttribute(gl, 1, this.instances, 4, { divisor: 1, stride, offset: 0 });
    floatAttribute(gl, 2, this.instances, 3, { divisor: 1, stride, offset: 16 });
    floatAttribute(gl, 3, this.instances, 3, { divisor: 1, stride, offset: 28 });
    gl.bindVertexArray(null);
    this.indexCount = shape.indices.length;
    this.count = 0;
  }

  upload(data) {
    this.instances.upload(data);
    this.count = data.length / FLOATS_PER_INSTANCE;
  }

  draw(gl) {
    if (this.count === 0) return;
    gl.bindVertexArray(this.vao);
    gl.drawElementsInstanced(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0, this.count);
  }
}

class ArmLayer {
  constructor(gl) {
    this.spheres = new InstancedShape(gl, unitSphere());
    this.capsules = new InstancedShape(gl, unitCylinder());
    this.chain = new LineSet(gl, gl.LINE_STRIP);
  }

  upload(gl, arm, verdict) {
    const { sphereData, capsuleData } = instances(arm, verdict);
    this.spheres.upload(sphereData);
    this.capsules.upload(capsuleData);
    this.chain.upload(gl, arm.linkOrigins);
  }
}

export class ArmRenderer {
  constructor(gl) {
    this.gl = gl;
    ({ program: this.shapeProgram, uniforms: this.shapeUniforms } = createProgram(gl, SHAPE_VERTEX, SHAPE_FRAGMENT));
    this.layers = new Map(); // arm name -> ArmLayer
  }

  upload(arm, verdict) {
    if (!this.layers.has(arm.arm)) this.layers.set(arm.arm, new ArmLayer(this.gl));
    this.layers.get(arm.arm).upload(this.gl, arm, verdict);
  }

  draw(viewProjection) {
    const { gl } = this;
    gl.useProgram(this.shapeProgram);
    gl.uniformMatrix4fv(this.shapeUniforms.viewProjection, false, viewProjection);
    for (const layer of this.layers.values()) {
      gl.uniform1i(this.shapeUniforms.cylinder, 0);
      layer.spheres.draw(gl);
      gl.uniform1i(this.shapeUniforms.cylinder, 1);
      layer.capsules.draw(gl);
    }
    gl.bindVertexArray(null);
  }

  // Each arm's chain of link origins with its colour, for a LineRenderer (drawn on top: the
  // shapes enclose it).
  chains() {
    return [...this.layers.values()].map((layer) => [layer.chain, LINK_LINE_COLOR]);
  }

  shapeCounts() {
    return Object.fromEntries([...this.layers].map(([arm, layer]) =>
      [arm, { spheres: layer.spheres.count, capsules: layer.capsules.count }]));
  }
}
