// Plain coloured lines: the arm's chain of link origins and the world axes.

import { GrowingBuffer, createProgram, floatAttribute } from './gl_util.js';

const VERTEX = `#version 300 es
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
void main() { gl_Position = viewProjection * vec4(position, 1.0); }`;

const FRAGMENT = `#version 300 es
precision mediump float;
uniform vec3 color;
out vec4 outColor;
void main() { outColor = vec4(color, 1.0); }`;

// One polyline or set of segments whose vertices can be replaced.
export class LineSet {
  constructor(gl, mode) {
    this.mode = mode; // gl.LINES or gl.LINE_STRIP
    this.vao = gl.createVertexArray();
    this.positions = new GrowingBuffer(gl, gl.ARRAY_BUFFER);
  }

  upload(gl, positions) {
    this.positions.upload(positions);
    gl.bindVertexArray(this.vao);
    floatAttribute(gl, 0, this.positions, 3);
    gl.bindVertexArray(null);
  }
}

export class LineRenderer {
  constructor(gl) {
    this.gl = gl;
    ({ program: this.program, uniforms: this.uniforms } = createProgram(gl, VERTEX, FRAGMENT));
  }

  // Draws each [lineSet, color] of `sets`; `onTop` ignores depth (lines inside solids stay visible).
  draw(viewProjection, sets, { onTop = false } = {}) {
    const { gl, uniforms: u } = this;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(u.viewProjection, false, viewProjection);
    if (onTop) gl.disable(gl.DEPTH_TEST);
    for (const [lineSet, color] of sets) {
      gl.uniform3fv(u.color, color);
      gl.bindVertexArray(lineSet.vao);
      gl.drawArrays(lineSet.mode, 0, lineSet.positions.length / 3);
    }
    gl.bindVertexArray(null);
    if (onTop) gl.enable(gl.DEPTH_TEST);
  }
}

// The world axes at the origin, `size` long: x red, y green, z blue.
export function axes(gl, size) {
  const colors = [[0.9, 0.3, 0.3], [0.3, 0.85, 0.4], [0.35, 0.55, 1.0]];
  return colors.map((color, axis) => {
    const end = [0, 0, 0];
    end[axis] = size;
    const set = new LineSet(gl, gl.LINES);
    set.upload(gl, new Float32Array([0, 0, 0, ...end]));
    return [set, color];
  });
}
