#version 330 core
// Water surface mesh, subsampled from the heightfield (paper 004, section 4). Per vertex:
// world (x, y), the mesh height eta (weighted average) and the linearised refraction
// coefficients (u0, v0, a, b); the base ground coordinate (u0, v0) + eta (a, b) is
// interpolated linearly across each triangle.
layout(location = 0) in vec2 a_xy;
layout(location = 1) in float a_h;
layout(location = 2) in vec4 a_lin;
uniform mat4 u_mvp;
out vec3 v_pos;
out vec2 v_base;
void main() {
  vec3 p = vec3(a_xy, a_h);
  v_pos = p;
  v_base = a_lin.xy + a_h * a_lin.zw;
  gl_Position = u_mvp * vec4(p, 1.0);
}
