#version 330 core
// Paper 004 sec. 5: one vertex of the caustics mesh, already refracted and projected onto
// the ground on the CPU (a_ground in [0,1]^2 of the caustics texture); a_surface is the
// vertex position at rest in [0,1]^2 of the surface domain (MIP-map / shadow coordinates).
layout(location = 0) in vec2 a_ground;
layout(location = 1) in vec2 a_surface;
out vec2 v_surface;
void main() {
  v_surface = a_surface;
  gl_Position = vec4(2.0 * a_ground - 1.0, 0.0, 1.0);
}
