// Draws triangle meshes: the upper and lower surrogate surfaces and the smooth fits, each
// semi-transparent and lit flat (normals from screen-space derivatives: the messages carry none).

import { SURFACE_COLORS } from './colors.js';
import { GrowingBuffer, createProgram, floatAttribute } from './gl_util.js';
import { LIGHTING_GLSL } from './shading.js';

const VERTEX = `#version 300 es
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
out vec3 world;
void main() {
  world = position;
  gl_Position = viewProjection * vec4(position, 1.0);
}`;

const FRAGMENT = `#version 300 es
precision highp float;
in vec3 world;
uniform vec4 color;
out vec4 outColor;
${LIGHTING_GLSL}
void main() {
  outColor = vec4(lit(color.rgb, cross(dFdx(world), dFdy(world))), color.a);
}`;

class MeshLayer {
  constructor(gl, kind) {
    this.kind = kind; // "upper", "lower" or "smooth": the key of SURFACE_COLORS
    this.vao = gl.createVertexArray();
    this.positions = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
    this.indices = new GrowingBuffer(gl, gl.ELEMENT_ARRAY_BUFFER);
  }

  upload(gl, mesh) {
    this.positions.upload(mesh.positions);
    // The element buffer binding belongs to the vertex array: bind it first.
    gl.bindVertexArray(this.vao);
    floatAttribute(gl, 0, this.positions, 3);
    this.indices.upload(mesh.indices);
    gl.bindVertexArray(null);
  }

  delete(gl) {
    this.positions.delete();
    this.indices.delete();
    gl.deleteVertexArray(this.vao);
  }
}

export class MeshRenderer {
  constructor(gl) {
    this.gl = gl;
    ({ program: this.program, uniforms: this.uniforms } = createProgram(gl, VERTEX, FRAGMENT));
    this.layers = new Map(); // "<stream>/<kind>" -> MeshLayer
  }

  // Replaces the meshes of `stream` among `kinds` with `meshes` ({kind: mesh}); a kind missing
  // from `meshes` (e.g. a surrogate that is now upper only) is removed.
  upload(stream, kinds, meshes) {
    for (const kind of kinds) {
      const key = `${stream}/${kind}`;
      const mesh = meshes[kind];
      if (!mesh) {
        this.layers.get(key)?.delete(this.gl);
        this.layers.delete(key);
        continue;
      }
      if (!this.layers.has(key)) this.layers.set(key, new MeshLayer(this.gl, kind));
      this.layers.get(key).upload(this.gl, mesh);
    }
  }

  // Draws the kinds for which `visible[kind]` is true, blended over what is drawn already.
  draw(viewProjection, visible) {
    const { gl, uniforms: u } = this;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(u.viewProjection, false, viewProjection);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.depthMask(false);
    for (const layer of this.layers.values()) {
      if (!visible[layer.kind] || layer.indices.length === 0) continue;
      gl.uniform4fv(u.color, SURFACE_COLORS[layer.kind]);
      gl.bindVertexArray(layer.vao);
      gl.drawElements(gl.TRIANGLES, layer.indices.length, gl.UNSIGNED_INT, 0);
    }
    gl.bindVertexArray(null);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
  }

  triangleCounts() {
    return Object.fromEntries([...this.layers].map(([key, layer]) => [key, layer.indices.length / 3]));
  }
}
