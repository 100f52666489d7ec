#pragma once
// Adapter between the renderer and the caustics pass of paper 004 section 5
// (viz/gl/caustics.hpp, huygens::viz::CausticsRenderer) and its accumulation-buffer blur
// (viz/gl/accum_blur.hpp). The renderer samples texture() over the ground rectangle
// origin()/extent() and multiplies by scale(), so that 1 is the light of a still surface.
#include <memory>
#include <span>

#include "caustics_cpu.hpp"
#include "gl.hpp"
#include "refraction.hpp"

namespace huygens {

struct RenderSettings;
struct ShipPose;

class CausticsStage {
 public:
  virtual ~CausticsStage() = default;
  /// False when the pass is not built in; the renderer then lights the ground uniformly.
  virtual bool available() const = 0;
  /// Renders the caustics of the visible field `eta` (rows x cols, m) into texture(); the
  /// ships cast their shadow into it.
  virtual void run(std::span<const float> eta, std::span<const ShipPose> ships, const RenderSettings& s) = 0;
  virtual GLuint texture() const = 0;
  /// World position of the texture's corner (u, v) = (0, 0) and its size (unit: m).
  virtual glm::dvec2 origin() const = 0;
  virtual glm::dvec2 extent() const = 0;
  /// Factor from the texture value to light relative to still water.
  virtual float scale() const = 0;
  /// The parameters of the last run (mesh size, sun, target, area model, cover_domain) in the
  /// frame of the visible field (x from its first column); null when the pass is not built in.
  virtual const viz::CausticsParams* params() const = 0;
};

/// The caustics pass for this grid and ground depth, or nullptr when it is not available.
std::unique_ptr<CausticsStage> make_caustics_stage(const GridPlacement& grid, double ground_z);

}  // namespace huygens
