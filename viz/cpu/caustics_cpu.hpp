// CPU side of the caustics of paper 004 section 5 (no GL here): the heightfield view,
// the parameters, the per-vertex refraction of sun rays onto the ground (the paper's
// linear approximation and the exact Snell projection), the ship-shadow outline, and
// the photon-histogram reference of papers 001/003 used to validate the renderer.
//
// Geometry: the water surface at rest is the plane z = 0, the heightfield eta(x, y) is
// sampled at x = j dx, y = i dx (row i, column j; the surface domain is
// [0, (cols-1) dx] x [0, (rows-1) dx]), the ground is the plane z = -depth. Sun light
// travels along the unit vector s (s_z < 0). Refraction (Snell, vector form, relative
// index r = 1/n): t = r s + (r cos_i - sqrt(1 - r^2 (1 - cos_i^2))) N, cos_i = -N.s,
// N = (-eta_x, -eta_y, 1)/|.|. A ray entering at (x, y, eta) reaches the ground at
// (x, y) + (eta + depth) t_xy / (-t_z).
// The caustics texture covers the ground rectangle onto which the flat surface projects
// (the surface domain shifted by the flat-water displacement), so a still surface gives
// uniform light filling the texture exactly.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace huygens::viz {

/// A read-only view of a heightfield (row-major, rows = y, cols = x).
struct HeightfieldView {
  std::span<const float> eta;  ///< surface elevation (unit: m), rows*cols values
  int rows = 0;                ///< samples along y
  int cols = 0;                ///< samples along x
  float dx_m = 0.0f;           ///< grid spacing (unit: m)
  float depth_m = 1.0f;        ///< depth of the ground below the surface at rest (unit: m)
};

/// How a surface triangle's vertices are projected onto the ground.
enum class CausticsProjection {
  Linear,  ///< paper 004 sec. 5: (x, y) = (x0, y0) + [a b; c d] (eta_x, eta_y), coefficients from
           ///< numerical derivatives of the exact projection at rest (the ray starts at z = 0)
  Exact,   ///< exact Snell refraction of the ray entering at (x, y, eta) and its intersection with z = -depth
};

/// How each projected triangle's brightness is made inversely proportional to its area.
enum class CausticsArea {
  Mip,       ///< paper 004 sec. 5: trilinear MIP map whose levels are constant, each 4x brighter
  Explicit,  ///< brightness = (surface triangle area) / (ground triangle area), computed per triangle
};

struct CausticsParams {
  /// Caustics mesh vertices along x (the paper's 96).
  int mesh_cols = 96;
  /// Caustics mesh vertices along y.
  int mesh_rows = 96;
  /// Caustics texture width (unit: texels).
  int texture_width = 512;
  /// Caustics texture height (unit: texels).
  int texture_height = 512;
  /// Refractive index of water (unit: 1).
  float refractive_index = 1.333f;
  /// Direction sun light travels, need not be normalised, z < 0 (unit: 1).
  std::array<float, 3> sun_dir{0.0f, 0.0f, -1.0f};
  /// Vertex projection.
  CausticsProjection projection = CausticsProjection::Linear;
  /// Brightness model.
  CausticsArea area = CausticsArea::Mip;
  /// Float (R32F) caustics target instead of the paper's 8-bit one.
  bool float_target = false;
  /// Value of unit irradiance (still water) in the 8-bit target (unit: 8-bit level); float targets store 1.
  float unit_level_u8 = 32.0f;
  /// MIP mode: still water selects level 2 + mip_lod_offset (a texture() LOD bias); the constant
  /// levels are 4^(L-2) / (1 + 3 mip_lod_offset), so still water still reads 1. 0 puts still water
  /// on a level (the kink of the piecewise-linear interpolation: brightening is overstated 2x);
  /// 0.5 centres it between two, which halves the MIP mode's error against the photon reference
  /// (huygens-caustics-bench) (unit: MIP levels, in [0, 1)).
  float mip_lod_offset = 0.5f;
  /// MIP mode variant (not in the paper): take the level of detail from the area scale
  /// sqrt|det J| of the surface-to-ground map (textureGrad) instead of GL's own lambda, which
  /// follows the more compressed axis only and so overstates line-like caustics.
  bool mip_isotropic_lod = false;
  /// Light carried by a triangle: its beam cross-section (the area of its projection along the
  /// sun onto z = 0; exact flux for an oblique sun) if true, or the same for every triangle (the
  /// paper) if false. Identical for an overhead sun.
  bool flux_by_beam_area = true;
  /// The texture covers the ground right below the surface domain, [0, W] x [0, H], instead of
  /// the still-water projection of the domain (shifted by D tan(theta_t) along the sun): the
  /// mesh's rest positions move back along the sun by that shift, so that every floor point
  /// under the water gets its light (no seam where the texture would stop). Rays entering
  /// outside the domain see the border's height continued flat (the field's edge value), i.e.
  /// the still-water light 1 in a strip D tan(theta_t) wide on the sun's side.
  bool cover_domain = false;
  /// Explicit mode: the largest square block of mesh cells (a power of 2 >= 4) drawn as one fan
  /// where its light is uniform (caustics_mesh_triangles); 0 draws every cell's two triangles.
  int merge_block = 0;
  /// A block is merged when its cells' gains agree to this ratio, max / min - 1 (unit: 1) ...
  float merge_gain_tolerance = 0.005f;
  /// ... and every vertex inside it is within this distance, ground and surface coordinates
  /// alike, of the bilinear map through its four corners (unit: texels).
  float merge_position_tolerance = 0.05f;
  /// Explicit mode, float target, merge_block > 0, at least half the blocks still: the target starts at still-water
  /// light 1 and the blocks of merge_block^2 cells that are still (gains within merge_gain_tolerance of 1, vertices
  /// within merge_position_tolerance of their rest positions, away from the ship's shadow) are not drawn; every other
  /// block takes its rest footprint's light 1 away (a quad of gain -1) and adds its triangles'
  /// (caustics_mesh_triangles).
  bool skip_still = false;
};

/// Mesh vertices per side that resolve the field's caustics: `per_wavelength` cells per dominant
/// wavelength lambda = 2 pi rms(grad eta) / rms(laplacian eta) (the k^4-weighted mean: the
/// curvature that focuses light, so short rings on a long swell are resolved), at least `min_n`
/// and at most the field's own points along its longer side (unit: vertices).
int mesh_size_for_field(const HeightfieldView& field, double per_wavelength = 8.0, int min_n = 96);

/// Horizontal displacement (dx, dy) on the ground of the ray entering a surface point with
/// slopes (gx, gy) = (d eta/dx, d eta/dy) at height eta above rest. Exact Snell refraction.
std::array<double, 2> refract_displacement(const CausticsParams& p, double depth_m, double eta, double gx, double gy);

/// The paper's linear approximation, coefficients x0 = displacement at rest and
/// [a b; c d] = d(displacement)/d(gx, gy) at rest (numerical central derivatives of the
/// exact projection, as the paper does for its section 4 coefficients).
struct LinearProjection {
  double x0 = 0, y0 = 0;              ///< displacement of a ray through still water (unit: m)
  double a = 0, b = 0, c = 0, d = 0;  ///< d(dx,dy)/d(gx,gy) (unit: m per unit slope)
};
LinearProjection linear_projection(const CausticsParams& p, double depth_m);

/// The ground rectangle the caustics texture covers: origin (unit: m) and size (unit: m).
struct GroundRect {
  double x0 = 0, y0 = 0, width = 0, height = 0;
};
GroundRect ground_rect(const CausticsParams& p, const HeightfieldView& field);

/// The caustics mesh on the CPU: heights bilinearly sampled from the full heightfield at the
/// mesh vertices, slopes by central differences on the mesh (one-sided at its border), each
/// vertex projected onto the ground. Sized once, refilled each frame without allocation.
///
/// Skirt: the texture covers exactly the still-water projection of the domain, so wherever a
/// wave moves the border vertices inwards the outer texels would receive no light at all
/// (short black lines along the texture's edge, seen through the water in huygens-viz). A
/// ring of skirt vertices outside the border closes that gap: each continues the map linearly
/// from its anchor (the nearest border vertex), P_ring = P_anchor + r (P_anchor - P_inner) per
/// outward axis, in ground and surface coordinates alike, so a skirt quad has about the
/// Jacobian, hence the irradiance, of the border cell next to it. The reach r >= 1 (cells, one
/// for the whole ring, at most 16) is the smallest that puts every ring vertex at least one
/// texel beyond the texture's edge; where a fold at the border defeats that, the ground
/// position is pushed out to that margin. So the ring encloses the whole texture and every
/// texel is covered (the boundary of the map winds once around it). Skirt vertices are
/// numbered after the rows*cols mesh vertices.
struct CausticsMesh {
  int cols = 0, rows = 0;
  std::vector<float> height;     ///< sampled elevation per vertex (unit: m)
  std::vector<float> ground_uv;  ///< projected vertex position in texture coordinates [0,1]^2 of the ground rect
  /// where the sun ray through the vertex crosses z = 0, in [0,1]^2 of the surface domain (the
  /// vertex position at rest when the sun is overhead or flux_by_beam_area is off): the
  /// triangle's area here is its beam cross-section, and MIP / shadow lookups use it
  std::vector<float> surface_uv;
  /// two triangles per mesh cell, then two per skirt cell (indices >= rows*cols are skirt vertices)
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> skirt_anchor;  ///< border vertex each skirt vertex continues
  std::vector<std::int8_t> skirt_dir;       ///< its outward direction (x, y) in {-1, 0, 1}^2, 2 per vertex
  std::vector<float> skirt_ground_uv;       ///< skirt vertices in ground texture coordinates (2 per vertex)
  std::vector<float> skirt_surface_uv;      ///< skirt vertices in surface coordinates (2 per vertex)
  float skirt_reach = 1;                    ///< the reach r of the last update (unit: mesh cells)
  /// The triangles to draw (caustics_mesh_triangles): `indices`, or with merged blocks fewer
  /// (capacity reserved at init: no allocation per frame), and each one's gain.
  std::vector<std::uint32_t> draw_indices;
  std::vector<float> gains;
  std::vector<float> cell_gain;  ///< scratch: the gain of every triangle of `indices`
  /// skip_still: the rest footprints' corners (ground = surface coordinates, 2 per vertex),
  /// numbered after the skirt's vertices in `draw_indices` (capacity reserved at init)
  std::vector<float> rest_uv;
  bool start_still = false;               ///< the draw list assumes a target cleared to still-water light
  std::vector<std::uint8_t> block_still;  ///< scratch: 1 per still block (skip_still)
  std::size_t vertex_count() const { return std::size_t(cols) * rows + skirt_anchor.size(); }
};
void caustics_mesh_init(const CausticsParams& p, CausticsMesh& mesh);
void caustics_mesh_update(const CausticsParams& p, const HeightfieldView& field, CausticsMesh& mesh);

/// Explicit mode's draw list after caustics_mesh_update: per triangle the gain
/// unit * (surface area) / (ground area), both in texels (unit = 1 in a float target,
/// unit_level_u8 / 255 in the 8-bit one; the surface area is the beam cross-section, so every
/// triangle delivers exactly the light its surface triangle receives). With merge_block > 0 a
/// block of merge_block^2 cells whose light is uniform (gains within merge_gain_tolerance,
/// vertices within merge_position_tolerance of the corners' bilinear map), else each of its
/// quarters recursively down to 4 x 4 cells, is drawn as a fan from its centre vertex to every
/// vertex on its boundary: 4 b triangles instead of 2 b^2, the same light in total (the fan
/// tiles the same polygon, so the surface areas sum to the same beam), and no cracks next to
/// finer blocks (the boundary keeps all its vertices). Under llvmpipe the caustics pass costs
/// about its triangle count, and still or uniformly sloped water is most of many scenes.
/// `shadow_uv` (skip_still): the bounding box (u0, v0, u1, v1) of the ship's shadow in surface
/// coordinates; blocks reaching into it are drawn (the shadow's mask darkens them).
void caustics_mesh_triangles(const CausticsParams& p, CausticsMesh& mesh,
                             std::array<float, 4> shadow_uv = {1.0f, 1.0f, 0.0f, 0.0f});

/// Ship shadow: a convex hull outline (counter-clockwise or clockwise, metres, surface frame),
/// at height `height_m` above the surface at rest; it is projected along the sun onto the
/// surface. make_ellipse_hull() builds an elliptic outline.
struct ShipShadow {
  std::vector<std::array<float, 2>> outline;  ///< convex polygon (unit: m)
  float height_m = 0.0f;                      ///< height of the shadow-casting outline above z = 0 (unit: m)
};
ShipShadow make_ellipse_hull(float cx_m, float cy_m, float heading_rad, float length_m, float beam_m,
                             int segments = 64);

/// Photon-histogram caustics reference (papers 001 and 003): photons on a jittered
/// `per_cell` x `per_cell` grid in every cell of the full-resolution surface, height and
/// slopes bilinearly interpolated from the full field (slopes: central differences),
/// refracted exactly, binned (nearest texel) on the ground rect. Result normalised to
/// irradiance relative to still water (1 = unlit-by-caustics level), texture_height rows
/// of texture_width, row 0 at the ground rect's y0 (GL's texture order). Photons inside the
/// shadow polygon (projected along the sun onto z = 0) carry no light.
std::vector<float> photon_caustics(const CausticsParams& p, const HeightfieldView& field, int per_cell,
                                   std::uint64_t seed, const ShipShadow* ship = nullptr);

/// Paper 000's "simple caustics" (section 2.4, eq. 4): the floor's light from the surface above it
/// along the sun (the point the still-water refracted sun ray from the texel left the surface),
///   I = a (z - z_min) / (z_max - z_min) + b |n_x + n_y| + c,
/// z the height there and n its unit normal (central differences, bilinear), z_min and z_max over
/// the field. The paper leaves a, b, c to the animator; here c makes the mean over the rect 1 (the
/// light the surface lets through), so still water reads 1 everywhere. Texture layout as
/// photon_caustics (the ground rect of `p`, row 0 at its y0).
struct SimpleCausticsWeights {
  float a = 1.0f, b = 2.0f;
};
std::vector<float> simple_caustics(const CausticsParams& p, const HeightfieldView& field,
                                   const SimpleCausticsWeights& w = {});

/// Projected shadow polygon on the surface plane z = 0 (the outline shifted along the sun).
std::vector<std::array<float, 2>> shadow_on_surface(const CausticsParams& p, const ShipShadow& ship);
/// Point-in-convex-polygon test (either orientation).
bool inside_convex(const std::vector<std::array<float, 2>>& poly, float x, float y);

/// Normalised 3x3 [1 2 1; 2 4 2; 1 2 1]/16 blur of a float image, clamp-to-edge.
std::vector<float> blur121_f32(std::span<const float> img, int width, int height);

/// Comparison of two caustics images (e.g. renderer against photon reference) on the
/// interior window that leaves out `border` texels on every side: both are divided by their
/// mean there; rel_l2 = ||a - b|| / ||b||, rel_l2_contrast = ||a - b|| / ||b - 1|| (relative
/// to the caustic contrast of b), max_abs = max |a - b| (all after normalisation).
struct CausticsDiff {
  double rel_l2 = 0, rel_l2_contrast = 0, max_abs = 0;
  double mean_a = 0, mean_b = 0;  ///< the means before normalisation
};
CausticsDiff compare_caustics(std::span<const float> a, std::span<const float> b, int width, int height, int border);

/// Synthetic heightfields for the tests and the benchmark (n x n points on an L x L domain).
struct SyntheticField {
  std::vector<float> eta;  ///< elevation (unit: m)
  int n = 0;               ///< points per side
  float dx = 0;            ///< spacing (unit: m)
  float depth = 0.5f;      ///< ground depth (unit: m)
  HeightfieldView view() const { return {eta, n, n, dx, depth}; }
};
/// (1 - 1/n) D: ground displacement per unit surface slope (linearised, sun overhead) (unit: m).
double focus_factor(double depth_m, double n);
/// Wind-like sea: five sines with wave vectors on the domain's periodic lattice, amplitudes
/// scaled so that sum (1 - 1/n) D A_k k^2 = strength (the largest local compression of the
/// ground map, sun overhead); `window` zeroes the outer tenth of the domain smoothly.
SyntheticField synthetic_wind_sea(int n, double L_m, double depth_m, double strength, bool window);
/// Ring wave A J0(k r) exp(-r^2 / (2 s^2)) about the centre, k = 2 pi / (0.15 L), s = 0.2 L; its
/// Hessian at the centre is -A k^2 / 2 I, and strength = (1 - 1/n) D A k^2 / 2.
SyntheticField synthetic_ring_wave(int n, double L_m, double depth_m, double strength);

}  // namespace huygens::viz
