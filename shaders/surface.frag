// (#version, solids_trace.glsl, ground_common.glsl, solid_colour.glsl and solids_optics.glsl are
// prepended by the renderer)
// Water surface shading (paper 004, section 4; paper 003 for colour and absorption).
// Per pixel: the normal from the full-resolution central height differences,
//   n = normalize(-eta_u / (2 dx), -eta_v / (2 dx), 1);
// the ground point seen through the surface, either linearised
//   G = (u0, v0) + eta (a, b) + [c d; e f] (eta_u, eta_v)
// or exact (Snell: t = refract(d, n, 1/index), followed to z = ground_z, or over terrain through
// the bed's heightfield to where it meets the bed: march_bed, paper 001);
// then C = (1 - F) [ lit_ground(G) T + W (1 - T) ] + F S(r) + g L, T = exp(-a_rgb d), where a
// solid met by the refracted or the reflected ray stands in for the ground or the sky S
// (solids_optics.glsl)
// (deep water: W alone); the glint g is the paper's clamp(100 n.h - 98.95) or the sun reflected
// by the facets of the surface's slope spread (ground_common.glsl, glint).
in vec3 v_pos;
in vec2 v_base;
out vec4 o_color;

uniform sampler2D u_diffs;  // RG32F: eta_u, eta_v at the grid points
uniform sampler2D u_coef;   // RGBA32F: c, d, e, f at the grid points
uniform sampler2D u_dye;    // R32F: dye in [0, 1] at the grid points (u_use_dye)
uniform int u_use_dye;
uniform float u_dry_depth;  // water thinner than this over a bed (or u_hide_dry) is not drawn (m)
uniform int u_hide_dry;     // leave out thin water over the flat floor too (the SPH look)
uniform vec3 u_dye_colour;
uniform sampler2D u_foam;   // R32F: foam in [0, 1] at the grid points (u_use_foam)
uniform int u_use_foam;
uniform vec3 u_foam_colour;
// (u_eye, u_ortho, u_view_dir, u_index, u_water_colour, u_sky*, u_sun_dir, u_deep: ground_common.glsl)
// (u_bed, u_use_bed, u_grid_origin, u_grid_size, u_dx, march_bed: ground_common.glsl)
uniform float u_ground_z;
uniform int u_exact;
// (u_absorption, u_absorb, through_water: ground_common.glsl; underside, reflected, refracted_solids:
// solids_optics.glsl)
// (u_fresnel, u_glint, u_sun_*, u_slope_var, u_region_var: ground_common.glsl)

// Value noise in [0, 1] at p (grid points): an integer hash per lattice corner, smooth blend.
float hash(ivec2 c) {
  uint h = uint(c.x) * 0x8da6b343u ^ uint(c.y) * 0xd8163841u;
  h = (h ^ (h >> 13)) * 0x5bd1e995u;
  return float((h ^ (h >> 15)) & 0xffffu) / 65535.0;
}
float value_noise(vec2 p) {
  ivec2 c = ivec2(floor(p));
  vec2 t = fract(p);
  t = t * t * (3.0 - 2.0 * t);
  return mix(mix(hash(c), hash(c + ivec2(1, 0)), t.x), mix(hash(c + ivec2(0, 1)), hash(c + ivec2(1, 1)), t.x), t.y);
}

void main() {
  vec2 tc = ((v_pos.xy - u_grid_origin) / u_dx + 0.5) / u_grid_size;
  vec2 d = texture(u_diffs, tc).rg;
  vec3 n = normalize(vec3(-d / (2.0 * u_dx), 1.0));
  vec3 dir = u_ortho != 0 ? u_view_dir : normalize(v_pos - u_eye);

  // over a bed: dry land is not water; the refracted ray is followed to the bed (march_bed)
  float floor_z = u_ground_z;
  if (u_use_bed != 0) {
    floor_z = texture(u_bed, tc).r;
    if (v_pos.z - floor_z < u_dry_depth) discard;
  } else if (u_hide_dry != 0 && v_pos.z - floor_z < u_dry_depth) {
    discard;
  }
  // seen from under the water (the eye below this point of the surface): Snell's window, total
  // internal reflection, and the water along the eye's path. (A per-pixel normal turned away from
  // an eye above the water, on a steep wave seen grazing, is not the underside: there n.v clamps
  // to 0 and the facet reflects the sky.)
  if (u_ortho == 0 && u_eye.z < v_pos.z) {
    o_color = vec4(through_water(underside(v_pos, n, dir, floor_z), length(v_pos - u_eye)), 1.0);
    return;
  }
  vec2 G;
  if (u_exact != 0 || u_use_bed != 0) {
    vec3 nn = dot(n, dir) > 0.0 ? -n : n;
    vec3 t = refract(dir, nn, 1.0 / u_index);
    t.z = min(t.z, -1e-6);
    vec3 F = floor_hit(v_pos, t, floor_z);
    G = F.xy;
    floor_z = F.z;
  } else {
    vec4 c = texture(u_coef, tc);
    G = v_base + vec2(c.x * d.x + c.y * d.y, c.z * d.x + c.w * d.y);
  }

  // where the refracted ray ends: a solid, the floor or a pool's wall; in deep water a solid or
  // nothing (the water's own colour), the ray followed 1e4 m down
  vec3 hit = u_deep != 0 ? v_pos + 1e4 * refract(dir, n, 1.0 / u_index) : vec3(0.0);
  vec3 refr = u_deep != 0 ? deep_water_colour(n) : seen_under_water(v_pos, G, floor_z, hit);
  if (refracted_solids(v_pos, hit, refr) || u_deep == 0) refr = through_water(refr, length(hit - v_pos));
  // dye carried by the flow (paper 002; viz/app/dye.hpp), in the water at this point
  if (u_use_dye != 0) refr = mix(refr, u_dye_colour, 0.7 * texture(u_dye, tc).r);

  float nv = max(dot(n, -dir), 0.0);
  vec3 col = mix(refr, reflected(v_pos, reflect(dir, n)), fresnel(nv)) + glint(n, dir, u_region_var);
  vec3 sun = normalize(u_sun_dir);
  if (u_use_foam != 0) {
    vec2 gp = (v_pos.xy - u_grid_origin) / u_dx;
    float q = 0.6 * value_noise(gp / 4.0) + 0.4 * value_noise(gp / 2.0 + 57.0);
    float a = clamp(texture(u_foam, tc).r * (0.25 + 1.5 * q), 0.0, 1.0);
    float lit = u_ambient + u_sun_light * clamp(max(dot(n, sun), 0.0) / max(sun.z, 0.1), 0.0, 1.0);
    col = mix(col, u_foam_colour * lit, a);
  }
  o_color = vec4(col, 1.0);
}
