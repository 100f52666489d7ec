#version 330 core
// A solid drawn into a virtual eye's map (paper 000; viz/passes/virtual_eye_maps.hpp): only the part
// on one side of the plane z = u_plane (u_side +1: above, for the reflection; -1: below, for the
// refraction), clipped in hardware.
layout(location = 0) in vec3 a_pos;
uniform mat4 u_vp;
uniform float u_plane;
uniform float u_side;
out vec3 v_pos;
void main() {
  v_pos = a_pos;
  gl_Position = u_vp * vec4(a_pos, 1.0);
  gl_ClipDistance[0] = u_side * (a_pos.z - u_plane);
}
