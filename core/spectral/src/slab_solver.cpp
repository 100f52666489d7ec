#include "huygens/spectral/slab_solver.hpp"

#ifdef HUYGENS_HAVE_MPI
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>

#include "huygens/common/finite.hpp"
#include "huygens/common/time_interp.hpp"
#include "huygens/spectral/cutoff.hpp"
#include "huygens/spectral/rotation.hpp"

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kParallelMin = 256;  // grids below this run the passes on one thread
std::uint64_t elapsed_ns(std::chrono::steady_clock::time_point t0) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
}
// quadrant index of FFT index i: |signed index|, 0..N/2
inline int quad(int i, int n) { return i <= n / 2 ? i : n - i; }
}  // namespace

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

HuygensSlabSolver::HuygensSlabSolver(const HuygensScene& scene, MPI_Comm comm, SlabTransforms how)
    : scene_(scene), comm_(comm) {
  const HuygensParams& p = scene_.params;
  if (auto e = huygens_params_error(p); !e.empty()) throw std::invalid_argument(e);
  const bool bits_possible = slab_row_column(p.n, p.effort);
  if (how == SlabTransforms::one_process_bits && !bits_possible)
    throw std::invalid_argument("the one-process bits need FFTW_ESTIMATE plans and N >= 256");
  if (how == SlabTransforms::automatic)
    how = bits_possible ? SlabTransforms::one_process_bits : SlabTransforms::fftw_transposed;
  g_ = slab_grid(p.n, comm_, how == SlabTransforms::fftw_transposed);
  g_.row_column = how == SlabTransforms::one_process_bits;
  sent_per_transform_ = static_cast<std::uint64_t>(g_.transposes() * slab_transpose_bytes(g_));
  spatial_ = p.absorber != Absorber::off || !scene_.ships.empty();
  every_ = std::clamp(p.round_trip_every, 1, 64);
  second_ = scene_.stokes;
  v_ = p.n - 2 * p.margin;
  const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(g_.row0, p.margin);
  const std::ptrdiff_t hi = std::min<std::ptrdiff_t>(g_.row0 + g_.rows, p.n - p.margin);
  vis_rows_ = std::max<std::ptrdiff_t>(0, hi - lo);
  vis_row0_ = vis_rows_ > 0 ? lo - p.margin : 0;
  vis_first_ = vis_rows_ > 0 ? lo - g_.row0 : 0;
  allocate();
  make_plans();  // before any data: measure planning overwrites the buffers
  build_tables();
  build_cutoff();
  if (!scene_.drops.empty()) reserve_sources();
  if (!scene_.ships.empty()) {
    ships_ = std::make_unique<ShipWaves>(p.water, p.n, p.length_m, scene_.ship_patch, scene_.ships, p.effort);
    ships_->check_step(p.dt_s);
    if (every_ > 1) ships_->reserve_gather(every_);
  }
  if (scene_.has_wind)
    wind_ = std::make_unique<WindSea>(scene_.wind, p.water, p.n, p.length_m, p.dt_s,
                                      WindRows{static_cast<int>(g_.krow0), static_cast<int>(g_.krows), g_.transposed});
  initial_state();
}

HuygensSlabSolver::~HuygensSlabSolver() = default;

void HuygensSlabSolver::allocate() {
  const std::size_t slab = static_cast<std::size_t>(g_.alloc), q = static_cast<std::size_t>(g_.n / 2 + 1);
  const std::size_t vv = static_cast<std::size_t>(vis_rows_) * v_;
  z_ = AlignedBuffer<cfloat>(slab);
  s_ = AlignedBuffer<cfloat>(slab);
  a_ = AlignedBuffer<cfloat>(slab);
  b_ = AlignedBuffer<cfloat>(slab);
  if (second_) {
    chi_ = AlignedBuffer<cfloat>(slab);
    chid_ = AlignedBuffer<cfloat>(slab);
  }
  for (auto* t : {&rot_a_, &rot_b_, &rot_c_, &kw_, &kk_, &sq_}) *t = AlignedBuffer<float>(q * q);
  cut_ = AlignedBuffer<float>(2 * static_cast<std::size_t>(g_.n));
  src_x_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(g_.n));
  src_y_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(g_.n));
  eta_ = AlignedBuffer<float>(vv);
  etadot_ = AlignedBuffer<float>(vv);
  if (scene_.display_per_step > 1) {
    eta0_ = AlignedBuffer<float>(vv);
    etadot0_ = AlignedBuffer<float>(vv);
    frame_ = AlignedBuffer<float>(vv);
  }
}

void HuygensSlabSolver::make_plans() {
  const PlanEffort e = scene_.params.effort;
  inv_prop_ = std::make_unique<SlabFft>(g_, z_.data(), z_.data(), Fft2D::backward, e, comm_);
  fwd_ = std::make_unique<SlabFft>(g_, z_.data(), s_.data(), Fft2D::forward, e, comm_);
  inv_height_ = std::make_unique<SlabFft>(g_, a_.data(), a_.data(), Fft2D::backward, e, comm_);
  for (auto* b : {&z_, &s_, &a_, &b_}) std::fill(b->data(), b->data() + b->size(), cfloat(0.0f, 0.0f));
}

void HuygensSlabSolver::build_tables() {
  // the quadrant tables of HuygensPropagator::build_tables and StokesHeight (same formulas)
  const HuygensParams& p = scene_.params;
  const int n = p.n, q = n / 2 + 1;
  const double inv_nn = 1.0 / (static_cast<double>(n) * n);
  // HuygensPropagator::build_tables: unscaled with the round trip every K > 1 steps
  const double rot_scale = spatial_ && every_ == 1 ? inv_nn : 1.0;
  for (int r = 0; r < q; ++r)
    for (int c = 0; c < q; ++c) {
      const double k = std::hypot(fft_wavenumber(c, n, p.length_m), fft_wavenumber(r, n, p.length_m));
      const double w = omega(p.water, k);
      const std::size_t i = static_cast<std::size_t>(r) * q + c;
      const RotationEntry e = rotation_entry(p.rotation, w * p.dt_s, rot_scale);
      rot_a_[i] = e.a;
      rot_b_[i] = e.b;
      rot_c_[i] = e.c;
      kk_[i] = static_cast<float>(k);
      kw_[i] = k > 0 && w > 0 ? static_cast<float>(k / w) : 0.0f;
      sq_[i] = static_cast<float>(std::sqrt(0.5 * k));
    }
}

void HuygensSlabSolver::build_cutoff() { fill_cutoff_window(scene_.params, cut_.data()); }

void HuygensSlabSolver::reserve_sources() {
  // -omega/k factor and omega on the local rows of the spectrum (|k| is symmetric in kx, ky)
  if (src_.size()) return;
  const HuygensParams& p = scene_.params;
  const int n = p.n;
  src_ = AlignedBuffer<float>(static_cast<std::size_t>(g_.krows) * n);
  omega_ = AlignedBuffer<float>(static_cast<std::size_t>(g_.krows) * n);
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const double kx = fft_wavenumber(static_cast<int>(g_.krow0 + lr), n, p.length_m);
    for (int c = 0; c < n; ++c) {
      const double k = std::hypot(fft_wavenumber(c, n, p.length_m), kx);
      const double w = omega(p.water, k);
      const std::size_t i = static_cast<std::size_t>(lr) * n + c;
      src_[i] = k > 0 ? static_cast<float>(w / k) : 0.0f;
      omega_[i] = static_cast<float>(w);
    }
  }
}

void HuygensSlabSolver::initial_state() {
  const HuygensParams& p = scene_.params;
  for (const auto& w : scene_.initial_plane_waves) add_plane_wave(w.wavelength_m, w.amplitude_m, w.direction_deg);
  for (const auto& gs : scene_.initial_gaussians) add_gaussian(gs.x_m, gs.y_m, gs.sigma_m, gs.amplitude_m, 0.0);
  while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t_s <= 0.0) {
    const auto& d = scene_.drops[next_drop_++];
    add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, -d.t_s);
  }
  const std::uint64_t field = static_cast<std::uint64_t>(g_.alloc) * sizeof(cfloat);
  st_propagate_ = stats_.add("propagate", 2 * field);
  if (p.absorber != Absorber::off) st_cutoff_ = stats_.add("cutoff", 2 * p.n * sizeof(float));
  if (spatial_) st_spectrum_ = stats_.add("spectrum", 0);
  st_drops_ = stats_.add("drops", src_.size() * 2 * sizeof(float));
  if (ships_) st_ships_ = stats_.add("ships", ships_->bytes());
  if (wind_) st_wind_ = stats_.add("wind", wind_->bytes());
  st_height_ = stats_.add(second_ ? "height_stokes" : wind_ ? "height_wind" : "height", (second_ ? 4 : 2) * field);
  if (scene_.still_skip && !ships_ && !wind_ && scene_.still_check_every > 0) {
    const double k1 = 2.0 * kPi / p.length_m, a = scene_.still_amplitude_m;
    still_energy_ = 0.5 * (p.water.density_kgpm3 * p.water.gravity_mps2 + p.water.surface_tension_npm * k1 * k1) * a *
                    a * p.length_m * p.length_m;
    st_still_ = stats_.add("still", 0);
  }
  make_height();
  flags_.fill(0.0);
  const bool ok = extract_height();
  double bad = ok ? 0.0 : 1.0;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_DOUBLE, MPI_SUM, comm_);
  if (bad > 0) throw NonFiniteError("initial", 0);
  stats_.reset_counts();
}

// ---- sources --------------------------------------------------------------------------------

void HuygensSlabSolver::add_gaussian(double x_m, double y_m, double sigma_m, double amplitude_m, double age_s) {
  // HuygensPropagator::add_gaussian on the local rows: a row's factor is fx (transposed: kx rows)
  // or fy (normal: ky rows), a column's the other
  reserve_sources();
  const HuygensParams& p = scene_.params;
  const int n = p.n;
  const double d = p.length_m / n;
  const double amp = 2.0 * kPi * sigma_m * sigma_m * amplitude_m / (d * d);
  gaussian_axis_factors(src_x_.data(), n, p.length_m, x_m, sigma_m, 1.0);
  gaussian_axis_factors(src_y_.data(), n, p.length_m, y_m, sigma_m, amp);
  const cfloat* fr = (g_.transposed ? src_x_ : src_y_).data();  // row factor
  const cfloat* fc = (g_.transposed ? src_y_ : src_x_).data();  // column factor
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const std::size_t o = static_cast<std::size_t>(lr) * n;
    add_gaussian_row(fr[g_.krow0 + lr], fc, src_.data() + o, omega_.data() + o, age_s, s_.data() + o, n);
  }
}

void HuygensSlabSolver::add_plane_wave(double wavelength_m, double amplitude_m, double direction_deg) {
  // Z = -i a e^{i k.x} on the local spatial rows, one forward transform into a scratch slab
  const HuygensParams& p = scene_.params;
  const int n = p.n;
  const double k0 = 2.0 * kPi / wavelength_m, th = direction_deg * kPi / 180.0;
  const double kx = k0 * std::cos(th), ky = k0 * std::sin(th);
  const double a = omega(p.water, k0) / k0 * amplitude_m, d = p.length_m / n;
  for (std::ptrdiff_t lr = 0; lr < g_.rows; ++lr)
    for (int c = 0; c < n; ++c) {
      const double ph = kx * c * d + ky * static_cast<double>(g_.row0 + lr) * d;
      a_[static_cast<std::size_t>(lr) * n + c] =
          cfloat(static_cast<float>(a * std::sin(ph)), static_cast<float>(-a * std::cos(ph)));
    }
  fwd_->execute(a_.data(), b_.data());
  const std::size_t m = static_cast<std::size_t>(g_.krows) * n;
  for (std::size_t i = 0; i < m; ++i) s_[i] += b_[i];
}

// ---- the step -------------------------------------------------------------------------------

void HuygensSlabSolver::check(int stage, std::span<const cfloat> v) {
  if (!all_finite(v)) flags_[static_cast<std::size_t>(stage)] += 1.0;
}

void HuygensSlabSolver::rotate(const float* s, float* z, float scale) {
  // HuygensPropagator::propagate's rotation on the local kx rows (quadrant tables symmetric)
  const int n = g_.n, q = n / 2 + 1;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const std::size_t qo = static_cast<std::size_t>(quad(static_cast<int>(g_.krow0 + lr), n)) * q;
    rotate_row(scene_.params.rotation, rot_a_.data() + qo, rot_b_.data() + qo, rot_c_.data() + qo,
               s + 2 * static_cast<std::size_t>(lr) * n, z + 2 * static_cast<std::size_t>(lr) * n, n, scale);
  }
}

void HuygensSlabSolver::propagate() {
  check_now_ = scene_.params.check_every > 0 && (steps_ + 1) % scene_.params.check_every == 0;
  trip_now_ = spatial_ && (steps_ + 1) % every_ == 0;  // HuygensPropagator::propagate
  {
    StageTimer timer(stats_[st_propagate_]);
    const float scale = trip_now_ && every_ > 1 ? 1.0f / (static_cast<float>(g_.n) * static_cast<float>(g_.n)) : 1.0f;
    rotate(reinterpret_cast<const float*>(s_.data()), reinterpret_cast<float*>(trip_now_ ? z_.data() : s_.data()),
           scale);
    if (trip_now_) {
      const auto t0 = std::chrono::steady_clock::now();
      inv_prop_->execute();
      fft_ns_ += elapsed_ns(t0);
      stats_[st_propagate_].transforms += 1;
      stats_[st_propagate_].sent += sent_per_transform_;
    }
  }
  const std::size_t m = static_cast<std::size_t>(trip_now_ ? g_.rows : g_.krows) * g_.n;
  if (check_now_) check(st_propagate_, std::span<const cfloat>((trip_now_ ? z_ : s_).data(), m));
}

void HuygensSlabSolver::cutoff() {
  if (st_cutoff_ < 0 || !trip_now_) return;
  {
    StageTimer timer(stats_[st_cutoff_]);
    apply_cutoff_rows(reinterpret_cast<float*>(z_.data()), cut_.data(), g_.n, scene_.params.margin, g_.row0, g_.rows);
  }
  if (check_now_) check(st_cutoff_, std::span<const cfloat>(z_.data(), static_cast<std::size_t>(g_.rows) * g_.n));
}

void HuygensSlabSolver::add_ships(double t0) {
  // every rank makes every patch (P x P, small) and adds the rows it owns
  StageTimer timer(stats_[st_ships_]);
  const int r0 = static_cast<int>(g_.row0), rows = static_cast<int>(g_.rows);
  bool ok = true;
  if (every_ == 1) {
    ok = ships_->add_rows(z_.data(), r0, rows, t0, scene_.params.dt_s);
  } else {  // HuygensSolver::add_ships: gathered until the round trip
    ok = ships_->gather(t0, scene_.params.dt_s, static_cast<int>((every_ - (steps_ + 1) % every_) % every_));
    if (ok && trip_now_) ships_->scatter_rows(z_.data(), r0, rows);
  }
  if (!ok) flags_[static_cast<std::size_t>(st_ships_)] += 1.0;
}

void HuygensSlabSolver::spectrum() {
  if (!trip_now_) return;
  {
    StageTimer timer(stats_[st_spectrum_]);
    const auto t0 = std::chrono::steady_clock::now();
    fwd_->execute();
    fft_ns_ += elapsed_ns(t0);
    stats_[st_spectrum_].transforms += 1;
    stats_[st_spectrum_].sent += sent_per_transform_;
  }
  if (check_now_) check(st_spectrum_, std::span<const cfloat>(s_.data(), static_cast<std::size_t>(g_.krows) * g_.n));
}

bool HuygensSlabSolver::drop_due() const {
  if (next_drop_ >= scene_.drops.size()) return false;
  const double t1 = static_cast<double>(steps_ + 1) * scene_.params.dt_s;
  return scene_.drops[next_drop_].t_s <= t1 + 1e-9 * scene_.params.dt_s;
}

void HuygensSlabSolver::release_drops() {
  const double t1 = static_cast<double>(steps_ + 1) * scene_.params.dt_s;
  const double eps = 1e-9 * scene_.params.dt_s;
  StageTimer timer(stats_[st_drops_]);
  while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t_s <= t1 + eps) {
    const auto& d = scene_.drops[next_drop_++];
    add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, std::max(0.0, t1 - d.t_s));
  }
  check(st_drops_, std::span<const cfloat>(s_.data(), static_cast<std::size_t>(g_.krows) * g_.n));
}

void HuygensSlabSolver::pack_height(const float* s, float zscale) {
  // Y = zscale Z^ + W^(0) P (wind); U^ = m Y, V^ = k Y with m = k/omega (then eta = -Im U,
  // etadot = Re V); second order: chi^ = i m s Y, chidot^ = k s Y, s = sqrt(k/2)
  const int n = g_.n, h = n / 2, q = h + 1;
  const float* w0 = wind_ && wind_on_ ? reinterpret_cast<const float*>(wind_->base()) : nullptr;
  const float* ph = w0 ? reinterpret_cast<const float*>(wind_->phase_quadrant()) : nullptr;
  float *A = reinterpret_cast<float*>(a_.data()), *B = reinterpret_cast<float*>(b_.data());
  float *C = reinterpret_cast<float*>(chi_.data()), *D = reinterpret_cast<float*>(chid_.data());
  const bool sec = second_;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const int qr = quad(static_cast<int>(g_.krow0 + lr), n);
    const std::size_t o = 2 * static_cast<std::size_t>(lr) * n, qo = static_cast<std::size_t>(qr) * q;
    const float *tm = kw_.data() + qo, *tk = kk_.data() + qo, *ts = sq_.data() + qo;
    for (int c = 0; c < n; ++c) {
      const int j = c <= h ? c : n - c;
      float yr = zscale * s[o + 2 * c], yi = zscale * s[o + 2 * c + 1];
      if (w0) {
        const float wr = w0[o + 2 * c], wi = w0[o + 2 * c + 1], pr = ph[2 * (qo + j)], pi = ph[2 * (qo + j) + 1];
        yr += wr * pr - wi * pi;
        yi += wr * pi + wi * pr;
      }
      const float m = tm[j], k = tk[j];
      A[o + 2 * c] = m * yr;
      A[o + 2 * c + 1] = m * yi;
      B[o + 2 * c] = k * yr;
      B[o + 2 * c + 1] = k * yi;
      if (!sec) continue;
      const float ms = m * ts[j], ks = k * ts[j];
      C[o + 2 * c] = -ms * yi;
      C[o + 2 * c + 1] = ms * yr;
      D[o + 2 * c] = ks * yr;
      D[o + 2 * c + 1] = ks * yi;
    }
  }
}

void HuygensSlabSolver::make_height() {
  StageTimer timer(stats_[st_height_]);
  // Z^ is the unnormalised forward transform of the field (with or without the round trip)
  const float zscale = 1.0f / (static_cast<float>(g_.n) * static_cast<float>(g_.n));
  pack_height(reinterpret_cast<const float*>(s_.data()), zscale);
  const auto t0 = std::chrono::steady_clock::now();
  inv_height_->execute();
  inv_height_->execute(b_.data(), b_.data());
  if (second_) {
    inv_height_->execute(chi_.data(), chi_.data());
    inv_height_->execute(chid_.data(), chid_.data());
  }
  fft_ns_ += elapsed_ns(t0);
  stats_[st_height_].transforms += second_ ? 4 : 2;
  stats_[st_height_].sent += (second_ ? 4 : 2) * sent_per_transform_;
}

bool HuygensSlabSolver::extract_height() {
  // eta + i etadot = i A + i conj(B) with A = (U + V)/2, B = (V - U)/2: eta = -Im U, etadot = Re V
  // (U, V in a_, b_; no difference of the large k/2 terms is formed); second order adds
  // Re(chi^2) and Re(2 chi chidot) (stokes.hpp). Fused non-finite test (x - x).
  const int n = g_.n, m0 = scene_.params.margin, v = v_;
  const float *A = reinterpret_cast<const float*>(a_.data()), *B = reinterpret_cast<const float*>(b_.data());
  const float *C = reinterpret_cast<const float*>(chi_.data()), *D = reinterpret_cast<const float*>(chid_.data());
  const bool sec = second_;
  float acc = 0.0f;
#pragma omp parallel for schedule(static) reduction(+ : acc) if (n >= kParallelMin)
  for (std::ptrdiff_t r = 0; r < vis_rows_; ++r) {
    const std::size_t o = 2 * (static_cast<std::size_t>(r + vis_first_) * n + m0);
    float* e = eta_.data() + static_cast<std::size_t>(r) * v;
    float* d = etadot_.data() + static_cast<std::size_t>(r) * v;
    for (int c = 0; c < v; ++c) {
      float ev = -A[o + 2 * c + 1], dv = B[o + 2 * c];
      if (sec) {
        const float cr = C[o + 2 * c], ci = C[o + 2 * c + 1], dr = D[o + 2 * c], di = D[o + 2 * c + 1];
        ev += cr * cr - ci * ci;
        dv += 2.0f * (cr * dr - ci * di);
      }
      e[c] = ev;
      d[c] = dv;
      acc += (ev - ev) + (dv - dv);
    }
  }
  return acc == 0.0f;
}

void HuygensSlabSolver::reduce_step(bool energy_due) {
  double& energy = flags_[kMaxStages];
  energy = 0.0;
  if (energy_due) {
    const float* s = reinterpret_cast<const float*>(s_.data());
    const std::ptrdiff_t m = 2 * g_.krows * g_.n;
    double sum = 0.0;
#pragma omp parallel for simd schedule(static) reduction(+ : sum) if (g_.n >= kParallelMin)
    for (std::ptrdiff_t i = 0; i < m; ++i) sum += static_cast<double>(s[i]) * static_cast<double>(s[i]);
    energy = sum;
  }
  MPI_Allreduce(MPI_IN_PLACE, flags_.data(), static_cast<int>(flags_.size()), MPI_DOUBLE, MPI_SUM, comm_);
  // the first failing stage in step order, as the one-process solver would name it
  for (int st : {st_propagate_, st_cutoff_, st_ships_, st_spectrum_, st_drops_, st_wind_, st_height_})
    if (st >= 0 && flags_[static_cast<std::size_t>(st)] > 0) throw NonFiniteError(stats_[st].name, steps_ + 1);
}

void HuygensSlabSolver::keep_previous_step() {
  if (scene_.display_per_step <= 1) return;
  std::swap(eta0_, eta_);
  std::swap(etadot0_, etadot_);
}

void HuygensSlabSolver::step() {
  const bool energy_due = st_still_ >= 0 && (steps_ + 1) % scene_.still_check_every == 0;
  if (still_) {
    if (!drop_due()) {  // still sea: time advances, nothing else (the same on every rank)
      StageTimer timer(stats_[st_still_]);
      ++steps_;
      return;
    }
    still_ = false;
  }
  keep_previous_step();
  flags_.fill(0.0);
  const double t0 = time();
  propagate();
  cutoff();
  if (ships_) add_ships(t0);
  spectrum();
  if (drop_due()) release_drops();
  if (wind_) {
    StageTimer timer(stats_[st_wind_]);
    wind_->advance();
  }
  make_height();
  if (!extract_height()) {
    // name the stage as HuygensPropagator::diagnose_nonfinite would (Z^ before the height)
    const std::size_t m = static_cast<std::size_t>(g_.krows) * g_.n;
    const bool s_ok = all_finite(std::span<const cfloat>(s_.data(), m));
    const bool own = !second_ && !wind_;  // the Stokes/wind stage names itself (HuygensSolver::make_height)
    flags_[static_cast<std::size_t>(s_ok || !own ? st_height_ : trip_now_ ? st_spectrum_ : st_propagate_)] += 1.0;
  }
  reduce_step(energy_due);
  ++steps_;
  if (energy_due) {
    const HuygensParams& p = scene_.params;
    const double nn = static_cast<double>(p.n) * p.n, kmax = std::sqrt(2.0) * kPi * p.n / p.length_m;
    const double inv_h = p.water.deep() ? 0.0 : 1.0 / p.water.depth_m;
    const double bound =
        0.5 * p.water.density_kgpm3 * p.length_m * p.length_m / (nn * nn) * (kmax + inv_h) * flags_[kMaxStages];
    if (bound < still_energy_) {  // HuygensSolver::check_still: a flat sea at rest
      for (auto* b : {&z_, &s_}) std::fill(b->data(), b->data() + b->size(), cfloat(0.0f, 0.0f));
      for (auto* b : {&eta_, &etadot_, &eta0_, &etadot0_}) std::fill(b->data(), b->data() + b->size(), 0.0f);
      still_ = true;
    }
  }
}

// ---- outputs --------------------------------------------------------------------------------

std::vector<OutputField> HuygensSlabSolver::outputs() {
  OutputField f{"eta", {static_cast<std::size_t>(vis_rows_), static_cast<std::size_t>(v_)}, eta_.span()};
  f.global_shape = {static_cast<std::size_t>(v_), static_cast<std::size_t>(v_)};
  f.row0 = static_cast<std::size_t>(vis_row0_);
  return {f};
}

std::vector<OutputField> HuygensSlabSolver::display_outputs(int j) {
  const int d = scene_.display_per_step;
  if (j == 0 || d <= 1) return outputs();
  if (j < 0 || j >= d || steps_ < 1) return {};
  hermite_interpolate(eta0_.data(), etadot0_.data(), eta_.data(), etadot_.data(), eta_.size(), hermite_weights(j, d),
                      scene_.params.dt_s, frame_.data());
  auto out = outputs();
  out[0].data = frame_.span();
  return out;
}

std::size_t HuygensSlabSolver::ship_poses(std::span<ShipState> out) const {
  if (!ships_) return 0;
  const std::size_t k = std::min(out.size(), static_cast<std::size_t>(ships_->ships()));
  for (std::size_t i = 0; i < k; ++i) {
    const ShipPoseNow p = ships_->pose(static_cast<int>(i), time());
    out[i] = ShipState{p.x_m, p.y_m, p.heading_rad, p.speed_mps};
  }
  return k;
}

int HuygensSlabSolver::transforms_per_step() const { return (spatial_ ? 2 : 0) + (second_ ? 4 : 2); }

double HuygensSlabSolver::mean_transforms_per_step() const {
  return (spatial_ ? 2.0 / every_ : 0.0) + (second_ ? 4 : 2);
}

double HuygensSlabSolver::bytes_sent_per_step() const {
  return mean_transforms_per_step() * g_.transposes() * slab_transpose_bytes(g_);
}

nlohmann::json HuygensSlabSolver::meta() const {
  // the one-process description of the global grid, plus how it was split
  nlohmann::json j = huygens_meta(scene_, mean_transforms_per_step(), still_energy_);
  j["mpi"] = {{"ranks", g_.ranks},
              {"layout", g_.row_column   ? "row slabs; spectrum normal; row-column transforms (one-process bits)"
                         : g_.transposed ? "row slabs; spectrum transposed (FFTW_MPI_TRANSPOSED_OUT/IN)"
                                         : "row slabs; spectrum normal (FFTW's MPI plans)"},
              {"transposes_per_step", mean_transforms_per_step() * g_.transposes()},
              {"height", "i IFFT[alpha Y] + i conj(IFFT[beta Y]): two transforms, no mirror exchange"}};
  return j;
}

}  // namespace huygens
#endif
