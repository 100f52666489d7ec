#version 330 core
// The floor (z = u_ground_z) and the pool deck at the rest level (z = 0), world metres.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_mvp;
uniform float u_ground_z;
out vec2 v_xy;
out float v_deck;
void main() {
  v_xy = a_pos.xy;
  v_deck = a_pos.z > u_ground_z + 1e-4 ? 1.0 : 0.0;
  gl_Position = u_mvp * vec4(a_pos, 1.0);
}
