#include "huygens/spectral/grid_layout.hpp"

#include <algorithm>

namespace huygens {

namespace {
// Fft2D behind the layout's transform interface (the one-process plans, fft.hpp)
class WholeGridTransform final : public GridTransform {
 public:
  WholeGridTransform(int n, cfloat* in, cfloat* out, int sign, PlanEffort effort) : fft_(n, n, in, out, sign, effort) {}
  void execute() const override { fft_.execute(); }
  void execute(cfloat* in, cfloat* out) const override { fft_.execute(in, out); }

 private:
  Fft2D fft_;
};
}  // namespace

VisibleRows GridLayout::visible(int margin) const {
  const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(row0, margin);
  const std::ptrdiff_t hi = std::min<std::ptrdiff_t>(row0 + rows, n - margin);
  VisibleRows v;
  v.count = std::max<std::ptrdiff_t>(0, hi - lo);
  v.row0 = v.count > 0 ? lo - margin : 0;
  v.first = v.count > 0 ? lo - row0 : 0;
  return v;
}

GridLayout whole_grid_layout(int n, PlanEffort effort) {
  GridLayout g;
  g.n = n;
  g.rows = g.krows = n;
  g.alloc = static_cast<std::ptrdiff_t>(n) * n;
  g.make_transform = [n, effort](cfloat* in, cfloat* out, int sign) -> std::unique_ptr<GridTransform> {
    return std::make_unique<WholeGridTransform>(n, in, out, sign, effort);
  };
  g.sum_over_ranks = [](std::span<double>) {};
  return g;
}

}  // namespace huygens
