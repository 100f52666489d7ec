// Refraction texture coordinates of paper 004 section 4 (viz/cpu/refraction.hpp): Snell's law,
// the weighted-average mesh, and the linearised coordinates against the exact per-pixel
// Snell path, for the default scene and for synthetic waves.
#include "refraction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "camera.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
#include "scenes_dir.hpp"
#include "virtual_eye.hpp"

using namespace huygens;

TEST(Refraction, SnellsLawInVectorForm) {
  const double n = 1.333;
  for (double deg : {0.0, 10.0, 30.0, 60.0, 85.0}) {
    const double ti = deg * M_PI / 180.0;
    const glm::dvec3 d(std::sin(ti), 0.0, -std::cos(ti));
    const glm::dvec3 t = refract_dir(d, {0.0, 0.0, 1.0}, 1.0 / n);
    EXPECT_NEAR(glm::length(t), 1.0, 1e-12);
    EXPECT_NEAR(t.x, std::sin(ti) / n, 1e-12) << deg;  // sin(theta_t) = sin(theta_i) / n
    EXPECT_NEAR(t.y, 0.0, 1e-15);
    EXPECT_LT(t.z, 0.0);
  }
  // from water to air beyond the critical angle: total internal reflection
  EXPECT_EQ(refract_dir(glm::normalize(glm::dvec3(1.0, 0.0, 0.5)), {0.0, 0.0, -1.0}, 1.333), glm::dvec3(0.0));
}

TEST(Refraction, IndexOneFollowsTheStraightRay) {
  ViewRays v;
  v.eye = {1.0, 2.0, 5.0};
  RefractionParams p;
  p.index = 1.0;
  p.ground_z = -2.0;
  const glm::dvec3 P(3.0, 1.0, 0.1);
  const glm::dvec2 g = snell_ground_point(v, P, normal_from_differences(0.3, -0.2, 0.1), p);
  const glm::dvec3 d = glm::normalize(P - v.eye);
  const double s = (p.ground_z - P.z) / d.z;
  EXPECT_NEAR(g.x, P.x + s * d.x, 1e-12);
  EXPECT_NEAR(g.y, P.y + s * d.y, 1e-12);
}

TEST(Refraction, WeightedAverageKeepsLinearFields) {
  const std::size_t rows = 37, cols = 41, f = 4;
  std::vector<float> eta(rows * cols);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) eta[i * cols + j] = 0.01f * i - 0.02f * j + 0.5f;
  const SurfaceMeshLayout L = make_mesh_layout(rows, cols, f);
  EXPECT_EQ(L.col_idx.front(), 0u);
  EXPECT_EQ(L.col_idx.back(), cols - 1);
  EXPECT_EQ(L.row_idx.back(), rows - 1);
  std::vector<float> mesh(L.vertex_rows() * L.vertex_cols());
  subsample_heights(eta, rows, cols, f, L, mesh);
  for (std::size_t l = 0; l < L.vertex_rows(); ++l)
    for (std::size_t k = 0; k < L.vertex_cols(); ++k) {
      const std::size_t i = L.row_idx[l], j = L.col_idx[k];
      if (i < f || j < f || i + f > rows - 1 || j + f > cols - 1) continue;  // tent cut by the border
      EXPECT_NEAR(mesh[l * L.vertex_cols() + k], eta[i * cols + j], 1e-5);
    }
  // a plane wave of exactly the mesh spacing averages to (nearly) nothing: small waves only
  // reach the shading through the normals, as the paper intends
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) eta[i * cols + j] = std::cos(2.0 * M_PI * j / f);
  subsample_heights(eta, rows, cols, f, L, mesh);
  EXPECT_NEAR(mesh[2 * L.vertex_cols() + 3], 0.0, 1e-5);
}

namespace {
// Synthetic sea of a few progressive waves (amplitudes in metres) on a grid like the default scene's.
std::vector<float> synthetic_sea(const GridPlacement& g, double amp) {
  std::vector<float> eta(g.rows * g.cols);
  const double k1 = 2 * M_PI / 1.7, k2 = 2 * M_PI / 0.6, k3 = 2 * M_PI / 0.25;
  for (std::size_t i = 0; i < g.rows; ++i)
    for (std::size_t j = 0; j < g.cols; ++j) {
      const double x = g.x(j), y = g.y(i);
      eta[i * g.cols + j] = static_cast<float>(amp * (std::cos(k1 * (0.8 * x + 0.6 * y)) +
                                                      0.4 * std::cos(k2 * (0.3 * x - 0.95 * y) + 1.0) +
                                                      0.15 * std::cos(k3 * (-0.7 * x + 0.71 * y) + 2.0)));
    }
  return eta;
}
}  // namespace

// The linearisation is first order in height and slope: halving the waves divides the
// error between the linearised and the exact coordinates by about 4.
TEST(Refraction, LinearisationErrorIsSecondOrder) {
  GridPlacement g;
  g.rows = g.cols = 192;
  g.dx = 15.0 / 512 * 2;
  g.x0 = g.y0 = 64 * 15.0 / 512;
  const OrbitCamera cam = default_camera(g.x0, g.y0, g.cols * g.dx, g.rows * g.dx);
  RefractionParams p;
  p.ground_z = -3.0;
  const double texel = g.cols * g.dx / 512;
  const RefractionError e1 = compare_refraction(g, 4, synthetic_sea(g, 0.02), cam.rays(), p, texel);
  const RefractionError e2 = compare_refraction(g, 4, synthetic_sea(g, 0.01), cam.rays(), p, texel);
  std::printf("synthetic sea: max %.4f / %.4f texels, mean %.4f / %.4f texels (amplitude 2 cm / 1 cm)\n", e1.max_texels,
              e2.max_texels, e1.mean_texels, e2.mean_texels);
  EXPECT_GT(e1.mean_texels, 0.0);
  // 2 cm waves with slopes up to about 0.2 still stay within one texel
  EXPECT_LT(e1.max_texels, 1.0);
  EXPECT_GT(e1.mean_texels / e2.mean_texels, 3.0);
  EXPECT_LT(e1.mean_texels / e2.mean_texels, 5.0);
  // still water: only the linear interpolation of the base coordinate (u0, v0) across a mesh
  // triangle remains (it is not affine in x, y for index != 1): far below a texel
  const RefractionError e0 = compare_refraction(g, 4, std::vector<float>(g.rows * g.cols, 0.0f), cam.rays(), p, texel);
  std::printf("still water: max %.5f texels\n", e0.max_texels);
  EXPECT_LT(e0.max_texels, 0.05);
}

// Issue 5, test 3: for the default scene (its field after 1.5 s, the start-up camera) the
// linearised coordinates are within one ground-texture texel (visible width / 512) of the
// exact Snell path at every grid point; the maximum and the mean are printed.
TEST(Refraction, DefaultSceneLinearisedWithinOneTexel) {
  const std::string file = huygens::test::scenes_dir() + "/default.json";
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  const Scene scene = load_scene(file);
  RunOptions ro;
  ro.measure_plans = false;
  auto solver = make_solver(scene, ro);
  const RenderInfo info = solver->render_info();  // where the viewer places the field
  GridPlacement g;
  g.rows = info.grid.rows;
  g.cols = info.grid.cols;
  g.dx = info.grid.dx_m;
  g.x0 = info.grid.x0_m;
  g.y0 = info.grid.y0_m;
  RefractionParams p;
  p.ground_z = info.depth_m ? -*info.depth_m : -3.0;  // SceneView::kDeepGround
  while (solver->time() < 1.5) solver->step();
  const auto h = solver->height();
  const std::vector<float> eta(h.begin(), h.end());
  const OrbitCamera cam = default_camera(g.x0, g.y0, g.cols * g.dx, g.rows * g.dx);
  const double texel = g.cols * g.dx / 512;
  const RefractionError e = compare_refraction(g, 4, eta, cam.rays(), p, texel);
  float lo = 0, hi = 0;
  for (float v : eta) lo = std::min(lo, v), hi = std::max(hi, v);
  std::printf(
      "default scene at t = %.2f s (eta in [%.4f, %.4f] m): linearised vs exact max %.4f texels, "
      "mean %.5f texels (texel %.4f m)\n",
      solver->time(), lo, hi, e.max_texels, e.mean_texels, texel);
  EXPECT_LT(e.max_texels, 1.0);
}

// The camera ray through a pixel (used to drop stones under the cursor) passes through the
// world point that the view-projection matrix maps to that pixel; the centre ray hits the target.
TEST(Refraction, CameraRayThroughPixelInvertsTheProjection) {
  OrbitCamera cam = default_camera(1.0, 2.0, 10.0, 8.0);
  cam.yaw = 0.7;
  const double aspect = 16.0 / 9.0;
  glm::dvec3 o, d;
  cam.ray_through(0.0, 0.0, aspect, o, d);
  const double s = (cam.target.z - o.z) / d.z;
  EXPECT_NEAR(glm::length(o + s * d - cam.target), 0.0, 1e-9);
  const glm::dvec3 p(3.0, 7.0, 0.0);
  glm::dvec4 c = cam.projection(aspect) * cam.view() * glm::dvec4(p, 1.0);
  c /= c.w;
  cam.ray_through(c.x, c.y, aspect, o, d);
  const double s2 = (p.z - o.z) / d.z;
  EXPECT_NEAR(glm::length(o + s2 * d - p), 0.0, 1e-9);
}

// Issue 5, defect 1: the linearised coefficients are recomputed whenever the camera moves.
// The paper's way (central differences of the exact Snell calculation at every grid point)
// took 15-35 ms on the render thread for the 384 x 384 default; the renderer now uses the
// closed-form derivatives at the mesh vertices, bilinear in between (LinearisationMethod).
// (1) The closed form equals the central differences (perspective from above, a grazing
// view, straight down onto a point, parallel rays).
TEST(VizRefraction, ClosedFormSlopeDerivativesEqualCentralDifferences) {
  RefractionParams p;
  p.ground_z = -3.0;
  const double dx = 15.0 / 512;
  std::vector<ViewRays> views(4);
  views[0].eye = {7.5, -4.0, 6.0};
  views[1].eye = {-20.0, 3.0, 0.8};
  views[2].eye = {9.0, 11.0, 4.0};
  views[3].ortho = true;
  views[3].dir = glm::normalize(glm::dvec3(0.3, 0.5, -1.0));
  double worst = 0.0;
  for (const ViewRays& v : views)
    for (const glm::dvec3 P : {glm::dvec3(2.0, 3.0, 0.0), glm::dvec3(9.0, 11.0, 0.0), glm::dvec3(12.5, 1.0, 0.0)}) {
      glm::dvec2 du, dv;
      ASSERT_TRUE(snell_slope_derivatives(v, P, dx, p, du, dv));
      const double h = 1e-4 * dx;
      const glm::dvec2 nu = (snell_ground_point(v, P, normal_from_differences(h, 0.0, dx), p) -
                             snell_ground_point(v, P, normal_from_differences(-h, 0.0, dx), p)) /
                            (2.0 * h);
      const glm::dvec2 nv = (snell_ground_point(v, P, normal_from_differences(0.0, h, dx), p) -
                             snell_ground_point(v, P, normal_from_differences(0.0, -h, dx), p)) /
                            (2.0 * h);
      const double scale = std::max(glm::length(nu), glm::length(nv));
      ASSERT_GT(scale, 1.0);  // metres of ground per metre of height difference: far from zero
      const double e = std::max(glm::length(du - nu), glm::length(dv - nv)) / scale;
      worst = std::max(worst, e);
      EXPECT_LT(e, 1e-6) << "eye " << v.eye.x << "," << v.eye.y << "," << v.eye.z << " ortho " << v.ortho;
    }
  std::printf("closed-form vs central-difference (c, d, e, f): max relative difference %.2e\n", worst);
}

// (2) The renderer's coefficients (closed form at the mesh vertices, bilinear between) against
// the paper's (central differences at every grid point), on the default scene's grid and
// start-up camera: the ground points of a 2 cm synthetic sea differ by far less than the
// linearisation error itself (refraction_test: up to 0.7 texels for this sea). The run times
// of both are printed (same run; no bound, timing is not asserted).
TEST(VizRefraction, FastCoefficientsMatchThePapersNumericalOnes) {
  GridPlacement g;
  g.rows = g.cols = 384;
  g.dx = 15.0 / 512;
  g.x0 = g.y0 = 64 * g.dx;
  RefractionParams p;
  p.ground_z = -3.0;
  const OrbitCamera cam = default_camera(g.x0, g.y0, g.cols * g.dx, g.rows * g.dx);
  const SurfaceMeshLayout layout = make_mesh_layout(g.rows, g.cols, 4);
  using clock = std::chrono::steady_clock;
  auto timed = [&](const LinearisationMethod& m, double& ms) {  // fastest of 3 (a shared machine)
    LinearRefraction lin;
    ms = 1e30;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = clock::now();
      lin = linearise_refraction(g, layout, cam.rays(), p, m);
      ms = std::min(ms, std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    }
    return lin;
  };
  double ms_paper = 0, ms_fast = 0, ms_analytic_full = 0;
  const LinearRefraction paper = timed({false, false}, ms_paper);
  const LinearRefraction full = timed({true, false}, ms_analytic_full);
  const LinearRefraction fast = timed({}, ms_fast);
  ASSERT_EQ(fast.grid.size(), paper.grid.size());
  EXPECT_EQ(fast.vertex, paper.vertex);  // (u0, v0, a, b) are computed the same way
  double cmax = 0, dmax = 0, dfull = 0;
  for (std::size_t q = 0; q < paper.grid.size(); ++q) {
    cmax = std::max(cmax, std::abs(double(paper.grid[q])));
    dmax = std::max(dmax, std::abs(double(fast.grid[q]) - paper.grid[q]));
    dfull = std::max(dfull, std::abs(double(full.grid[q]) - paper.grid[q]));
  }
  // a 2 cm sea (slopes up to ~0.2) through both sets of coefficients
  std::vector<float> eta(g.rows * g.cols);
  for (std::size_t i = 0; i < g.rows; ++i)
    for (std::size_t j = 0; j < g.cols; ++j)
      eta[i * g.cols + j] = static_cast<float>(0.02 * std::cos(2 * M_PI / 1.7 * (0.8 * g.x(j) + 0.6 * g.y(i))) +
                                               0.008 * std::cos(2 * M_PI / 0.6 * (0.3 * g.x(j) - 0.95 * g.y(i)) + 1.0));
  std::vector<float> mesh(layout.vertex_rows() * layout.vertex_cols()), diffs(2 * g.rows * g.cols);
  subsample_heights(eta, g.rows, g.cols, 4, layout, mesh);
  height_differences(eta, g.rows, g.cols, diffs);
  const double texel = g.cols * g.dx / 512;
  double gmax = 0;
  for (std::size_t i = 0; i < g.rows; ++i)
    for (std::size_t j = 0; j < g.cols; ++j)
      gmax = std::max(gmax, glm::length(linear_ground_point(g, layout, fast, mesh, diffs, i, j) -
                                        linear_ground_point(g, layout, paper, mesh, diffs, i, j)) /
                                texel);
  std::printf(
      "coefficients (c, d, e, f): max |fast - paper| %.2e of max |c..f| (closed form at every point: %.2e); "
      "2 cm sea: ground points differ by at most %.2e texels\n"
      "time (this run, 1 thread, fastest of 3): paper %.2f ms, closed form at every grid point %.2f ms,\n"
      "closed form at the vertices + bilinear %.2f ms (x%.1f)\n",
      dmax / cmax, dfull / cmax, gmax, ms_paper, ms_analytic_full, ms_fast, ms_paper / ms_fast);
  EXPECT_LT(dfull / cmax, 1e-5);
  EXPECT_LT(dmax / cmax, 1e-3);
  EXPECT_LT(gmax, 0.01);
}

// Paper 000's virtual eye points (viz/cpu/virtual_eye.hpp).
TEST(VirtualEye, ReflectedEyeIsTheFocusOfTheReflectedRays) {
  const glm::dvec3 eye(1.0, -2.0, 3.0), E = huygens::reflected_eye(eye, 0.5);
  EXPECT_DOUBLE_EQ(E.z, -2.0);
  for (const glm::dvec3 p : {glm::dvec3(0.0, 0.0, 0.5), glm::dvec3(4.0, 1.0, 0.5)}) {
    const glm::dvec3 r = glm::reflect(glm::normalize(p - eye), glm::dvec3(0.0, 0.0, 1.0));
    EXPECT_NEAR(glm::length(glm::cross(r, glm::normalize(p - E))), 0.0, 1e-12);  // E, p and r in line
  }
}

TEST(VirtualEye, RefractedEyeSeesThePointAAlongItsRefractedRay) {
  const glm::dvec3 eye(0.0, -5.0, 4.0), lo(-0.5, -0.5, -2.0), hi(0.5, 0.5, 1.0);
  const glm::dvec3 a = huygens::nearest_waterline_point(eye, lo, hi, 0.0);
  EXPECT_NEAR(a.x, 0.0, 1e-12);
  EXPECT_NEAR(a.y, -0.5, 1e-12);  // where the line from the eye's foot to the axis enters the box
  const glm::dvec3 E = huygens::refracted_eye(eye, a, 1.333);
  EXPECT_NEAR(glm::length(E - a), glm::length(eye - a), 1e-12);  // eq. 2: |E_refr - a| = |E - a|
  const glm::dvec3 t = huygens::refract_dir(glm::normalize(a - eye), glm::dvec3(0.0, 0.0, 1.0), 1.0 / 1.333);
  EXPECT_NEAR(glm::length(glm::cross(glm::normalize(a - E), glm::normalize(t))), 0.0, 1e-12);
}

TEST(VirtualEye, RefractedRayThroughAPointUnderTheSurfaceMeetsIt) {
  const glm::dvec3 eye(0.3, -6.0, 2.5), b(0.1, 0.4, -1.7);
  const glm::dvec3 t = huygens::refracted_ray_through(eye, b, 0.0, 1.333);
  // back along -t from b to the surface, then the view ray from there must come from the eye
  const glm::dvec3 q = b - t * (b.z / t.z);
  const glm::dvec3 t_q = huygens::refract_dir(glm::normalize(q - eye), glm::dvec3(0.0, 0.0, 1.0), 1.0 / 1.333);
  EXPECT_NEAR(q.z, 0.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(glm::normalize(t_q), t)), 0.0, 1e-9);
}
