#pragma once
// The "solver": "huygens" scene (DESIGN.md section 6) on the Huygens propagator of paper 004
// section 3. Pipeline per full step (stages are timed and counted separately):
//   propagate -> cutoff -> spectrum -> drops (only when the scene has drops) -> height
// Ships (spatial sources) belong between cutoff and spectrum, wind and Stokes height after it.
#include <memory>
#include <string>
#include <vector>

#include "huygens/huygens_propagator.hpp"
#include "huygens/scene.hpp"
#include "huygens/solver.hpp"

namespace huygens {

/// An elevation released from rest (initial "gaussian" or a timed drop).
struct GaussianSource {
  /// Release time (unit: s); 0 for initial conditions.
  double t = 0;
  /// Centre (unit: m), in the full grid's frame.
  double x_m = 0, y_m = 0;
  /// Standard deviation of the Gaussian (unit: m).
  double sigma_m = 0.1;
  /// Peak elevation (unit: m); a drop of depth d is a depression, amplitude -d.
  double amplitude_m = 0.01;
};

/// A progressive plane wave present at t = 0.
struct PlaneWaveSource {
  /// Wavelength (unit: m).
  double wavelength_m = 1.0;
  /// Elevation amplitude (unit: m).
  double amplitude_m = 0.01;
  /// Direction of travel, counter-clockwise from +x (unit: degrees).
  double direction_deg = 0.0;
};

/// Everything a Huygens scene specifies.
struct HuygensScene {
  HuygensParams params;
  /// Displayed frames per full step (unit: 1); used by the renderer's time interpolation.
  int display_per_step = 1;
  std::vector<GaussianSource> initial_gaussians;
  std::vector<PlaneWaveSource> initial_plane_waves;
  /// Timed drops, sorted by time.
  std::vector<GaussianSource> drops;
};

/// Parses and checks a "huygens" scene; every error is a SceneError naming the JSON path.
HuygensScene parse_huygens_scene(const Scene& scene, const RunOptions& options = {});

class HuygensSolver : public Solver {
 public:
  explicit HuygensSolver(const HuygensScene& scene);
  void step() override;
  double time() const override { return prop_.time(); }
  std::int64_t steps() const override { return prop_.steps(); }
  std::vector<OutputField> outputs() override;
  nlohmann::json meta() const override;
  const StageStats& stats() const override { return prop_.stats(); }
  std::span<const float> height() override { return prop_.eta(); }
  std::size_t height_rows() const override { return static_cast<std::size_t>(prop_.visible_size()); }
  std::size_t height_cols() const override { return static_cast<std::size_t>(prop_.visible_size()); }
  std::span<const float> height_rate() override { return prop_.etadot(); }
  /// Supports cmd::Drop (a Gaussian depression released now; the height is refreshed).
  bool apply(const Command& c) override;

  HuygensPropagator& propagator() { return prop_; }
  const HuygensScene& scene() const { return scene_; }

 private:
  HuygensScene scene_;
  HuygensPropagator prop_;
  std::size_t next_drop_ = 0;
  int st_drops_ = -1;
};

}  // namespace huygens
