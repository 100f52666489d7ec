#version 330 core
// Caustics triangles, drawn with additive blending (GL_ONE, GL_ONE).
// MIP mode (paper 004 sec. 5): the brightness comes from a trilinear MIP map in surface
// coordinates whose levels are constant, each 4x brighter than the one below; the GPU picks
// the level from the screen-space derivatives of v_surface, i.e. from how much the triangle
// shrank on the ground, so brightness ~ 1/area. The ship's shadow is drawn black into the
// lower levels (Figure 7).
// EXPLICIT mode: brightness = the triangle's gain, unit * (surface area) / (ground area)
// computed on the CPU (CausticsRenderer::render), fetched by gl_PrimitiveID from a buffer
// texture, times the shadow mask.
in vec2 v_surface;
#ifdef EXPLICIT
uniform samplerBuffer u_gain;
uniform sampler2D u_mask;  // 1 = lit, 0 = ship shadow (surface coordinates)
uniform int u_use_mask;
#else
uniform sampler2D u_mip;
uniform float u_lod_bias;  // still water selects level 2 + u_lod_bias
uniform int u_isotropic;   // 1: level of detail from the area scale sqrt|det J| instead of the GPU's own
#endif
out vec4 o_color;
void main() {
#ifdef EXPLICIT
  // a negative gain takes still-water light away (CausticsParams::skip_still): never masked
  float g = texelFetch(u_gain, gl_PrimitiveID).r;
  float m = (u_use_mask != 0 && g > 0.0) ? texture(u_mask, v_surface).r : 1.0;
  o_color = vec4(g * m);
#else
  if (u_isotropic != 0) {
    // isotropic variant (not in the paper): texels per pixel from the triangle's area scale,
    // rho = sqrt|det J|, instead of GL's max(|J e_x|, |J e_y|), which sees only the more
    // compressed axis; lambda = log2(rho) + bias through explicit isotropic gradients
    vec2 size = vec2(textureSize(u_mip, 0));
    vec2 jx = dFdx(v_surface) * size, jy = dFdy(v_surface) * size;
    float rho = sqrt(abs(jx.x * jy.y - jx.y * jy.x)) * exp2(u_lod_bias);
    o_color = vec4(textureGrad(u_mip, v_surface, vec2(rho, 0.0) / size, vec2(0.0, rho) / size).r);
  } else {
    o_color = vec4(texture(u_mip, v_surface, u_lod_bias).r);
  }
#endif
}
