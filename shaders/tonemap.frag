#version 330 core
// The scene (linear radiance, half float, never clamped) into the 8-bit display image, tone-mapped
// once and then encoded to sRGB:
// identity up to the knee k, then k + (1 - k)(1 - exp(-(x - k)/(1 - k))), which has slope 1
// at k and tends to 1 (bright caustics and glints keep their shape instead of clipping).
uniform sampler2D u_hdr;
uniform int u_on;
uniform float u_knee;
out vec4 o_color;
void main() {
  vec3 x = max(texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb, vec3(0.0));
  if (u_on != 0) {
    float k = u_knee;
    vec3 hi = k + (1.0 - k) * (1.0 - exp(-(x - k) / (1.0 - k)));
    x = mix(x, hi, step(vec3(k), x));
  }
  // linear radiance -> sRGB value, once (IEC 61966-2-1)
  x = clamp(x, 0.0, 1.0);
  x = mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), x));
  o_color = vec4(x, 1.0);
}
