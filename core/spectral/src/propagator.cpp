#include "huygens/spectral/propagator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "huygens/common/finite.hpp"
#include "huygens/spectral/cutoff.hpp"
#include "huygens/spectral/rotation.hpp"

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
std::uint64_t elapsed_ns(std::chrono::steady_clock::time_point t0) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
}
// one complex float moved as a unit (may alias the float data)
using Bits64 = std::uint64_t __attribute__((may_alias));
// grids below this size run the non-FFT passes on one thread (a fork costs more than the pass)
constexpr int kParallelMin = 256;
bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }
}  // namespace

std::string huygens_params_error(const HuygensParams& p) {
  if (p.n < 16 || p.n > 32768 || !power_of_two(p.n)) return "grid n must be a power of two in [16, 32768]";
  if (!(p.length_m > 0) || !std::isfinite(p.length_m)) return "grid length must be > 0";
  if (p.margin < 0) return "margin must be >= 0";
  if (2 * p.margin >= p.n) return "margin too large: 2 * margin must be < n";
  if (p.absorber == Absorber::paper_quadratic && p.margin < 1) return "the quadratic cutoff needs margin >= 1";
  if (!(p.dt_s > 0) || !std::isfinite(p.dt_s)) return "dt must be > 0";
  if (!(p.water.gravity_mps2 >= 0) || !(p.water.surface_tension_npm >= 0) || !(p.water.density_kgpm3 > 0))
    return "water needs gravity >= 0, surface_tension >= 0, density > 0";
  if (p.water.gravity_mps2 == 0 && p.water.surface_tension_npm == 0) return "gravity and surface tension are both 0";
  if (!(p.water.depth_m > 0)) return "depth must be > 0 (or infinite)";
  if (p.check_every < 0) return "check_every must be >= 0";
  if (!(p.cutoff_time_s >= 0) || !std::isfinite(p.cutoff_time_s)) return "cutoff_time_s must be >= 0";
  if (p.round_trip_every < 1 || p.round_trip_every > 64) return "round_trip_every must be in [1, 64]";
  return {};
}

HuygensPropagator::HuygensPropagator(const HuygensParams& p) : HuygensPropagator(p, whole_grid_layout(p.n, p.effort)) {}

HuygensPropagator::HuygensPropagator(const HuygensParams& p, GridLayout layout)
    : p_(p),
      g_(std::move(layout)),
      checks_(!g_.whole),
      spatial_(p.absorber != Absorber::off || p.spatial),
      every_(std::clamp(p.round_trip_every, 1, 64)) {
  if (auto e = huygens_params_error(p); !e.empty()) throw std::invalid_argument(e);
  if (g_.n != p.n) throw std::invalid_argument("HuygensPropagator: the layout is not of grid n");
  // the packed height reads Z^(-k): on a slab the caller makes the height (StokesHeight)
  if (!g_.whole) p_.external_height = true;
  allocate();
  make_plans();  // before any data: a slab's measured planning overwrites the buffers
  if (p_.runtime_sources) reserve_sources();
  build_tables();
  register_stages();
}

void HuygensPropagator::allocate() {
  const std::size_t slab = static_cast<std::size_t>(g_.alloc);
  const std::size_t vv = static_cast<std::size_t>(visible_size()) * visible_size();
  z_ = AlignedBuffer<cfloat>(slab);
  s_ = AlignedBuffer<cfloat>(slab);
  const bool own_height = !p_.external_height;
  if (own_height) h_ = AlignedBuffer<cfloat>(slab);
  // per-mode tables depend on |k_x|, |k_y| only: one quadrant of (N/2+1)^2 values
  const std::size_t qq = static_cast<std::size_t>(p_.n / 2 + 1) * (p_.n / 2 + 1);
  rot_a_ = AlignedBuffer<float>(qq);
  rot_b_ = AlignedBuffer<float>(qq);
  if (p_.rotation == Rotation::lifting) rot_c_ = AlignedBuffer<float>(qq);
  if (own_height) {
    alpha_ = AlignedBuffer<float>(qq);
    beta_ = AlignedBuffer<float>(qq);
  }
  cut_ = AlignedBuffer<float>(static_cast<std::size_t>(2 * p_.n));
  src_x_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(p_.n));
  src_y_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(p_.n));
  if (own_height) {
    eta_ = AlignedBuffer<float>(vv);
    etadot_ = AlignedBuffer<float>(vv);
  }
}

void HuygensPropagator::make_plans() {
  if (spatial_) inv_prop_ = g_.make_transform(z_.data(), z_.data(), Fft2D::backward);
  // the forward plan is part of the step only with the spatial round trip; otherwise the
  // construction-time sources that need it (plane waves, set_field) make it on demand on the whole
  // grid (Fft2D plans on copies), at once on a slab (its collective plans overwrite the buffers)
  if (spatial_ || !g_.whole) fwd_ = g_.make_transform(z_.data(), s_.data(), Fft2D::forward);
  if (!p_.external_height) inv_height_ = g_.make_transform(h_.data(), h_.data(), Fft2D::backward);
  for (auto* b : {&z_, &s_, &h_}) std::fill(b->data(), b->data() + b->size(), cfloat(0.0f, 0.0f));
}

void HuygensPropagator::register_stages() {
  const std::uint64_t field = static_cast<std::uint64_t>(g_.alloc) * sizeof(cfloat);
  const std::uint64_t table = static_cast<std::uint64_t>(p_.n / 2 + 1) * (p_.n / 2 + 1) * sizeof(float);
  const std::uint64_t vv = static_cast<std::uint64_t>(visible_size()) * visible_size();
  st_propagate_ = stats_.add("propagate", 2 * field + (p_.rotation == Rotation::lifting ? 3 : 2) * table);
  if (p_.absorber != Absorber::off) st_cutoff_ = stats_.add("cutoff", 2 * p_.n * sizeof(float));
  if (spatial_) st_spectrum_ = stats_.add("spectrum", 0);
  if (!p_.external_height) st_height_ = stats_.add("height", field + 2 * table + 2 * vv * sizeof(float));
}

HuygensPropagator::~HuygensPropagator() = default;

double HuygensPropagator::wavenumber(int i) const { return fft_wavenumber(i, p_.n, p_.length_m); }

void HuygensPropagator::build_tables() {
  const int n = p_.n;
  const double inv_nn = 1.0 / (static_cast<double>(n) * n);
  // the rotation carries the 1/N^2 of the FFT round trip when every step takes it; with the
  // round trip every K > 1 steps the tables are unscaled and propagate() passes 1/N^2 (a power
  // of two: the same bits as a scaled table) on the steps that take it
  const double rot_scale = spatial_ && every_ == 1 ? inv_nn : 1.0;
  const int q = n / 2 + 1;  // quadrant tables: index (|row index|, |col index|), 0..N/2
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int r = 0; r < q; ++r) {
    const double ky = wavenumber(r);
    for (int c = 0; c < q; ++c) {
      const double kx = wavenumber(c);
      const double k = std::hypot(kx, ky);
      const double w = omega(p_.water, k);
      const std::size_t i = static_cast<std::size_t>(r) * q + c;
      const RotationEntry e = rotation_entry(p_.rotation, w * p_.dt_s, rot_scale);
      rot_a_[i] = e.a;
      rot_b_[i] = e.b;
      if (p_.rotation == Rotation::lifting) rot_c_[i] = e.c;
      // height packing: P = i (alpha Z^(k) + beta conj Z^(-k)), 1/N^2 folded in
      if (alpha_.size() == 0) {
        // external height: no packing tables
      } else if (k > 0 && w > 0) {
        const double kow = k / w;
        alpha_[i] = static_cast<float>(0.5 * (kow + k) * inv_nn);
        beta_[i] = static_cast<float>(0.5 * (k - kow) * inv_nn);
      } else {
        alpha_[i] = 0.0f;
        beta_[i] = 0.0f;
      }
    }
  }
  fill_cutoff_window(p_, cut_.data());  // paper 004's quadratic cutoff h(p)
}

void HuygensPropagator::clear() {
  for (auto* b : {&z_, &s_, &h_}) std::fill(b->data(), b->data() + b->size(), cfloat(0.0f, 0.0f));
  for (auto* b : {&eta_, &etadot_}) std::fill(b->data(), b->data() + b->size(), 0.0f);
}

void HuygensPropagator::set_field(std::span<const cfloat> z) {
  if (!g_.whole) throw std::logic_error("HuygensPropagator::set_field: whole grid only");
  if (z.size() != z_.size()) throw std::invalid_argument("set_field: size is not N*N");
  for (std::size_t i = 0; i < z.size(); ++i) z_[i] = z[i];
  if (!fwd_) fwd_ = g_.make_transform(z_.data(), s_.data(), Fft2D::forward);
  fwd_->execute();
  if (p_.external_height) return;
  const bool c = check_now_;
  check_now_ = false;
  height();
  check_now_ = c;
}

// ---- the step -------------------------------------------------------------------------------

void HuygensPropagator::check_stage(int stage, std::span<const cfloat> v) {
  if (!all_finite(v)) checks_.fail(stats_, stage, steps_ + 1);
}

void HuygensPropagator::run_transform(const GridTransform& t, int stage) {
  const auto t0 = std::chrono::steady_clock::now();
  t.execute();
  fft_ns_ += elapsed_ns(t0);
  stats_[stage].transforms += 1;
  stats_[stage].sent += t.sent_bytes();
}

void HuygensPropagator::propagate() {
  check_now_ = p_.check_every > 0 && (steps_ + 1) % p_.check_every == 0;
  // the round trip at the end of steps K, 2K, ...: between them Z^ only rotates (exact, eq. 1)
  trip_now_ = spatial_ && (steps_ + 1) % every_ == 0;
  {
    StageTimer timer(stats_[st_propagate_]);
    const int n = p_.n;
    // spectral rotation into Z (then IFFT), or in place on Z^ on a step without the round trip
    const float* s = reinterpret_cast<const float*>(s_.data());
    float* z = reinterpret_cast<float*>(trip_now_ ? z_.data() : s_.data());
    const float scale = trip_now_ && every_ > 1 ? 1.0f / (static_cast<float>(n) * static_cast<float>(n)) : 1.0f;
    const float *ta = rot_a_.data(), *tb = rot_b_.data(), *tc = rot_c_.data();
    const int q = n / 2 + 1;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
      // quadrant tables: row r reads table row min(r, N - r)
      const std::size_t qo = static_cast<std::size_t>(quadrant_index(g_.spectrum_row(lr), n)) * q;
      rotate_row(p_.rotation, ta + qo, tb + qo, tc == nullptr ? nullptr : tc + qo,
                 s + 2 * static_cast<std::size_t>(lr) * n, z + 2 * static_cast<std::size_t>(lr) * n, n, scale);
    }
    if (trip_now_) run_transform(*inv_prop_, st_propagate_);
  }
  if (inject_due_for_test(st_propagate_)) (trip_now_ ? z_ : s_)[mid_index()] = std::numeric_limits<float>::quiet_NaN();
  if (check_now_) check_stage(st_propagate_, trip_now_ ? field() : spectrum_view());
}

void HuygensPropagator::cutoff() {
  if (st_cutoff_ < 0 || !trip_now_) return;
  {
    StageTimer timer(stats_[st_cutoff_]);
    apply_cutoff_rows(reinterpret_cast<float*>(z_.data()), cut_.data(), p_.n, p_.margin, g_.row0, g_.rows);
  }
  if (inject_due_for_test(st_cutoff_)) z_[mid_index()] = std::numeric_limits<float>::quiet_NaN();
  if (check_now_) check_stage(st_cutoff_, field());
}

void HuygensPropagator::spectrum() {
  if (!trip_now_) return;
  {
    StageTimer timer(stats_[st_spectrum_]);
    run_transform(*fwd_, st_spectrum_);
  }
  if (inject_due_for_test(st_spectrum_)) s_[mid_index()] = std::numeric_limits<float>::quiet_NaN();
  if (check_now_) check_stage(st_spectrum_, spectrum_view());
}

void HuygensPropagator::height() {
  if (p_.external_height) throw std::logic_error("HuygensPropagator::height: external_height is set");
  bool finite = true;
  {
    StageTimer timer(stats_[st_height_]);
    const int n = p_.n, m = p_.margin, v = visible_size();
    const float* s = reinterpret_cast<const float*>(s_.data());
    float* h = reinterpret_cast<float*>(h_.data());
    const float* al = alpha_.data();
    const float* be = beta_.data();
    // pack: P(k) = i (alpha u + beta conj(w)), u = Z^(k), w = Z^(-k):
    //   Re P = beta Im w - alpha Im u,  Im P = alpha Re u + beta Re w
    const int hn = n / 2, q = hn + 1;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
    for (int r = 0; r < n; ++r) {
      const int rn = (n - r) & (n - 1);
      const float* u = s + 2 * static_cast<std::size_t>(r) * n;
      const float* w = s + 2 * static_cast<std::size_t>(rn) * n;
      float* p = h + 2 * static_cast<std::size_t>(r) * n;
      const std::size_t qo = static_cast<std::size_t>(r <= hn ? r : n - r) * q;
      const float* a = al + qo;
      const float* b = be + qo;
      // first the mirrored row Z^(-k) into p as whole 64-bit complex values (a reversed copy
      // the vectoriser handles), then everything runs forward and in place
      const Bits64* wb = reinterpret_cast<const Bits64*>(w);
      Bits64* pb = reinterpret_cast<Bits64*>(p);
      pb[0] = wb[0];
#pragma omp simd
      for (int c = 1; c < n; ++c) pb[c] = wb[n - c];
#pragma omp simd
      for (int c = 0; c <= hn; ++c) {
        const float wr = p[2 * c], wi = p[2 * c + 1];
        p[2 * c] = b[c] * wi - a[c] * u[2 * c + 1];
        p[2 * c + 1] = a[c] * u[2 * c] + b[c] * wr;
      }
      // quadrant tables: index N - c above N/2
#pragma omp simd
      for (int c = hn + 1; c < n; ++c) {
        const int j = n - c;
        const float wr = p[2 * c], wi = p[2 * c + 1];
        p[2 * c] = b[j] * wi - a[j] * u[2 * c + 1];
        p[2 * c + 1] = a[j] * u[2 * c] + b[j] * wr;
      }
    }
    run_transform(*inv_height_, st_height_);
    if (inject_due_for_test(st_height_)) h_[mid_index()] = std::numeric_limits<float>::quiet_NaN();
    // visible region out, with the non-finite test fused (x - x is NaN only for NaN/inf)
    float acc = 0.0f;
    float* eo = eta_.data();
    float* ed = etadot_.data();
#pragma omp parallel for schedule(static) reduction(+ : acc) if (n >= kParallelMin)
    for (int r = 0; r < v; ++r) {
      const float* row = h + 2 * (static_cast<std::size_t>(r + m) * n + m);
      float* e = eo + static_cast<std::size_t>(r) * v;
      float* d = ed + static_cast<std::size_t>(r) * v;
#pragma omp simd reduction(+ : acc)
      for (int c = 0; c < v; ++c) {
        e[c] = row[2 * c];
        d[c] = row[2 * c + 1];
        acc += (row[2 * c] - row[2 * c]) + (row[2 * c + 1] - row[2 * c + 1]);
      }
    }
    finite = acc == 0.0f;
  }
  if (!finite) {
    const int blame = height_blame();
    checks_.fail(stats_, blame < 0 ? st_height_ : blame, steps_ + 1);
  }
  if (check_now_) check_stage(st_height_, h_.span());
}

int HuygensPropagator::height_blame() const {
  // The buffers still hold each stage's output: Z after propagate/cutoff (the cutoff cannot
  // create a non-finite value from finite ones), Z^ after spectrum (and spectral sources,
  // which check themselves). The first non-finite one names the stage.
  const std::span<const cfloat> z(z_.data(), g_.field_size());
  if (trip_now_ && !all_finite(z)) return st_propagate_;
  if (!all_finite(spectrum_view())) return trip_now_ ? st_spectrum_ : st_propagate_;
  return -1;
}

void HuygensPropagator::inject_nonfinite_for_test(const std::string& stage, std::int64_t step) {
  const int i = stats_.find(stage);
  if (i < 0) throw std::invalid_argument("inject_nonfinite_for_test: no stage '" + stage + "'");
  inject_stage_ = i;
  inject_step_ = step;
}

double HuygensPropagator::spectrum_norm2() const {
  const float* s = reinterpret_cast<const float*>(s_.data());
  const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(2 * g_.spectrum_size());
  double sum = 0.0;
#pragma omp parallel for simd schedule(static) reduction(+ : sum) if (p_.n >= kParallelMin)
  for (std::ptrdiff_t i = 0; i < m; ++i) sum += static_cast<double>(s[i]) * static_cast<double>(s[i]);
  return sum;
}

double HuygensPropagator::energy_bound_of(double sum) const {
  const double nn = static_cast<double>(p_.n) * p_.n;
  const double kmax = std::sqrt(2.0) * kPi * p_.n / p_.length_m;
  const double inv_h = p_.water.deep() ? 0.0 : 1.0 / p_.water.depth_m;
  return 0.5 * p_.water.density_kgpm3 * p_.length_m * p_.length_m / (nn * nn) * (kmax + inv_h) * sum;
}

void HuygensPropagator::end_step() {
  ++steps_;
  t_ = static_cast<double>(steps_) * p_.dt_s;
}

void HuygensPropagator::step() {
  propagate();
  cutoff();
  spectrum();
  height();
  end_step();
}

void HuygensPropagator::raw_transforms() {
  if (spatial_) {
    inv_prop_->execute();
    fwd_->execute();
  }
  if (inv_height_) inv_height_->execute();
}

double HuygensPropagator::energy() const {
  if (!g_.whole) throw std::logic_error("HuygensPropagator::energy: whole grid only");
  const int n = p_.n;
  const double g = p_.water.gravity_mps2, st = p_.water.surface_tension_npm / p_.water.density_kgpm3;
  const double nn = static_cast<double>(n) * n;
  double sum = 0.0;
  for (int r = 0; r < n; ++r) {
    const int rn = (n - r) & (n - 1);
    const double ky = wavenumber(r);
    for (int c = 0; c < n; ++c) {
      const int cn = (n - c) & (n - 1);
      const double k = std::hypot(wavenumber(c), ky);
      if (k == 0) continue;
      const double w = omega(p_.water, k);
      const std::complex<double> u = s_[static_cast<std::size_t>(r) * n + c];
      const std::complex<double> v = std::conj(std::complex<double>(s_[static_cast<std::size_t>(rn) * n + cn]));
      // H = Hermitian part of i k/omega Z^, D = Hermitian part of k Z^
      const std::complex<double> hh = std::complex<double>(0, 0.5 * k / w) * (u - v);
      const std::complex<double> dd = 0.5 * k * (u + v);
      sum += (g + st * k * k) * (std::norm(hh) + std::norm(dd) / (w * w));
    }
  }
  return 0.5 * p_.water.density_kgpm3 * p_.length_m * p_.length_m / (nn * nn) * sum;
}

}  // namespace huygens
