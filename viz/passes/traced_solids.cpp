#include "traced_solids.hpp"

#include <algorithm>

namespace huygens {

void TracedSolids::set_prisms(std::span<const Prism> prisms) {
  prisms_.clear();
  for (const Prism& p : prisms) {
    const float kind = p.cylinder ? 1.0f : 0.0f;
    prisms_.emplace_back(p.lo.x, p.lo.y, p.z0, kind);
    prisms_.emplace_back(p.hi.x, p.hi.y, p.z1, 0.0f);
    prisms_.emplace_back(0.0f);
  }
  repack();
}

void TracedSolids::set_hulls(std::span<const ShipPose> ships) {
  hulls_.clear();
  for (const ShipPose& s : ships) {
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
}

}  // namespace huygens
