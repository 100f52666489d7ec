#pragma once
// Refraction of the ground seen through the water surface (paper 004, section 4).
//
// World frame of the renderer: x along the heightfield's columns, y along its rows, z up;
// the water at rest is the plane z = 0, the ground the plane z = ground_z < 0. The
// visible heightfield point (row i, col j) sits at (x0 + j dx, y0 + i dx).
//
// Exact path (per pixel): the view ray d (unit, from the eye to the surface point P) is
// refracted by Snell's law at the unit normal n, t = refract(d, n, 1/index), and followed
// to the ground: G = P + t (ground_z - P_z) / t_z. The ground texture is looked up at G.
//
// Linearised path (the paper's texture coordinates):
//   (u, v) = (u0, v0) + eta (a, b) + [c d; e f] (eta_u, eta_v)
// (u0, v0) is the ground point seen through the point (x, y, 0) of the water at rest;
// (a, b) its derivative with respect to the height eta of a flat water plane through the
// vertex (both given per mesh vertex, linearly interpolated across a triangle);
// eta_u, eta_v are the central height differences eta(i, j+1) - eta(i, j-1) and
// eta(i+1, j) - eta(i-1, j), and [c d; e f] the derivative of the ground point with respect
// to them at rest (given per original grid point). All six coefficients are derivatives of
// the exact Snell calculation (numerical in the paper; here (c, d, e, f) in closed form at the
// mesh vertices, bilinear in between: LinearisationMethod), computed at start-up and again
// whenever the camera moves. The normal from the differences is
//   n = normalize(-eta_u / (2 dx), -eta_v / (2 dx), 1).
// Coordinates are returned in metres on the ground plane; the renderer divides by the
// ground texture's extent.
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace huygens {

/// Where the view rays come from: a perspective eye, or parallel rays (orthographic).
struct ViewRays {
  /// Eye position for a perspective camera (unit: m).
  glm::dvec3 eye{0.0, 0.0, 10.0};
  /// True for an orthographic camera: every ray has direction `dir`.
  bool ortho = false;
  /// Ray direction of the orthographic camera (unit vector, pointing away from the eye).
  glm::dvec3 dir{0.0, 0.0, -1.0};
  /// Unit direction of the ray from the eye to the point p.
  glm::dvec3 toward(const glm::dvec3& p) const { return ortho ? dir : glm::normalize(p - eye); }
};

struct RefractionParams {
  /// Refractive index of the water relative to air (unit: 1).
  double index = 1.333;
  /// Height of the ground plane; the water at rest is z = 0 (unit: m).
  double ground_z = -2.0;
};

/// The visible heightfield's placement in the world.
struct GridPlacement {
  std::size_t rows = 0;
  std::size_t cols = 0;
  /// Grid spacing (unit: m).
  double dx = 1.0;
  /// World position of grid point (0, 0) (unit: m).
  double x0 = 0.0, y0 = 0.0;
  double x(std::size_t j) const { return x0 + static_cast<double>(j) * dx; }
  double y(std::size_t i) const { return y0 + static_cast<double>(i) * dx; }
};

/// Snell refraction of the unit direction d at the unit normal n (pointing to the side d
/// comes from), ratio = n_from / n_to. Returns the zero vector on total internal reflection.
glm::dvec3 refract_dir(const glm::dvec3& d, const glm::dvec3& n, double ratio);

/// Unit normal from central height differences: normalize(-eta_u/(2dx), -eta_v/(2dx), 1).
glm::dvec3 normal_from_differences(double eta_u, double eta_v, double dx);

/// Exact path: ground point (x, y) seen through the surface point p with unit normal n.
glm::dvec2 snell_ground_point(const ViewRays& view, const glm::dvec3& p, const glm::dvec3& n,
                              const RefractionParams& params);

/// Central height differences of a rows x cols field (one-sided, doubled, at the border),
/// interleaved (eta_u, eta_v) per point: out.size() = 2 rows cols.
void height_differences(std::span<const float> eta, std::size_t rows, std::size_t cols, std::span<float> out);

/// The subsampled surface mesh: vertex k along an axis sits at grid index idx[k]
/// (0, f, 2f, ..., and the last grid index), so the mesh covers the whole field.
struct SurfaceMeshLayout {
  std::vector<std::size_t> col_idx;  ///< grid column of each vertex column
  std::vector<std::size_t> row_idx;  ///< grid row of each vertex row
  std::size_t vertex_cols() const { return col_idx.size(); }
  std::size_t vertex_rows() const { return row_idx.size(); }
};
/// Layout for a subsampling factor f >= 1 (paper: 4, i.e. 96 x 96 vertices for 384 x 384).
SurfaceMeshLayout make_mesh_layout(std::size_t rows, std::size_t cols, std::size_t factor);
/// The mesh's triangles as vertex indices (row-major vertices), each quad split into (00, 10, 11)
/// and (00, 11, 01), the split linear_ground_point interpolates over.
std::vector<std::uint32_t> mesh_triangles(const SurfaceMeshLayout& layout);

/// Vertex heights by weighted average (paper 004, section 4): a tent window of half-width
/// f around the vertex, weights (f - |di|)(f - |dj|), renormalised at the border.
void subsample_heights(std::span<const float> eta, std::size_t rows, std::size_t cols, std::size_t factor,
                       const SurfaceMeshLayout& layout, std::span<float> out);

/// The linearised coefficients for one view.
struct LinearRefraction {
  /// Per mesh vertex (row-major over the layout): u0, v0, a, b (units: m, m, 1, 1).
  std::vector<float> vertex;
  /// Per grid point (row-major): c, d, e, f (unit: m per m of height difference).
  std::vector<float> grid;
};

/// How linearise_refraction finds (c, d, e, f). The paper takes numerical derivatives of the
/// exact calculation at every grid point; that costs 4 Snell evaluations per grid point (0.6 M
/// for the 384 x 384 default, 15-35 ms on the render thread at every camera move). Both
/// shortcuts below are on by default and leave the result within float rounding of it
/// (refraction_test): the derivatives at rest have a closed form (snell_slope_derivatives),
/// and they vary smoothly on the scale of the view distance, so evaluating them only at the
/// mesh vertices and interpolating bilinearly over each mesh cell (what the GPU's linear
/// filter would do) is ~factor^2 times cheaper.
struct LinearisationMethod {
  /// Closed-form derivatives (true) or central differences of snell_ground_point (false, the paper).
  bool analytic = true;
  /// Evaluate (c, d, e, f) at the mesh vertices and interpolate bilinearly to the grid points
  /// (true), or evaluate at every grid point (false, the paper).
  bool coarse = true;
};

/// Coefficients from derivatives of snell_ground_point at rest (paper 004, sec. 4): (u0, v0)
/// exactly, (a, b) by central differences in the height of a flat water plane, (c, d, e, f) as
/// `method` says.
LinearRefraction linearise_refraction(const GridPlacement& grid, const SurfaceMeshLayout& layout, const ViewRays& view,
                                      const RefractionParams& params, const LinearisationMethod& method = {});

/// Closed-form derivatives of snell_ground_point(view, p, n, params) at n = up with respect to
/// the central height differences eta_u and eta_v (n = normal_from_differences(eta_u, eta_v, dx)):
/// d_eta_u = (c, e), d_eta_v = (d, f). With the view ray d, c0 = -n.d, k = 1 - r^2 (1 - c0^2),
/// r = 1/index, t = r d + (r c0 - sqrt k) n and s = (ground_z - P_z) / t_z, a tilt dn of the
/// normal gives dc0 = -dn.d, dt = dc0 (r - r^2 c0 / sqrt k) n + (r c0 - sqrt k) dn and
/// dG = s (dt_xy - t_xy dt_z / t_z), with dn = (-1, 0, 0) / (2 dx) per unit eta_u and
/// (0, -1, 0) / (2 dx) per unit eta_v. Returns false where snell_ground_point is not smooth
/// there (total internal reflection, or a refracted ray that does not go down).
bool snell_slope_derivatives(const ViewRays& view, const glm::dvec3& p, double dx, const RefractionParams& params,
                             glm::dvec2& d_eta_u, glm::dvec2& d_eta_v);

/// Ground point of the linearised path at grid point (i, j), given the mesh heights and
/// the interleaved height differences, interpolated over the same triangles the GPU draws
/// (each quad split along the diagonal from its (0,0) to its (1,1) corner).
glm::dvec2 linear_ground_point(const GridPlacement& grid, const SurfaceMeshLayout& layout, const LinearRefraction& lin,
                               std::span<const float> mesh_heights, std::span<const float> diffs, std::size_t i,
                               std::size_t j);

/// Exact path at grid point (i, j): surface point at the interpolated mesh height, normal
/// from the full-resolution differences (what the per-pixel shader does at that point).
glm::dvec2 exact_ground_point(const GridPlacement& grid, const SurfaceMeshLayout& layout,
                              std::span<const float> mesh_heights, std::span<const float> diffs, const ViewRays& view,
                              const RefractionParams& params, std::size_t i, std::size_t j);

/// Distance between the linearised and the exact ground points over all grid points.
struct RefractionError {
  /// Largest distance (unit: texels of the ground texture).
  double max_texels = 0.0;
  /// Mean distance (unit: texels).
  double mean_texels = 0.0;
};
/// Compares both paths at every grid point; `texel_m` is the ground texture's texel size (m).
RefractionError compare_refraction(const GridPlacement& grid, std::size_t factor, std::span<const float> eta,
                                   const ViewRays& view, const RefractionParams& params, double texel_m);

}  // namespace huygens
