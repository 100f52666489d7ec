// The solids as the lit programs trace them (prepended in front of ground_common.glsl): the rays the
// surface refracts and reflects (solids_optics.glsl) and the rays towards the sun (sun_visible) are
// traced exactly against the scene's boxes, vertical cylinders and hulls afloat
// (viz/passes/traced_solids.hpp packs them). Paper 000 renders penetrating obstacles into
// per-object environment maps from virtual eye points; this is the exact per-pixel answer that
// method approximates.
uniform int u_trace_solids;  // 0: the rays meet only the floor and the sky, nothing shades the sun;
                             // 1: traced; 2: paper 000's virtual eye maps (solids_optics.glsl)
uniform int u_traced_count;
uniform vec4 u_traced[96];   // three per solid (traced_solids.hpp)
uniform vec3 u_traced_lo;    // a box holding them all: a ray that misses it meets none
uniform vec3 u_traced_hi;

// Entry and exit distances of the ray o + t d through the box lo-hi (the slab method), and the axis
// of the entry face.
vec2 box_span(vec3 o, vec3 d, vec3 lo, vec3 hi, out int axis) {
  vec3 inv = (step(0.0, d) * 2.0 - 1.0) / max(abs(d), vec3(1e-12));
  vec3 a = (lo - o) * inv, b = (hi - o) * inv;
  vec3 near = min(a, b), far = max(a, b);
  axis = near.x > near.y ? (near.x > near.z ? 0 : 2) : (near.y > near.z ? 1 : 2);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

// The vertical cylinder around c (radius r) from z0 to z1: entry and exit distances, and whether
// the entry is on its side (else a cap).
vec2 cylinder_span(vec3 o, vec3 d, vec2 c, float r, float z0, float z1, out bool side) {
  vec2 oc = o.xy - c;
  float a = dot(d.xy, d.xy), b = dot(oc, d.xy), cc = dot(oc, oc) - r * r;
  vec2 s = vec2(-1e30, 1e30);  // the infinite cylinder's span (all of the ray inside when vertical)
  if (a > 1e-12) {
    float disc = b * b - a * cc;
    if (disc < 0.0) return vec2(1.0, 0.0);
    s = (vec2(-b) + vec2(-1.0, 1.0) * sqrt(disc)) / a;
  } else if (cc > 0.0) {
    return vec2(1.0, 0.0);
  }
  float inv = (d.z >= 0.0 ? 1.0 : -1.0) / max(abs(d.z), 1e-12);
  vec2 zs = vec2((z0 - o.z) * inv, (z1 - o.z) * inv);
  vec2 z = vec2(min(zs.x, zs.y), max(zs.x, zs.y));
  side = s.x > z.x;
  return vec2(max(s.x, z.x), min(s.y, z.y));
}

// A hull afloat in its frame: l = (along the heading, across, above the plane the hull floats on);
// the map from the world is affine, l = J (p - (x, y, heave)), so a ray stays a ray.
mat3 hull_frame(vec4 a, vec4 c) {
  float ch = cos(a.z), sh = sin(a.z);
  // columns of J: d l / dx, d l / dy, d l / dz (lz = z - heave - s_along lx - s_across ly)
  return mat3(ch, -sh, -c.y * ch + c.z * sh, sh, ch, -c.y * sh - c.z * ch, 0.0, 0.0, 1.0);
}

// The hull's solid as a field, inside where <= 0: append_hull's Wigley hull below the waterline,
// y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2), topsides flaring 12 % to a deck at the freeboard F, crowned
// by 8 % of the beam on its centre line. b = (L, B, T, F).
float hull_half(vec4 b, float xi, float z) {
  float zz = z < 0.0 ? z / b.z : 0.0, flare = z > 0.0 ? 1.0 + 0.12 * z / b.w : 1.0;
  return 0.5 * b.y * (1.0 - xi * xi) * (1.0 - zz * zz) * flare;
}
float hull_field(vec4 b, vec3 l) {
  float xi = 2.0 * l.x / b.x, w = hull_half(b, xi, b.w);
  float side = abs(l.y) - hull_half(b, xi, min(l.z, b.w));
  float deck = l.z - (b.w + 0.08 * b.y * (1.0 - xi * xi) * (1.0 - abs(l.y) / max(w, 1e-6)));
  return max(max(side, deck), max(-b.z - l.z, abs(l.x) - 0.5 * b.x));
}

// The hull met by o + t d within (t0, t1): a march of 40 steps through its bounding box, then 12
// bisections; the normal from the field's gradient, carried back to the world by J^T.
bool hull_hit(vec3 o, vec3 d, vec4 a, vec4 b, vec4 c, float tmax, out float t, out vec3 n) {
  mat3 J = hull_frame(a, c);
  vec3 lo = J * (o - vec3(a.xy, c.x)), ld = J * d;
  int axis;
  vec2 s = box_span(lo, ld, vec3(-0.5 * b.x, -0.56 * b.y, -b.z), vec3(0.5 * b.x, 0.56 * b.y, b.w + 0.08 * b.y), axis);
  s = vec2(max(s.x, 1e-4), min(s.y, tmax));
  if (s.x >= s.y) return false;
  float dt = (s.y - s.x) / 40.0, prev = s.x;
  for (int k = 0; k <= 40; ++k) {
    float tk = s.x + dt * float(k);
    if (hull_field(b, lo + tk * ld) <= 0.0) {
      float lo_t = prev, hi_t = tk;
      for (int i = 0; i < 12; ++i) {
        float m = 0.5 * (lo_t + hi_t);
        if (hull_field(b, lo + m * ld) <= 0.0) hi_t = m; else lo_t = m;
      }
      t = hi_t;
      vec3 l = lo + lo_t * ld, e = vec3(2e-3 * b.x, 0.0, 0.0);
      vec3 g = vec3(hull_field(b, l + e.xyy) - hull_field(b, l - e.xyy), hull_field(b, l + e.yxy) - hull_field(b, l - e.yxy),
                    hull_field(b, l + e.yyx) - hull_field(b, l - e.yyx));
      n = normalize(transpose(J) * g);
      return true;
    }
    prev = tk;
  }
  return false;
}

// The nearest traced solid on o + t d (d unit) with 1e-4 < t < tmax: its distance, outward normal
// and solid_colour kind (0 hull, 1 obstacle). A ray starting inside a solid meets nothing.
bool trace_solids(vec3 o, vec3 d, float tmax, out float t, out vec3 n, out int kind) {
  t = tmax;
  int axis;
  vec2 all = box_span(o, d, u_traced_lo, u_traced_hi, axis);
  if (all.x > all.y || all.y < 1e-4 || all.x > tmax) return false;
  for (int i = 0; i < u_traced_count; ++i) {
    vec4 a = u_traced[3 * i], b = u_traced[3 * i + 1], c = u_traced[3 * i + 2];
    float th;
    vec3 nh;
    if (a.w > 1.5) {
      if (hull_hit(o, d, a, b, c, t, th, nh)) t = th, n = nh, kind = 0;
      continue;
    }
    vec2 s;
    if (a.w < 0.5) {
      int axis;
      s = box_span(o, d, a.xyz, b.xyz, axis);
      nh = vec3(0.0);
      nh[axis] = d[axis] > 0.0 ? -1.0 : 1.0;
    } else {
      bool side;
      s = cylinder_span(o, d, a.xy, b.x, a.z, b.z, side);
      vec3 p = o + s.x * d;
      nh = side ? vec3((p.xy - a.xy) / b.x, 0.0) : vec3(0.0, 0.0, d.z > 0.0 ? -1.0 : 1.0);
    }
    if (s.x <= s.y && s.x > 1e-4 && s.x < t) t = s.x, n = nh, kind = 1;
  }
  return t < tmax;
}
