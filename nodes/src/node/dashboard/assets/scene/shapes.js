// Unit shapes the arm renderer instances: a sphere of radius 1 at the origin and an open
// cylinder of radius 1 along z from 0 to 1, as indexed triangle lists (normal = radial part).

export function unitSphere(rings = 12, segments = 20) {
  const positions = [];
  for (let ring = 0; ring <= rings; ring++) {
    const polar = (Math.PI * ring) / rings;
    for (let segment = 0; segment <= segments; segment++) {
      const azimuth = (2 * Math.PI * segment) / segments;
      positions.push(Math.sin(polar) * Math.cos(azimuth), Math.sin(polar) * Math.sin(azimuth), Math.cos(polar));
    }
  }
  return { positions: new Float32Array(positions), indices: gridTriangles(rings, segments) };
}

export function unitCylinder(segments = 20) {
  const positions = [];
  for (let end = 0; end <= 1; end++) {
    for (let segment = 0; segment <= segments; segment++) {
      const azimuth = (2 * Math.PI * segment) / segments;
      positions.push(Math.cos(azimuth), Math.sin(azimuth), end);
    }
  }
  return { positions: new Float32Array(positions), indices: gridTriangles(1, segments) };
}

// Two triangles per cell of a (rows + 1) x (columns + 1) vertex grid laid out row by row.
function gridTriangles(rows, columns) {
  const indices = [];
  const stride = columns + 1;
  for (let row = 0; row < rows; row++) {
    for (let column = 0; column < columns; column++) {
      const a = row * stride + column;
      const b = a + stride;
      indices.push(a, b, a + 1, a + 1, b, b + 1);
    }
  }
  return new Uint32Array(indices);
}
