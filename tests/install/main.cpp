// The installed package in use: a scene from inline JSON (parse_scene_text + make_solver), a
// Gaussian hump sigma 0.1 m, A 1 cm released from rest at the centre of a periodic 2 m square,
// five steps of 1/60 s of the FFT Huygens propagator (paper 004 eq. 1; Loviscach 2003). The
// height must be finite everywhere, and at the hump's centre nonzero and within 1e-3 A of the
// exact Cauchy-Poisson solution (validation library) less the hump's mean over the square,
// 2 pi sigma^2 A / L^2 (the periodic grid carries no k = 0 mode). Exit 0 when so, 1 otherwise.
#include <cmath>
#include <cstdio>
#include <exception>

#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
#include "huygens/validation/reference/cauchy_poisson.hpp"

namespace {

constexpr const char* kScene = R"({
  "solver": "huygens",
  "grid": {"n": 64, "length_m": 2.0, "margin": 0, "cutoff": false},
  "time": {"dt_s": 0.016666666666666666, "display_per_step": 1},
  "initial": [{"type": "gaussian", "x_m": 1.0, "y_m": 1.0, "sigma_m": 0.1, "amplitude_m": 0.01}]
})";

int run() {
  auto solver = huygens::make_solver(huygens::parse_scene_text(kScene, "install test"), huygens::RunOptions{false});
  const int steps = 5;
  for (int i = 0; i < steps; ++i) solver->step();
  const huygens::RenderGrid g = solver->render_info().grid;
  const auto h = solver->height();
  for (float v : h)
    if (!std::isfinite(v)) {
      std::printf("FAIL: non-finite height\n");
      return 1;
    }
  const auto col = static_cast<std::size_t>(std::lround((1.0 - g.x0_m) / g.dx_m));
  const auto row = static_cast<std::size_t>(std::lround((1.0 - g.y0_m) / g.dx_m));
  const double eta = h[row * g.cols + col];
  huygens::CauchyPoissonGaussian exact;  // default water, sigma 0.1 m, A 1 cm, as the scene
  const double pi = 3.14159265358979323846, length_m = 2.0;
  const double mean = 2 * pi * exact.sigma_m * exact.sigma_m * exact.amplitude_m / (length_m * length_m);
  const double ref = huygens::cauchy_poisson_eta(exact, 0.0, solver->time()) - mean;
  const bool ok = eta != 0.0 && std::abs(eta - ref) <= 1e-3 * exact.amplitude_m;
  std::printf("huygens install test: t = %.4f s, height at the hump %.6g m, exact %.6g m: %s\n", solver->time(), eta,
              ref, ok ? "pass" : "FAIL");
  return ok ? 0 : 1;
}

}  // namespace

int main() {
  try {
    return run();
  } catch (const std::exception& e) {
    std::printf("FAIL: %s\n", e.what());
    return 1;
  }
}
