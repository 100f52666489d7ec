#version 330 core
// Paper 004 sec. 6, second pass: c = green (sum of the high parts), d = blue (sum of the
// low parts); the precomputed 256 x 256 table holds c + floor((d + 7) / 16) / 255.
uniform sampler2D u_accum;        // GL_RGBA8 accumulation target
uniform sampler2D u_combine_lut;  // 256 x 256 GL_R8, row c, column d
out vec4 o_color;
void main() {
  vec4 a = texelFetch(u_accum, ivec2(gl_FragCoord.xy), 0);
  int c = int(a.g * 255.0 + 0.5);
  int d = int(a.b * 255.0 + 0.5);
  o_color = vec4(texelFetch(u_combine_lut, ivec2(d, c), 0).r);
}
