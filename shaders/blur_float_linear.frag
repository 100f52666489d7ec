#version 330 core
// The [1 2 1; 2 4 2; 1 2 1] / 16 blur of blur_float.frag in four bilinear taps, for float
// sources (u_src sampled GL_LINEAR through a sampler object, clamp to edge; llvmpipe filters
// GL_R32F in float but 8-bit sources with 8-bit weights, so GL_R8 keeps blur_float.frag): the
// tap at (+-1/2, +-1/2) texel averages a 2 x 2 block, and the four blocks together weigh the
// 3 x 3 neighbourhood by [1 2 1] x [1 2 1] / 16. At the edge the clamped tap repeats the edge
// texel, as the texelFetch version does.
uniform sampler2D u_src;
out vec4 o_color;
void main() {
  vec2 texel = 1.0 / vec2(textureSize(u_src, 0));
  vec2 c = gl_FragCoord.xy * texel;  // the texel's centre
  float s = texture(u_src, c + vec2(-0.5, -0.5) * texel).r + texture(u_src, c + vec2(0.5, -0.5) * texel).r +
            texture(u_src, c + vec2(-0.5, 0.5) * texel).r + texture(u_src, c + vec2(0.5, 0.5) * texel).r;
  o_color = vec4(0.25 * s);
}
