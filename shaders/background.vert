#version 330 core
// The background: one triangle over the viewport at the far plane (depth 1), so it fills only
// what nothing else covered. v_ndc: the pixel's normalised device coordinates.
out vec2 v_ndc;
void main() {
  v_ndc = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(v_ndc, 1.0, 1.0);
}
