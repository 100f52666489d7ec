// Shared by ground.frag, surface.frag and background.frag (prepended by the renderer, after
// solids_trace.glsl): the lit
// ground colour at a ground point G (world metres). Everything here is linear radiance (the
// colour uniforms and the ground texture arrive decoded from sRGB; the tone map encodes). The ground texture covers the visible region
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
uniform vec4 u_floor_rect;  // the floor under the visible region: x0, y0, x1, y1 (m)
uniform int u_deck;         // 1: a pool with a deck; beyond the floor rect are its walls
uniform int u_deep;         // 1: open ocean (no floor; the sea goes on beyond the region, flat)
uniform vec3 u_eye;
uniform int u_ortho;
uniform vec3 u_view_dir;
uniform float u_index;
uniform vec3 u_water_colour;
uniform vec3 u_sky;
uniform vec3 u_sky_zenith;
uniform int u_sky_gradient;
uniform vec3 u_sun_dir;
uniform int u_fresnel;          // 0 off, 1 paper, 2 Schlick
uniform int u_glint;             // 0 off, 1 the paper's, 2 the sun reflected by a rough surface
uniform vec3 u_sun_colour;
uniform float u_sun_radius;      // the sun's angular radius (rad)
uniform float u_sun_irradiance;  // the sun's irradiance on a plane facing it over the sky's radiance (sr)
uniform float u_slope_var;       // mean square slope of the waves shorter than the heightfield's grid
uniform float u_region_var;      // more of it in the region, whose central differences resolve less
uniform int u_eye_under;        // 1: the eye is under the water (below the rest level over the region)
uniform int u_far;              // 1: the sea beyond the region has the ambient sea's slopes
uniform sampler2D u_far_slopes; // RGBA32F: d eta/dx, d eta/dy, their squares' sum, 0: the ambient sea
uniform vec2 u_far_origin;      // world position of texture coordinate (0, 0) (m)
uniform float u_far_length;     // the ambient sea's period (m)

// sRGB value -> linear radiance (IEC 61966-2-1; viz/passes/srgb.hpp): the colours the shaders hold
// as constants are sRGB values, decoded here (uniforms and textures arrive decoded).
vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

// The sky in direction r: u_sky at the horizon to u_sky_zenith overhead, or uniform.
vec3 sky(vec3 r) {
  if (u_sky_gradient == 0) return u_sky;
  return mix(u_sky, u_sky_zenith, sqrt(clamp(r.z, 0.0, 1.0)));
}

// Light leaving deep water below a surface with normal n (open ocean, paper 003): the water's
// colour W scattered up from the sunlit water body, brighter on the faces turned to the sun,
// W (0.7 + 0.6 (n.s - s_z)) (a Lambert-like approximation; still water gives 0.7 W).
vec3 deep_water_colour(vec3 n) {
  vec3 s = normalize(u_sun_dir);
  return u_water_colour * max(0.7 + 0.6 * (max(dot(n, s), 0.0) - s.z), 0.2);
}

// Schlick's Fresnel reflectance for the cosine nv (paper 003).
float schlick(float nv) {
  float r0 = (u_index - 1.0) / (u_index + 1.0);
  return r0 * r0 + (1.0 - r0 * r0) * pow(1.0 - clamp(nv, 0.0, 1.0), 5.0);
}

// The reflectance for the cosine nv between the normal and the way to the eye (u_fresnel).
float fresnel(float nv) {
  if (u_fresnel == 1) return clamp(1.0 - 2.5 * nv, 0.0, 1.0);
  return u_fresnel == 2 ? schlick(nv) : 0.0;
}

// Smith's masking of a Beckmann surface of mean square slope m2 seen at cos_t from its normal
// (Walter, Marschner, Li & Torrance 2007, eq. 27: a = 1 / (sqrt(m2) tan t)).
float smith_g1(float cos_t, float m2) {
  float c = clamp(cos_t, 1e-4, 1.0), a = c / sqrt(m2 * (1.0 - c * c) + 1e-20);
  return a >= 1.6 ? 1.0 : (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

// The sun reflected by a surface of mean normal n seen along dir (u_glint 2): the facets that
// send the sun to the eye have the normal h = (s - dir) / |s - dir|; with their slopes Gaussian
// about the mean slope, of mean square slope m2 (Cox & Munk 1954; the Beckmann distribution
// D(h) = exp(-tan^2 t_h / m2) / (pi m2 cos^4 t_h), t_h the angle of h from n), the radiance is
//   L = E_sun F(h.v) D(h) G1(n.v) G1(n.s) / (4 n.v)
// (Cook & Torrance's microfacet BRDF times the irradiance E_sun n.s). m2 sums: the sun's disc
// (radius a: a uniform disc of facet tilts a / 2, a^2 / 8), the waves shorter than the grid
// (u_slope_var), the spread of the mean slope over the pixel (derivatives of a linear slope over
// a unit square: (|dz/dx|^2 + |dz/dy|^2) / 12) and `extra_var` (a mipmap's slope variance).
// A fleck of glint fades over its pixel, and far away where a pixel holds many waves the
// flecks merge into the glitter path of their slope statistics (Bruneton, Neyret & Holzschuch
// 2010). u_glint 1: the paper's clamp(100 n.h - 98.95).
vec3 glint(vec3 n, vec3 dir, float extra_var) {
  vec3 sun = normalize(u_sun_dir), v = -dir;
  vec2 z = n.xy / max(n.z, 1e-3);  // minus the slope (its derivatives' lengths are the same)
  vec2 zx = dFdx(z), zy = dFdy(z);
  if (u_glint == 1) return clamp(100.0 * dot(n, normalize(sun - dir)) - 98.95, 0.0, 1.0) * u_sun_colour;
  if (u_glint != 2) return vec3(0.0);
  float m2 = u_sun_radius * u_sun_radius / 8.0 + u_slope_var + (dot(zx, zx) + dot(zy, zy)) / 12.0 + extra_var;
  vec3 h = normalize(sun + v);
  float nv = dot(n, v), ns = dot(n, sun), nh = max(dot(n, h), 1e-3);
  if (nv <= 0.0 || ns <= 0.0) return vec3(0.0);
  float tan2 = (1.0 - nh * nh) / (nh * nh);
  float D = exp(-tan2 / m2) / (3.14159265 * m2 * nh * nh * nh * nh);
  float G = smith_g1(nv, m2) * smith_g1(ns, m2);
  return u_sun_irradiance * schlick(dot(h, v)) * D * G / (4.0 * nv) * u_sun_colour;
}

// The sea at a point P of z = 0 outside the simulated region (open ocean look): flat, or with the
// ambient sea's slopes (u_far; mipmapped, so far away they average out towards flat water and
// their variance in the texel goes to the glint, which spreads into the glitter path).
vec3 flat_sea(vec3 P) {
  vec3 dir = u_ortho != 0 ? u_view_dir : normalize(P - u_eye);
  vec3 n = vec3(0.0, 0.0, 1.0);
  float var = 0.0;  // the slopes' variance in the mipmap's texel (E |s|^2 - |E s|^2)
  if (u_far != 0) {
    vec2 uv = (P.xy - u_far_origin) / u_far_length, px = uv * vec2(textureSize(u_far_slopes, 0));
    vec4 t = texture(u_far_slopes, uv);
    n = normalize(vec3(-t.rg, 1.0));
    // a magnified texel (level of detail below 1) is not a spread: bilinear weights of the
    // texels around would count as variance, faded out as the level falls to 0
    float lod = 0.5 * log2(max(max(dot(dFdx(px), dFdx(px)), dot(dFdy(px), dFdy(px))), 1e-12));
    var = max(t.b - dot(t.rg, t.rg), 0.0) * clamp(lod, 0.0, 1.0);
  }
  return mix(deep_water_colour(n), sky(reflect(dir, n)), fresnel(max(dot(n, -dir), 0.0))) + glint(n, dir, var);
}

// 1 where the sun reaches the point P, 0 where a traced solid (solids_trace.glsl) is in the way: from
// a point under the water along the sun's ray refracted at the still surface (Snell) up to the rest
// level, then along the sun's direction (the refracted shadow of paper 000 Fig. 9c and paper 001).
float sun_visible(vec3 P) {
  if (u_trace_solids == 0 || u_traced_count == 0) return 1.0;
  vec3 sun = normalize(u_sun_dir), n;
  float t;
  int kind;
  if (P.z < -1e-4) {
    vec3 up_w = -refract(-sun, vec3(0.0, 0.0, 1.0), 1.0 / u_index);
    float len = -P.z / up_w.z;
    if (trace_solids(P, up_w, len, t, n, kind)) return 0.0;
    P += len * up_w;
  }
  return trace_solids(P, sun, 1e5, t, n, kind) ? 0.0 : 1.0;
}

// The lit ground at G (world metres) of height z: the sky's light and the sun's through the water
// (the caustics' light, 1 for still water), shaded where a solid stands between it and the sun.
vec3 lit_ground(vec2 G, float z) {
  vec2 uv = (G - u_ground_origin) / u_ground_extent;
  vec3 albedo = texture(u_ground, uv).rgb;
  float light = 1.0;
  vec2 cuv = (G - u_caustics_origin) / u_caustics_extent;
  if (u_use_caustics != 0 && all(greaterThanEqual(cuv, vec2(0.0))) && all(lessThanEqual(cuv, vec2(1.0))))
    light = u_caustics_scale * textureLod(u_caustics, cuv, 0.0).r;
  return albedo * (u_ambient + u_sun_light * light * sun_visible(vec3(G, z)));
}

// The pool deck around the water: pale stone tiles (the ground texture, lightened), lit by the
// sun without caustics.
vec3 deck_colour(vec2 G) {
  if (u_deep != 0) return flat_sea(vec3(G, 0.0));
  vec3 albedo = mix(texture(u_ground, (G - u_ground_origin) / u_ground_extent).rgb, srgb_to_linear(vec3(0.85, 0.84, 0.80)), 0.6);
  return albedo * (u_ambient + u_sun_light * sun_visible(vec3(G, 1e-4)));
}

// What the ray under water from the surface point P to its floor point F = (G, floor_z) meets,
// and where (`hit`): the lit floor, or, with a deck, the pool's wall where G lies beyond the floor
// under the visible region. The wall is the first wall plane the ray crosses; its tiles continue
// the floor's, unfolded outwards about the wall's foot (the point h above the foot shows the
// floor's texture h beyond it). Its light, with the floor's sky light u_ambient and still-water
// sunlight u_sun_light as units: the sun through still water, max(n_w . (-s_w), 0) / (-s_w.z) of
// the floor's (s_w the sun's ray refracted into the water, travelling; n_w the wall's inward
// normal; Lambert's cosines; no caustics), plus what a vertical wall on a wide floor sees of a
// uniform sky and of the lit floor, half of each (view factors 1/2): 0.5 u_ambient and
// 0.5 rho (u_ambient + u_sun_light), rho the floor's albedo at the wall's foot (one bounce).
vec3 seen_under_water(vec3 P, vec2 G, float floor_z, out vec3 hit) {
  hit = vec3(G, floor_z);
  // how far G lies beyond the floor (m; < 0 inside), and the wall's share of the pixel: the
  // floor's edge anti-aliased over the pixel's footprint (a staircase of whole pixels before)
  vec2 beyond = max(u_floor_rect.xy - G, G - u_floor_rect.zw);
  float outside = max(beyond.x, beyond.y), px = max(fwidth(outside), 1e-6);
  float w = clamp(0.5 + outside / px, 0.0, 1.0);
  if (u_deck == 0 || w == 0.0) return lit_ground(G, floor_z);
  vec3 floor_part = w < 1.0 ? lit_ground(clamp(G, u_floor_rect.xy, u_floor_rect.zw), floor_z) : vec3(0.0);
  vec2 d = G - P.xy;
  float f = 1e9;  // the ray's fraction P -> F at the nearest wall plane it reaches (within a pixel)
  vec2 nw = vec2(0.0);
  vec2 lo = (u_floor_rect.xy - P.xy) / d, hi = (u_floor_rect.zw - P.xy) / d;
  if (u_floor_rect.x - G.x > -px && lo.x < f) { f = lo.x; nw = vec2(1.0, 0.0); }
  if (G.x - u_floor_rect.z > -px && hi.x < f) { f = hi.x; nw = vec2(-1.0, 0.0); }
  if (u_floor_rect.y - G.y > -px && lo.y < f) { f = lo.y; nw = vec2(0.0, 1.0); }
  if (G.y - u_floor_rect.w > -px && hi.y < f) { f = hi.y; nw = vec2(0.0, -1.0); }
  f = clamp(f, 0.0, 1.0);
  hit = w < 0.5 ? hit : mix(P, vec3(G, floor_z), f);
  vec3 H = mix(P, vec3(G, floor_z), f);
  vec2 unfolded = clamp(H.xy, u_floor_rect.xy, u_floor_rect.zw) - nw * (H.z - floor_z);
  vec3 albedo = texture(u_ground, (unfolded - u_ground_origin) / u_ground_extent).rgb;
  vec3 foot = texture(u_ground, (clamp(H.xy, u_floor_rect.xy, u_floor_rect.zw) - u_ground_origin) / u_ground_extent).rgb;
  vec3 s_w = refract(-normalize(u_sun_dir), vec3(0.0, 0.0, 1.0), 1.0 / u_index);
  float lambert = max(dot(vec3(nw, 0.0), -s_w), 0.0) / max(-s_w.z, 0.1);
  vec3 wall = albedo * (0.5 * u_ambient + u_sun_light * lambert + 0.5 * foot * (u_ambient + u_sun_light));
  return mix(floor_part, wall, w);
}

// Light along a path of `len` metres under water towards the eye, arriving with radiance c:
// absorbed as exp(-a_rgb len) and replaced by the water's own colour W scattered in (paper 003:
// c T + W (1 - T)); nothing without absorption.
uniform int u_absorption;
uniform vec3 u_absorb;
vec3 through_water(vec3 c, float len) {
  if (u_absorption == 0) return c;
  vec3 T = exp(-u_absorb * len);
  return c * T + u_water_colour * (1.0 - T);
}

// The ground under the water over terrain (u_use_bed, surface.frag): the bed's height at the grid
// points (R32F, m, the drawn frame), read bilinearly, and the grid's placement.
uniform sampler2D u_bed;
uniform int u_use_bed;
uniform vec2 u_grid_origin; // world position of grid point (0, 0) (m)
uniform vec2 u_grid_size;   // cols, rows
uniform float u_dx;

// h(s) = R_z(s) - b(R_xy(s)): the height of the ray's point R(s) = P + s t above the bed b.
float above_bed(vec3 P, vec3 t, float s) {
  vec3 r = P + s * t;
  return r.z - texture(u_bed, ((r.xy - u_grid_origin) / u_dx + 0.5) / u_grid_size).r;
}

// The smallest root in [0, 1] of A + B u + C u^2 (A > 0), or -1.
float first_root(float A, float B, float C) {
  if (abs(C) <= 1e-6 * (abs(A) + abs(B))) return B < 0.0 && -A / B <= 1.0 ? -A / B : -1.0;
  float disc = B * B - 4.0 * A * C;
  if (disc < 0.0) return -1.0;
  float q = -0.5 * (B + (B < 0.0 ? -1.0 : 1.0) * sqrt(disc));
  float u1 = q / C, u2 = q != 0.0 ? A / q : -1.0, best = -1.0;
  if (u1 >= 0.0 && u1 <= 1.0) best = u1;
  if (u2 >= 0.0 && u2 <= 1.0 && (best < 0.0 || u2 < best)) best = u2;
  return best;
}

// Where the ray P + s t going down from P (above the bed) first meets the bed. Paper 001 (Baboud &
// Decoret, "Realistic water volumes in real-time", sec. 3.2) traces the view ray through the
// volume between the ground and the surface heightfields, searching both together; here the
// rasteriser has found the surface point P already, and below it the refracted (or reflected) ray
// meets the ground alone, so only the ground heightfield is marched. The ray is cut where it
// crosses the grid lines x = x0 + j dx and y = y0 + i dx, found in order (the nearer of the next x
// line and the next y line: Amanatides & Woo's grid traversal); on a piece the bilinear bed along
// the ray is a quadratic in s, so h is the quadratic through its values at the piece's ends and
// middle (samples at most 0.71 cell apart in xy, and on every grid line, where a step's lip is),
//   h = A + B u + C u^2, A = h0, B = 4 hm - 3 h0 - h1, C = 2 h0 + 2 h1 - 4 hm, u in [0, 1],
// and the first piece where it has a root holds the hit, solved in closed form (no bisection).
// At most kBedPieces pieces (two bed reads each); beyond them, the plane at the bed's height at the
// last sample. viz/cpu/heightfield_march.hpp: the mirror (shader_bed_hit) and the exact hit.
const int kBedPieces = 128;
vec3 march_bed(vec3 P, vec3 t) {
  vec2 g = (P.xy - u_grid_origin) / u_dx, dir = t.xy / u_dx;
  vec2 inv = 1.0 / max(abs(dir), vec2(1e-4));  // s per grid line crossed
  vec2 next = mix(g - ceil(g) + 1.0, floor(g) + 1.0 - g, step(0.0, dir)) * inv;
  float s0 = 0.0, h0 = above_bed(P, t, 0.0);
  if (h0 <= 0.0) return P;
  for (int k = 0; k < kBedPieces; ++k) {
    float s1 = min(next.x, next.y);
    next += inv * vec2(equal(next, vec2(s1)));
    float hm = above_bed(P, t, 0.5 * (s0 + s1)), h1 = above_bed(P, t, s1);
    float u = first_root(h0, 4.0 * hm - 3.0 * h0 - h1, 2.0 * h0 + 2.0 * h1 - 4.0 * hm);
    if (u >= 0.0) return P + (s0 + u * (s1 - s0)) * t;
    s0 = s1;
    h0 = h1;
  }
  return P + s0 * t - t * (h0 / t.z);
}

// Where the ray P + s t going down meets the floor: the bed (march_bed), or the plane z = floor_z.
vec3 floor_hit(vec3 P, vec3 t, float floor_z) {
  return u_use_bed != 0 ? march_bed(P, t) : P + t * ((floor_z - P.z) / t.z);
}
