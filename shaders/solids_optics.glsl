// The solids seen in and through the water (prepended to surface.frag after ground_common.glsl,
// solid_colour.glsl and solids_trace.glsl): what the surface's refracted and reflected rays meet.

// A traced solid's radiance at p: solid_colour lit by the sun, under the water (below the rest
// level) by the sun's ray refracted into it (Snell at the still surface; no caustics, no shadow).
vec3 traced_radiance(vec3 p, vec3 n, int kind) {
  vec3 sun = normalize(u_sun_dir);
  if (p.z < 0.0) sun = -refract(-sun, vec3(0.0, 0.0, 1.0), 1.0 / u_index);
  return solid_colour(p, n, kind, sun);
}

// What the ray r reflected at the surface point P meets: a solid, else the sky.
vec3 reflected(vec3 P, vec3 r) {
  float t;
  vec3 n;
  int kind;
  if (u_trace_solids != 0 && trace_solids(P, r, 1e5, t, n, kind)) return traced_radiance(P + t * r, n, kind);
  return sky(r);
}

// The ray under the water from P towards `hit` (what it meets without solids, with its radiance
// c): a solid before it replaces both (true).
bool refracted_solids(vec3 P, inout vec3 hit, inout vec3 c) {
  vec3 d = hit - P;
  float len = length(d), t;
  vec3 n;
  int kind;
  if (u_trace_solids == 0 || len < 1e-6 || !trace_solids(P, d / len, len, t, n, kind)) return false;
  hit = P + t * d / len;
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
