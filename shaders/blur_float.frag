#version 330 core
// Comparison path: the same [1 2 1; 2 4 2; 1 2 1] / 16 blur in float, clamp to edge.
uniform sampler2D u_src;
out vec4 o_color;
void main() {
  ivec2 size = textureSize(u_src, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  float s = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      float w = float((2 - abs(dx)) * (2 - abs(dy)));
      s += w * texelFetch(u_src, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).r;
    }
  o_color = vec4(s / 16.0);
}
