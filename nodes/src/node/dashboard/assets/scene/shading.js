// The lighting every solid in the view shares: a fixed key light from above and a fill, two-sided
// so that a surface seen from below is lit like one seen from above.

export const LIGHTING_GLSL = `
vec3 lit(vec3 base, vec3 normal) {
  vec3 n = normalize(normal);
  float key = abs(dot(n, normalize(vec3(0.35, 0.25, 1.0))));
  float fill = abs(dot(n, normalize(vec3(-0.6, -0.4, 0.2))));
  return base * (0.30 + 0.55 * key + 0.20 * fill);
}`;
