// WebGL2 plumbing shared by the renderers: program compilation with the driver's log in the
// error, and GPU buffers that are reallocated only when the data outgrows them.

// {program, uniforms}: the linked program and its uniforms' locations by name.
export function createProgram(gl, vertexSource, fragmentSource) {
  const program = compileProgram(gl, vertexSource, fragmentSource);
  return { program, uniforms: uniformLocations(gl, program) };
}

function compileProgram(gl, vertexSource, fragmentSource) {
  const program = gl.createProgram();
  for (const [kind, source] of [[gl.VERTEX_SHADER, vertexSource], [gl.FRAGMENT_SHADER, fragmentSource]]) {
    const shader = gl.createShader(kind);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
      throw new Error(`shader does not compile: ${gl.getShaderInfoLog(shader)}`);
    }
    gl.attachShader(program, shader);
    gl.deleteShader(shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    throw new Error(`program does not link: ${gl.getProgramInfoLog(program)}`);
  }
  return program;
}

// Every active uniform's location by name.
function uniformLocations(gl, program) {
  const locations = {};
  const count = gl.getProgramParameter(program, gl.ACTIVE_UNIFORMS);
  for (let i = 0; i < count; i++) {
    const name = gl.getActiveUniform(program, i).name;
    locations[name] = gl.getUniformLocation(program, name);
  }
  return locations;
}

// A GPU buffer for data replaced every frame: bufferData only when the data grows past the
// allocation (with headroom), bufferSubData otherwise, so a steady stream allocates nothing.
export class GrowingBuffer {
  constructor(gl, target) {
    this.gl = gl;
    this.target = target;
    this.buffer = gl.createBuffer();
    this.capacityBytes = 0;
    this.length = 0; // elements of the last upload
  }

  upload(values) {
    const { gl, target } = this;
    gl.bindBuffer(target, this.buffer);
    if (values.byteLength > this.capacityBytes) {
      this.capacityBytes = Math.ceil(values.byteLength * 1.25 / 4) * 4;
      gl.bufferData(target, this.capacityBytes, gl.DYNAMIC_DRAW);
    }
    if (values.byteLength > 0) gl.bufferSubData(target, 0, values);
    this.length = values.length;
  }

  delete() {
    this.gl.deleteBuffer(this.buffer);
  }
}

// Binds `buffer` as float vertex attribute `location` with `size` components per vertex
// (per instance when `divisor` is 1).
export function floatAttribute(gl, location, buffer, size, { divisor = 0, stride = 0, offset = 0 } = {}) {
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer.buffer ?? buffer);
  gl.enableVertexAttribArray(location);
  gl.vertexAttribPointer(location, size, gl.FLOAT, false, stride, offset);
  gl.vertexAttribDivisor(location, divisor);
}
