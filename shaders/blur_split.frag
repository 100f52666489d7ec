#version 330 core
// Paper 004 sec. 6, first pass: one of the 16 shifted draws. Reads the 8-bit source texel
// at this pixel + u_offset (clamp to edge) and looks up (0, v >> 4, v & 15, 0) / 255 in
// the precomputed 256 x 1 table; additive blending sums the draws in the RGBA8 target.
uniform sampler2D u_src;        // GL_R8, the caustics texture
uniform sampler2D u_split_lut;  // 256 x 1 GL_RGBA8
uniform ivec2 u_offset;
out vec4 o_color;
void main() {
  ivec2 size = textureSize(u_src, 0);
  ivec2 p = clamp(ivec2(gl_FragCoord.xy) + u_offset, ivec2(0), size - 1);
  int v = int(texelFetch(u_src, p, 0).r * 255.0 + 0.5);
  o_color = texelFetch(u_split_lut, ivec2(v, 0), 0);
}
