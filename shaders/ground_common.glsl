// Shared by ground.frag and surface.frag (prepended by the renderer): the lit ground
// colour at a ground point G (world metres). The ground texture covers the visible region
// (origin u_ground_origin, size u_ground_extent) and repeats outside it; the caustics
// texture (u_caustics_scale * value = light relative to still water) covers the ground
// rectangle u_caustics_origin/extent, light 1 outside it.
uniform sampler2D u_ground;
uniform sampler2D u_caustics;
uniform vec2 u_ground_origin;
uniform vec2 u_ground_extent;
uniform float u_ambient;
uniform float u_sun_light;
uniform int u_use_caustics;
uniform vec2 u_caustics_origin;
uniform vec2 u_caustics_extent;
uniform float u_caustics_scale;

vec3 lit_ground(vec2 G) {
  vec2 uv = (G - u_ground_origin) / u_ground_extent;
  vec3 albedo = texture(u_ground, uv).rgb;
  float light = 1.0;
  vec2 cuv = (G - u_caustics_origin) / u_caustics_extent;
  if (u_use_caustics != 0 && all(greaterThanEqual(cuv, vec2(0.0))) && all(lessThanEqual(cuv, vec2(1.0))))
    light = u_caustics_scale * textureLod(u_caustics, cuv, 0.0).r;
  return albedo * (u_ambient + u_sun_light * light);
}
