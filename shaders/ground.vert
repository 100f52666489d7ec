#version 330 core
// The ground plane z = u_ground_z, drawn as one large quad in world metres.
layout(location = 0) in vec2 a_xy;
uniform mat4 u_mvp;
uniform float u_ground_z;
out vec2 v_xy;
void main() {
  v_xy = a_xy;
  gl_Position = u_mvp * vec4(a_xy, u_ground_z, 1.0);
}
