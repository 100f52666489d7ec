#include "traced_solids.hpp"

#include <algorithm>

namespace huygens {

void TracedSolids::set_prisms(std::span<const Prism> prisms) {
  prisms_.clear();
  prisms_lo_ = glm::vec3(1e30f), prisms_hi_ = glm::vec3(-1e30f);
  for (const Prism& p : prisms) {
    const float kind = p.cylinder ? 1.0f : 0.0f;
    const glm::dvec2 r = p.cylinder ? glm::dvec2(p.hi.x) : glm::dvec2(0.0);
    prisms_lo_ = glm::min(prisms_lo_, glm::vec3(glm::dvec3((p.cylinder ? p.lo - r : p.lo), p.z0)));
    prisms_hi_ = glm::max(prisms_hi_, glm::vec3(glm::dvec3((p.cylinder ? p.lo + r : p.hi), p.z1)));
    prisms_.emplace_back(p.lo.x, p.lo.y, p.z0, kind);
    prisms_.emplace_back(p.hi.x, p.hi.y, p.z1, 0.0f);
    prisms_.emplace_back(0.0f);
  }
  repack();
}

void TracedSolids::set_hulls(std::span<const ShipPose> ships) {
  hulls_.clear();
  hulls_lo_ = glm::vec3(1e30f), hulls_hi_ = glm::vec3(-1e30f);
  for (const ShipPose& s : ships) {
    // a box round the hull whatever its heading and tilt (slopes at most 0.3: 0.3 L of rise)
    const double reach = 0.5 * s.length + s.beam, tilt = 0.3 * s.length;
    hulls_lo_ = glm::min(hulls_lo_, glm::vec3(glm::dvec3(s.x - reach, s.y - reach, s.heave - s.draft - tilt)));
    hulls_hi_ = glm::max(
        hulls_hi_, glm::vec3(glm::dvec3(s.x + reach, s.y + reach, s.heave + hull_freeboard(s) + 0.1 * s.beam + tilt)));
    hulls_.emplace_back(s.x, s.y, s.heading, 2.0f);
    hulls_.emplace_back(s.length, s.beam, s.draft, hull_freeboard(s));
    hulls_.emplace_back(s.heave, s.slope_along, s.slope_across, 0.0f);
  }
  repack();
}

int TracedSolids::count() const { return static_cast<int>(packed_.size() / 3); }

void TracedSolids::repack() {
  packed_.assign(prisms_.begin(), prisms_.end());
  packed_.insert(packed_.end(), hulls_.begin(), hulls_.end());
  packed_.resize(std::min(packed_.size(), static_cast<std::size_t>(3 * kMax)));
  lo_ = glm::min(prisms_lo_, hulls_lo_), hi_ = glm::max(prisms_hi_, hulls_hi_);
}

}  // namespace huygens
