// (#version and ground_common.glsl are prepended by the renderer)
// What the view ray of a pixel meets when no geometry covered it: the sky S(r) (u_sky at the
// horizon to u_sky_zenith overhead), or, for the open ocean (u_deep), the sea at the rest level
// out to the horizon: P = o + d (-o_z / d_z) on z = 0, shaded by flat_sea(P) with its own depth,
// so the region's water (over its rectangle, where the sea is pushed to the far plane) and the
// hulls stay in front. Below the horizon without a sea: the horizon's colour.
in vec2 v_ndc;
out vec4 o_color;
uniform mat4 u_inv_vp;   // (projection * view)^-1
uniform mat4 u_vp;       // projection * view
uniform vec4 u_region;   // the simulated region's outline: x0, y0, x1, y1 (m)

vec3 unproject(float z_ndc) {
  vec4 p = u_inv_vp * vec4(v_ndc, z_ndc, 1.0);
  return p.xyz / p.w;
}

void main() {
  vec3 o = unproject(-1.0), d = normalize(unproject(1.0) - o);
  // the sea is shaded for every pixel (uniform control flow: its texture lookups and the glint's
  // fwidth take derivatives across the 2x2 pixel quad) and used below the horizon
  // (at most 100 km out: the ambient sea's slopes have long averaged out there, and the texture
  // coordinates stay small enough for the sampler)
  vec3 P = o + d * min(-o.z / min(d.z, -1e-6), 1e5);
  vec3 sea = flat_sea(P);
  gl_FragDepth = 1.0;
  if (u_deep == 0 || d.z >= 0.0 || o.z <= 0.0) {
    o_color = vec4(sky(vec3(d.xy, max(d.z, 0.0))), 1.0);
    return;
  }
  o_color = vec4(sea, 1.0);
  bool inside = all(greaterThanEqual(P.xy, u_region.xy)) && all(lessThanEqual(P.xy, u_region.zw));
  if (!inside) {
    vec4 c = u_vp * vec4(P, 1.0);
    gl_FragDepth = clamp(0.5 * c.z / c.w + 0.5, 0.0, 1.0);
  }
}
