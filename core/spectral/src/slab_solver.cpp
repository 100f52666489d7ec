#include "huygens/spectral/slab_solver.hpp"

#ifdef HUYGENS_HAVE_MPI
#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace huygens {

MemoryEstimate huygens_slab_memory(const HuygensScene& s, int ranks) {
  const HuygensParams& p = s.params;
  const std::uint64_t n2 = static_cast<std::uint64_t>(p.n) * p.n, q2 = (p.n / 2 + 1) * std::uint64_t(p.n / 2 + 1);
  const std::uint64_t slab = (n2 + ranks - 1) / ranks;  // an even split, rounded up
  const std::uint64_t v = static_cast<std::uint64_t>(p.n - 2 * p.margin);
  const std::uint64_t vslab = v * ((v + ranks - 1) / ranks);
  const std::uint64_t c = sizeof(cfloat), f = sizeof(float);
  MemoryEstimate m;
  m.size_key = "$.grid.n";
  // Z, Z^, the height transforms A and B (+ chi, chidot at second order); quadrant tables
  m.add("propagator", 2 * c * slab + 6 * f * q2 + 2 * f * vslab);
  m.add("height", (s.stokes ? 4 : 2) * c * slab);
  if (p.runtime_sources) m.add("drop tables", 2 * f * slab);
  if (s.has_wind) m.add("wind sea", c * slab + sizeof(double) * q2 + 2 * c * q2);
  if (s.display_per_step > 1) m.add("interpolation", 3 * f * vslab);
  if (!s.ships.empty()) {
    const std::uint64_t p2 = static_cast<std::uint64_t>(s.ship_patch) * s.ship_patch;
    // huygens_memory: K patches per ship kept and K - 1 delay tables with the round trip every K steps
    const std::uint64_t k = static_cast<std::uint64_t>(std::max(1, s.params.round_trip_every));
    m.add("ship patches", c * p2 * (1 + (2 + k) * s.ships.size() + (k - 1)) + sizeof(double) * p2, "$.ships");
  }
  return m;
}

SlabGrid huygens_slab_grid(const HuygensParams& p, MPI_Comm comm, SlabTransforms how) {
  const bool bits_possible = slab_row_column(p.n, p.effort);
  if (how == SlabTransforms::one_process_bits && !bits_possible)
    throw std::invalid_argument("the one-process bits need FFTW_ESTIMATE plans and N >= 256");
  if (how == SlabTransforms::automatic)
    how = bits_possible ? SlabTransforms::one_process_bits : SlabTransforms::fftw_transposed;
  SlabGrid g = slab_grid(p.n, comm, how == SlabTransforms::fftw_transposed);
  g.row_column = how == SlabTransforms::one_process_bits;
  return g;
}

namespace {
// SlabFft behind the layout's transform interface
class SlabGridTransform final : public GridTransform {
 public:
  SlabGridTransform(const SlabGrid& g, cfloat* in, cfloat* out, int sign, PlanEffort effort, MPI_Comm comm)
      : fft_(g, in, out, sign, effort, comm),
        sent_(static_cast<std::uint64_t>(g.transposes() * slab_transpose_bytes(g))) {}
  void execute() const override { fft_.execute(); }
  void execute(cfloat* in, cfloat* out) const override { fft_.execute(in, out); }
  std::uint64_t sent_bytes() const override { return sent_; }

 private:
  SlabFft fft_;
  std::uint64_t sent_;
};
}  // namespace

GridLayout slab_layout(const SlabGrid& g, MPI_Comm comm, PlanEffort effort) {
  GridLayout l;
  l.n = g.n;
  l.row0 = g.row0;
  l.rows = g.rows;
  l.krow0 = g.krow0;
  l.krows = g.krows;
  l.transposed = g.transposed;
  l.alloc = g.alloc;
  l.whole = false;
  l.make_transform = [g, comm, effort](cfloat* in, cfloat* out, int sign) -> std::unique_ptr<GridTransform> {
    return std::make_unique<SlabGridTransform>(g, in, out, sign, effort, comm);
  };
  l.sum_over_ranks = [comm](std::span<double> v) {
    MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm);
  };
  return l;
}

HuygensSlabSolver::HuygensSlabSolver(const HuygensScene& scene, MPI_Comm comm, SlabTransforms how)
    : detail::SlabPart{huygens_slab_grid(scene.params, comm, how), comm},
      HuygensSolver(scene, slab_layout(slab_grid, comm, scene.params.effort)) {}

int HuygensSlabSolver::round_trip_step_transforms() const {
  return (propagator().spatial_round_trip() ? 2 : 0) + (scene().stokes ? 4 : 2);
}

double HuygensSlabSolver::bytes_sent_per_step() const {
  return transforms_per_step() * slab_grid.transposes() * slab_transpose_bytes(slab_grid);
}

nlohmann::json HuygensSlabSolver::meta() const {
  // the one-process description of the global grid, plus how it was split
  nlohmann::json j = HuygensSolver::meta();
  j["mpi"] = {{"ranks", slab_grid.ranks},
              {"layout", slab_grid.row_column   ? "row slabs; spectrum normal; row-column transforms (one-process bits)"
                         : slab_grid.transposed ? "row slabs; spectrum transposed (FFTW_MPI_TRANSPOSED_OUT/IN)"
                                                : "row slabs; spectrum normal (FFTW's MPI plans)"},
              {"transposes_per_step", transforms_per_step() * slab_grid.transposes()},
              {"height", "i IFFT[alpha Y] + i conj(IFFT[beta Y]): two transforms, no mirror exchange"}};
  return j;
}

}  // namespace huygens
#endif
