// (#version, solids_trace.glsl and ground_common.glsl are prepended by the renderer)
// The ground seen directly (no water in between): the floor, or the pool deck around the water
// (pale stone, lit by the sun without caustics).
// Terrain (a bed) is lit by its slope: n . sun relative to a flat floor's, n from the screen-space
// derivatives of the position.
in vec2 v_xy;
in vec3 v_p;
in float v_deck;
out vec4 o_color;
uniform int u_terrain;
void main() {
  if (v_deck > 0.5) {
    o_color = vec4(deck_colour(v_xy), 1.0);
    return;
  }
  vec3 c = lit_ground(v_xy, v_p.z);
  if (u_terrain != 0) {
    vec3 n = normalize(cross(dFdx(v_p), dFdy(v_p)));
    if (n.z < 0.0) n = -n;
    vec3 s = normalize(u_sun_dir);
    c *= clamp(max(dot(n, s), 0.0) / max(s.z, 0.05), 0.35, 1.4);
  }
  // seen from an eye under the water: the floor through the water between them
  if (u_eye_under != 0) c = through_water(c, length(v_p - u_eye));
  o_color = vec4(c, 1.0);
}
