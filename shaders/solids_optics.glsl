// The solids seen in and through the water (prepended to surface.frag after ground_common.glsl,
// solid_colour.glsl and solids_trace.glsl): what the surface's refracted and reflected rays meet.

// A traced solid's radiance at p: solid_colour lit by the sun, under the water (below the rest
// level) by the sun's ray refracted into it (Snell at the still surface; no caustics, no shadow).
vec3 traced_radiance(vec3 p, vec3 n, int kind) {
  vec3 sun = normalize(u_sun_dir);
  if (p.z < 0.0) sun = -refract(-sun, vec3(0.0, 0.0, 1.0), 1.0 / u_index);
  return solid_colour(p, n, kind, sun);
}

// Paper 000's maps (u_trace_solids 2; viz/passes/virtual_eye_maps.hpp): tile 2i holds object i's
// part under the water as its virtual refracted eye sees it, tile 2i + 1 its part above as its
// virtual reflected eye sees it; 4 x 4 tiles of one atlas, rgb the radiance, a the distance from the
// virtual eye (0: nothing). A tile is read along the surface's per-pixel direction d from its eye,
// the refraction tiles scaled about a's image by k along the image e of the object's main axis
// (Fig. 3): u_env_fix[i] = (uv of a, k, |E - a|), u_env_shape[i] = (e, R); used only over the
// surface in the object's trapezium (Fig. 8): from x' = u_env_trap[i].xy along r = u_env_trap[i].zw
// towards the eye's foot, half-width R + s / 2 at distance s, blended out over its outer quarter.
uniform sampler2D u_env;
uniform int u_env_count;
uniform mat4 u_env_vp[16];
uniform vec3 u_env_eye[16];
uniform vec4 u_env_fix[8];
uniform vec4 u_env_shape[8];
uniform vec4 u_env_trap[8];
float trapezium(int i, vec2 m) {
  vec2 q = m - u_env_trap[i].xy, r = u_env_trap[i].zw;
  float s = dot(q, r), half_w = u_env_shape[i].z + 0.5 * max(s, 0.0);
  return s < 0.0 ? 0.0 : clamp(4.0 * (1.0 - abs(q.x * r.y - q.y * r.x) / half_w), 0.0, 1.0);
}
bool env_read(int tile, vec3 d, vec4 fix, vec2 e, out vec4 texel) {
  vec4 c = u_env_vp[tile] * vec4(u_env_eye[tile] + d, 1.0);
  if (c.w <= 1e-6) return false;
  vec2 r = c.xy / c.w * 0.5 + 0.5 - fix.xy;
  vec2 uv = fix.xy + r + (fix.z - 1.0) * dot(r, e) * e;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
  texel = textureLod(u_env, (vec2(tile % 4, tile / 4) + clamp(uv, 0.002, 0.998)) * 0.25, 0.0);
  return texel.a > 0.0;
}

// The nearest object in the maps along d from the surface point P: refraction tiles (the distance
// in the water: the map's less |E - a|, the virtual eye's distance behind the surface) or
// reflection tiles; w its trapezium's weight at P.
bool env_solids(vec3 P, vec3 d, bool refraction, out vec3 c, out float dist, out float w) {
  dist = 1e30;
  for (int i = 0; i < u_env_count; ++i) {
    vec4 texel, fix = refraction ? u_env_fix[i] : vec4(0.0, 0.0, 1.0, 0.0);
    float wi = trapezium(i, P.xy);
    if (wi <= 0.0 || !env_read(refraction ? 2 * i : 2 * i + 1, d, fix, u_env_shape[i].xy, texel)) continue;
    float s = max(texel.a - fix.w, 0.0);
    if (s < dist) dist = s, c = texel.rgb, w = wi;
  }
  return dist < 1e30;
}

// What the ray r reflected at the surface point P meets: a solid, else the sky.
vec3 reflected(vec3 P, vec3 r) {
  float t, w;
  vec3 n, c;
  int kind;
  if (u_trace_solids == 2 && env_solids(P, r, false, c, t, w)) return mix(sky(r), c, w);
  if (u_trace_solids == 1 && trace_solids(P, r, 1e5, t, n, kind)) return traced_radiance(P + t * r, n, kind);
  return sky(r);
}

// The ray under the water from P towards `hit` (what it meets without solids, with its radiance
// c): a solid before it replaces both (true).
bool refracted_solids(vec3 P, inout vec3 hit, inout vec3 c) {
  vec3 d = hit - P;
  float len = length(d), t, w;
  vec3 n, e;
  int kind;
  if (u_trace_solids == 0 || len < 1e-6) return false;
  d /= len;
  if (u_trace_solids == 2) {
    if (!env_solids(P, d, true, e, t, w) || t >= len) return false;
    hit = mix(hit, P + t * d, w), c = mix(c, e, w);
    return true;
  }
  if (!trace_solids(P, d, len, t, n, kind)) return false;
  hit = P + t * d;
  c = traced_radiance(hit, n, kind);
  return true;
}

// The surface seen from under the water at P (normal n, pointing up) along the view ray d (going
// up). Into the air the ray bends by Snell's law with the ratio index (water to air),
// t = refract(d, -n, index); beyond the critical angle asin(1 / index) (48.6 deg for 1.333) there
// is no t and the surface is a mirror (total internal reflection): Snell's window. Inside it
// (1 - F) S(t) + F R, S the sky or a solid above the water, F the reflectance at the air side's
// cosine t.n; R what the reflected ray r = reflect(d, -n) meets under the water: a solid, the floor
// (over terrain the bed, march_bed) or a pool's wall (seen_under_water),
// absorbed along its path, or deep water's colour W. The eye's own path to P: the caller.
vec3 underside(vec3 P, vec3 n, vec3 d, float floor_z) {
  vec3 t = refract(d, -n, u_index);
  vec3 r = reflect(d, -n);
  vec3 below = u_deep != 0 ? u_water_colour : vec3(0.0);
  if (u_deep == 0) {
    r.z = min(r.z, -1e-6);
    vec3 F = floor_hit(P, r, floor_z);
    vec3 hit;
    below = seen_under_water(P, F.xy, F.z, hit);
    refracted_solids(P, hit, below);
    below = through_water(below, length(hit - P));
  }
  if (dot(t, t) == 0.0) return below;  // total internal reflection
  float F = fresnel(max(dot(t, n), 0.0));
  return mix(reflected(P, t), below, F);
}
