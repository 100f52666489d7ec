#version 330 core
// Explicit area mode: every triangle carries the light its surface triangle intercepts, so
// its brightness is u_unit * (surface area) / (ground area), both measured in texels of the
// caustics texture (the still-water projection maps one onto the other). v_surface is where
// the sun rays through the vertices cross z = 0, so "surface area" is the beam cross-section
// (CausticsParams::flux_by_beam_area; the rest positions when it is off or the sun is overhead).
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec2 v_surface[];
out vec2 f_surface;
flat out float f_gain;
uniform vec2 u_target_size;  // caustics texture size (texels)
uniform float u_unit;        // value of unit irradiance (still water)
float area(vec2 a, vec2 b, vec2 c) {
  vec2 e1 = b - a, e2 = c - a;
  return 0.5 * abs(e1.x * e2.y - e1.y * e2.x);
}
void main() {
  vec2 h = 0.5 * u_target_size;
  float ground = area(gl_in[0].gl_Position.xy * h, gl_in[1].gl_Position.xy * h, gl_in[2].gl_Position.xy * h);
  float surface = area(v_surface[0] * u_target_size, v_surface[1] * u_target_size, v_surface[2] * u_target_size);
  float gain = u_unit * surface / max(ground, 1e-6 * surface);
  for (int k = 0; k < 3; ++k) {
    gl_Position = gl_in[k].gl_Position;
    f_surface = v_surface[k];
    f_gain = gain;
    EmitVertex();
  }
  EndPrimitive();
}
