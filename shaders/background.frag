// (#version, solids_trace.glsl and ground_common.glsl are prepended by the renderer)
// What the view ray of a pixel meets where nothing else was drawn (this pass comes last, at the
// far plane): the sky S(r) (u_sky at the horizon to u_sky_zenith overhead), or below the horizon
// the plane of the rest level out to the horizon, P = o + d (-o_z / d_z) on z = 0: the open sea
// (u_deep, flat_sea) or the pool's deck (u_deck, deck_colour), which go on where their quads
// (2 region sizes around the region, drawn with the geometry's depth) end. Below the horizon with
// neither: the horizon's colour.
in vec2 v_ndc;
out vec4 o_color;
uniform mat4 u_inv_vp;   // (projection * view)^-1

vec3 unproject(float z_ndc) {
  vec4 p = u_inv_vp * vec4(v_ndc, z_ndc, 1.0);
  return p.xyz / p.w;
}

void main() {
  vec3 o = unproject(-1.0), d = normalize(unproject(1.0) - o);
  bool below = (u_deep != 0 || u_deck != 0) && d.z < 0.0 && o.z > 0.0;
  // the plane is shaded for every pixel, the sky's too, and picked at the end (uniform control
  // flow: the texture lookups and the glint's slope spread take derivatives across the 2x2 pixel
  // quad); at most 100 km out (the sea's slopes and the deck's tiles have long averaged out
  // there, and the texture coordinates stay small enough for the sampler)
  vec3 P = o + d * min(-o.z / min(d.z, -1e-6), 1e5);
  vec3 plane = u_deep != 0 ? flat_sea(P) : deck_colour(P.xy);
  o_color = vec4(below ? plane : sky(vec3(d.xy, max(d.z, 0.0))), 1.0);
}
