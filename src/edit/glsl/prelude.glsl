// Distance helpers of the generated scene function: one per primitive, 2D primitive and
// combination, each the GLSL twin of the crate's f64 function (src/sdf/shapes.rs, eval.rs,
// extrusion.rs). The Rust test interpreter (src/edit/glsl/interp.rs) follows these lines.

const float EMPTY = 1e30;

float sdBox(vec3 p, vec3 h) {
  vec3 q = abs(p) - h;
  return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}
float sdSphere(vec3 p, float r) { return length(p) - r; }
float sdCylinder(vec3 p, float r, float hh) {
  vec2 d = vec2(length(p.xz) - r, abs(p.y) - hh);
  return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}
float sdCone(vec3 p, float h, float r1, float r2) {
  vec2 q = vec2(length(p.xz), p.y);
  vec2 k1 = vec2(r2, h);
  vec2 k2 = vec2(r2 - r1, 2.0 * h);
  vec2 ca = vec2(q.x - min(q.x, q.y < 0.0 ? r1 : r2), abs(q.y) - h);
  vec2 cb = q - k1 + k2 * clamp(dot(k1 - q, k2) / dot(k2, k2), 0.0, 1.0);
  float s = (cb.x < 0.0 && ca.y < 0.0) ? -1.0 : 1.0;
  return s * sqrt(min(dot(ca, ca), dot(cb, cb)));
}
float sdPyramidUnit(vec3 p, float h) {
  float m2 = h * h + 0.25;
  float x = abs(p.x), y = p.y, z = abs(p.z);
  if (z > x) { float t = x; x = z; z = t; }
  x -= 0.5;
  z -= 0.5;
  vec3 q = vec3(z, h * y - 0.5 * x, h * x + 0.5 * y);
  float s = max(-q.x, 0.0);
  float t = clamp((q.y - 0.5 * z) / (m2 + 0.25), 0.0, 1.0);
  float a = m2 * (q.x + s) * (q.x + s) + q.y * q.y;
  float b = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
  float d2 = min(q.y, -q.x * m2 - q.y * 0.5) > 0.0 ? 0.0 : min(a, b);
  float lateral = sqrt((d2 + q.z * q.z) / m2);
  if (max(q.z, -y) < 0.0) return -min(lateral, y);
  vec2 e = max(vec2(abs(p.x) - 0.5, abs(p.z) - 0.5), 0.0);
  return min(lateral, sqrt(dot(e, e) + y * y));
}
float sdPyramid(vec3 p, float base, float height) {
  return sdPyramidUnit((p + vec3(0.0, 0.5 * height, 0.0)) / base, height / base) * base;
}
float sdPlane(vec3 p, vec3 n, float offset) { return dot(n, p) + offset; }
float sdTorus(vec3 p, float R, float r) {
  return length(vec2(length(p.xz) - R, p.y)) - r;
}

// 2D primitives.
float sdRect(vec2 p, vec2 h) {
  vec2 q = abs(p) - h;
  return length(max(q, 0.0)) + min(max(q.x, q.y), 0.0);
}
float sdCircle(vec2 p, float r) { return length(p) - r; }
float sdRoundedRect(vec2 p, vec2 h, float r) { return sdRect(p, h - r) - r; }
// A rigid placement undone: rotate p - pos by -rot (given as cos, sin).
vec2 unplace(vec2 p, vec2 pos, vec2 cs) {
  vec2 d = p - pos;
  return vec2(cs.x * d.x + cs.y * d.y, -cs.y * d.x + cs.x * d.y);
}

// Extrusion along z of a 2D distance d2.
float extrusion(float d2, float z, float hh) {
  vec2 w = vec2(d2, abs(z) - hh);
  return min(max(w.x, w.y), 0.0) + length(max(w, 0.0));
}
// The slice point of a twisted / tapered extrusion: xy turned back and unscaled, and in z the
// slice's smaller scale factor.
vec3 warpedSlice(vec3 p, float hh, float twist, vec2 scaleTop) {
  float t = clamp((p.z + hh) / (2.0 * hh), 0.0, 1.0);
  vec2 s = max(mix(vec2(1.0), scaleTop, t), vec2(1e-12));
  float a = -radians(twist * t);
  vec2 cs = vec2(cos(a), sin(a));
  vec2 q = vec2(cs.x * p.x - cs.y * p.y, cs.y * p.x + cs.x * p.y) / s;
  return vec3(q, min(s.x, s.y));
}
// The bound of a warped extrusion from its slice distance g (see src/sdf/extrusion.rs).
float warpedBound(float g, vec3 p, float hh, float reach, vec3 slope, vec3 bmin, vec3 bmax) {
  float cap = abs(p.z) - hh;
  float rho = max(length(p.xy), reach);
  float lz = (slope.x + slope.z) * rho + slope.y;
  float d = max(g / sqrt(1.0 + lz * lz), cap);
  float outside = length(max(max(bmin - p, p - bmax), 0.0));
  return outside > 0.0 ? max(d, outside) : d;
}
// The meridian point of a revolution, and its wedge distance for a partial turn.
vec2 meridian(vec3 p) { return vec2(length(p.xz), p.y); }
float revolution(float d, vec3 p, float angle) {
  if (angle >= 360.0) return d;
  float a = radians(angle);
  float end = -sin(a) * p.x - cos(a) * p.z;
  float wedge = angle <= 180.0 ? max(p.z, end) : min(p.z, end);
  return max(d, wedge);
}

// Combinations. Smooth ones: exponential (k a sharpness) or polynomial (k a width).
float sminExp(float a, float b, float k) {
  float diff = abs(a - b);
  return min(a, b) - log(1.0 + exp(-k * diff)) / k;
}
float sminPoly(float a, float b, float k) {
  if (abs(b - a) >= k) return min(a, b);
  float h = clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}
float smin(float a, float b, float k, bool poly) { return poly ? sminPoly(a, b, k) : sminExp(a, b, k); }
float smax(float a, float b, float k, bool poly) { return -smin(-a, -b, k, poly); }
// The deciding operand's leaf, as the CPU picks the material.
vec2 pickUnion(vec2 a, vec2 b, float d) { return vec2(d, a.x <= b.x ? a.y : b.y); }
vec2 pickIntersect(vec2 a, vec2 b, float d) { return vec2(d, a.x >= b.x ? a.y : b.y); }
vec2 pickSubtract(vec2 a, vec2 b, float d) { return vec2(d, a.x >= -b.x ? a.y : b.y); }
