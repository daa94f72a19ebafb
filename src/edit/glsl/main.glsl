// The ray marcher of the preview: the CPU renderer's (src/raymarch/march.rs) steps, hit
// threshold, normals, soft shadows, occlusion and shading, per pixel. The generated part above
// defines sceneDist, sceneLeaf, LEAF_COLOR and the profile, box and light constants.

uniform vec2 uResolution;
uniform vec3 uEye;
uniform vec3 uTarget;
uniform vec3 uUp;
// Vertical field of view in degrees; ignored when uOrthoHeight > 0.
uniform float uFov;
uniform float uOrthoHeight;
// Leaves [uSelLo, uSelHi) are the selected node's: drawn highlighted.
uniform int uSelLo;
uniform int uSelHi;
out vec4 outColor;

const float PENUMBRA = 10.0;

// The parameter range of a ray inside the scene's box, clipped to [0, tmax]; x > y: a miss.
vec2 clipToBox(vec3 o, vec3 d, float tmax) {
  vec3 inv = 1.0 / d;
  vec3 t0 = (BOX_MIN - o) * inv;
  vec3 t1 = (BOX_MAX - o) * inv;
  vec3 lo = min(t0, t1);
  vec3 hi = max(t0, t1);
  float near = max(max(max(lo.x, lo.y), lo.z), 0.0);
  float far = min(min(min(hi.x, hi.y), hi.z), tmax);
  return vec2(near, far);
}

float pixelSize() {
  return uOrthoHeight > 0.0 ? uOrthoHeight / uResolution.y
                            : 2.0 * tan(radians(0.5 * uFov)) / uResolution.y;
}

float hitEpsilon(float t) {
  float foot = uOrthoHeight > 0.0 ? pixelSize() : pixelSize() * t;
  return max(HIT_EPS, 0.25 * foot);
}

float softShadow(vec3 o, vec3 dir, float dist, float eps) {
  vec2 box = clipToBox(o, dir, MAX_DIST);
  float tmax = min(box.x <= box.y ? box.y : 0.0, dist);
  float minStep = SIZE / (4.0 * float(SHADOW_STEPS));
  float res = 1.0;
  float t = 2.0 * eps;
  for (int i = 0; i < SHADOW_STEPS; i++) {
    if (t >= tmax) break;
    float d = sceneDist(o + dir * t);
    if (d < 0.5 * eps) return 0.0;
    res = min(res, PENUMBRA * d / t);
    t += max(d, minStep);
  }
  float r = clamp(res, 0.0, 1.0);
  return r * r * (3.0 - 2.0 * r);
}

float occlusion(vec3 p, vec3 n) {
  float len = 0.04 * SIZE;
  float occ = 0.0, w = 1.0, wsum = 0.0;
  for (int i = 1; i <= AO_STEPS; i++) {
    float h = len * float(i) / float(AO_STEPS);
    float d = sceneDist(p + n * h);
    occ += w * clamp((h - d) / h, 0.0, 1.0);
    wsum += w;
    w *= 0.7;
  }
  return wsum > 0.0 ? clamp(1.0 - occ / wsum, 0.0, 1.0) : 1.0;
}

vec3 encodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

void main() {
  // Pixel (x, y) from the top left, through its centre, as the CPU camera.
  vec2 px = vec2(gl_FragCoord.x, uResolution.y - gl_FragCoord.y);
  vec3 forward = normalize(uTarget - uEye);
  vec3 right = normalize(cross(forward, uUp));
  vec3 up = cross(right, forward);
  float pix = pixelSize();
  float sx = (px.x - 0.5 * uResolution.x) * pix;
  float sy = (0.5 * uResolution.y - px.y) * pix;
  vec3 ro, rd;
  if (uOrthoHeight > 0.0) {
    ro = uEye + right * sx + up * sy;
    rd = forward;
  } else {
    ro = uEye;
    rd = normalize(forward + right * sx + up * sy);
  }
  vec3 color = BACKGROUND;
  vec2 span = clipToBox(ro, rd, MAX_DIST);
  bool hit = false;
  float t = span.x;
  if (span.x <= span.y) {
    float last = EMPTY;
    for (int i = 0; i < MAX_STEPS; i++) {
      float d = sceneDist(ro + rd * t);
      if (d < hitEpsilon(t)) { hit = true; break; }
      last = d;
      t += d;
      if (t > span.y) break;
    }
    if (!hit && t <= span.y && last < 4.0 * hitEpsilon(t)) hit = true;
  }
  if (hit) {
    vec3 p = ro + rd * t;
    float eps = hitEpsilon(t);
    float h = 0.5 * eps;
    vec3 k0 = vec3(1.0, -1.0, -1.0), k1 = vec3(-1.0, -1.0, 1.0);
    vec3 k2 = vec3(-1.0, 1.0, -1.0), k3 = vec3(1.0, 1.0, 1.0);
    vec3 g = k0 * sceneDist(p + k0 * h) + k1 * sceneDist(p + k1 * h)
           + k2 * sceneDist(p + k2 * h) + k3 * sceneDist(p + k3 * h);
    vec3 n = dot(g, g) > 0.0 ? normalize(g) : -rd;
    int leaf = int(sceneLeaf(p).y + 0.5);
    vec3 base = leaf >= 0 && leaf < LEAVES ? LEAF_COLOR[leaf] : vec3(0.8);
    float occ = AO_STEPS > 0 ? occlusion(p, n) : 1.0;
    vec3 light = vec3(AMBIENT * occ);
    for (int i = 0; i < LIGHTS; i++) {
      vec4 l = LIGHT_WHERE[i];
      vec3 dir;
      float dist;
      if (l.w > 0.5) {
        vec3 d = l.xyz - p;
        dist = length(d);
        dir = d / max(dist, 1e-30);
      } else {
        dir = -normalize(l.xyz);
        dist = EMPTY;
      }
      float lambert = dot(n, dir);
      if (lambert <= 0.0) continue;
      float v = SHADOW_STEPS > 0 ? softShadow(p + n * (2.0 * eps), dir, dist, eps) : 1.0;
      light += LIGHT_COLOR[i] * lambert * v;
    }
    color = base * light;
    if (leaf >= uSelLo && leaf < uSelHi) {
      // The selected node: tinted orange, its silhouette lit.
      float rim = pow(1.0 - abs(dot(n, rd)), 2.0);
      color = mix(color, vec3(1.0, 0.45, 0.05), 0.35) + vec3(0.6, 0.25, 0.0) * rim;
    }
  }
  outColor = vec4(encodeSrgb(color), 1.0);
}
