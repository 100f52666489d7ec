// (#version and solid_colour.glsl are prepended by VirtualEyeMaps)
// A solid as its virtual eye sees it: solid_colour (face normal from the screen-space derivatives,
// turned to the eye; lit along u_light) and, in alpha, its distance from the virtual eye (0: empty).
in vec3 v_pos;
out vec4 o_color;
uniform vec3 u_eye_v;
uniform vec3 u_light;
uniform int u_kind;
void main() {
  vec3 n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  if (dot(n, u_eye_v - v_pos) < 0.0) n = -n;
  o_color = vec4(solid_colour(v_pos, n, u_kind, u_light), distance(v_pos, u_eye_v));
}
