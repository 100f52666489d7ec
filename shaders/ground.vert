#version 330 core
// The floor (z = u_ground_z) and the pool deck at the rest level (z = 0), or the bed as terrain,
// world metres.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_mvp;
uniform float u_ground_z;
uniform int u_terrain;  // 1: the bed as terrain (any height, never the deck)
out vec2 v_xy;
out vec3 v_p;
out float v_deck;
void main() {
  v_xy = a_pos.xy;
  v_p = a_pos;
  v_deck = u_terrain == 0 && a_pos.z > u_ground_z + 1e-4 ? 1.0 : 0.0;
  gl_Position = u_mvp * vec4(a_pos, 1.0);
}
