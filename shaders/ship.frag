// (#version and solid_colour.glsl are prepended by FlatDrawer)
// Flat-shaded hull or obstacle: the face normal from screen-space derivatives of the position.
in vec3 v_pos;
out vec4 o_color;
uniform vec3 u_sun_dir;
uniform vec3 u_eye;
uniform int u_solid;  // 1: an obstacle (concrete grey), 2: the water's sides, 3: a tank's wall
void main() {
  vec3 n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  if (dot(n, u_eye - v_pos) < 0.0) n = -n;
  o_color = vec4(solid_colour(v_pos, n, u_solid, normalize(u_sun_dir)), 1.0);
}
