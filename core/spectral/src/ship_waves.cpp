#include "huygens/spectral/ship_waves.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "huygens/common/finite.hpp"

namespace huygens {

using cd = std::complex<double>;

namespace {

constexpr double kPi = std::numbers::pi;

// (e^{s i a} - s i a - 1) / a^2 for s = -1 (g1) or +1 (g2); series sum_{n>=2} (s i)^n a^{n-2} / n!
// for |a| < 0.5 (terms to n = 18: truncation below 1e-19).
cd g_kernel(double a, double s) {
  if (std::abs(a) < 0.5) {
    cd term(1.0, 0.0), sum(0.0, 0.0);
    const cd si(0.0, s);
    // term_n = (s i)^n a^{n-2} / n!, starting at n = 2: (s i)^2 / 2 = -1/2
    term = si * si / 2.0;
    for (int n = 2; n <= 18; ++n) {
      sum += term;
      term *= si * a / static_cast<double>(n + 1);
    }
    return sum;
  }
  const cd e = std::exp(cd(0.0, s * a));
  return (e - cd(0.0, s * a) - 1.0) / (a * a);
}

// (e^{-i a} - 1) / a, series sum_{n>=1} (-i)^n a^{n-1} / n! for |a| < 0.5.
cd h_kernel(double a) {
  if (std::abs(a) < 0.5) {
    const cd mi(0.0, -1.0);
    cd term = mi, sum(0.0, 0.0);
    for (int n = 1; n <= 18; ++n) {
      sum += term;
      term *= mi * a / static_cast<double>(n + 1);
    }
    return sum;
  }
  return (std::exp(cd(0.0, -a)) - 1.0) / a;
}

// j1(q)/q = (sin q - q cos q) / q^3, series near 0.
double j1_over_q(double q) {
  if (q < 0.1) {
    const double q2 = q * q;
    return 1.0 / 3.0 - q2 / 30.0 + q2 * q2 / 840.0 - q2 * q2 * q2 / 45360.0;
  }
  return (std::sin(q) - q * std::cos(q)) / (q * q * q);
}

}  // namespace

// ---------------------------------------------------------------- path

ShipPath::ShipPath(std::vector<PathPoint> points) : pts_(std::move(points)) {
  if (pts_.empty()) throw std::invalid_argument("ship path: needs at least one point");
  for (std::size_t i = 1; i < pts_.size(); ++i)
    if (!(pts_[i].t_s >= pts_[i - 1].t_s))
      throw std::invalid_argument("ship path: point " + std::to_string(i) + " has a time before the previous point");
}

void ShipPath::append(const PathPoint& p) {
  if (!pts_.empty() && !(p.t_s >= pts_.back().t_s))
    throw std::invalid_argument("ship path: appended point lies before the last point in time");
  pts_.push_back(p);
}

void ShipPath::truncate_after(double t) {
  if (pts_.empty() || !(t < pts_.back().t_s)) return;  // nothing scripted after t
  double x, y;
  position(t, x, y);
  while (!pts_.empty() && pts_.back().t_s > t) pts_.pop_back();
  // at least one point was removed, so this stays within the old size (no allocation)
  if (pts_.empty() || pts_.back().t_s < t || pts_.back().x_m != x || pts_.back().y_m != y) pts_.push_back({t, x, y});
}

int ShipPath::segment(double t) const {
  if (pts_.empty() || t < pts_.front().t_s) return -1;
  // last i with t_i <= t
  const auto it = std::upper_bound(pts_.begin(), pts_.end(), t, [](double v, const PathPoint& p) { return v < p.t_s; });
  return static_cast<int>(it - pts_.begin()) - 1;
}

void ShipPath::position(double t, double& x, double& y) const {
  if (pts_.empty()) {
    x = y = 0.0;
    return;
  }
  const int i = segment(t);
  if (i < 0) {
    x = pts_.front().x_m;
    y = pts_.front().y_m;
    return;
  }
  if (i >= static_cast<int>(pts_.size()) - 1) {
    x = pts_.back().x_m;
    y = pts_.back().y_m;
    return;
  }
  const PathPoint& a = pts_[static_cast<std::size_t>(i)];
  const PathPoint& b = pts_[static_cast<std::size_t>(i) + 1];
  const double span = b.t_s - a.t_s;
  const double f = span > 0.0 ? (t - a.t_s) / span : 1.0;
  x = a.x_m + f * (b.x_m - a.x_m);
  y = a.y_m + f * (b.y_m - a.y_m);
}

void ShipPath::velocity(double t, double& vx, double& vy) const {
  vx = vy = 0.0;
  const int i = segment(t);
  if (i < 0 || i >= static_cast<int>(pts_.size()) - 1) return;
  const PathPoint& a = pts_[static_cast<std::size_t>(i)];
  const PathPoint& b = pts_[static_cast<std::size_t>(i) + 1];
  const double span = b.t_s - a.t_s;
  if (span <= 0.0) return;
  vx = (b.x_m - a.x_m) / span;
  vy = (b.y_m - a.y_m) / span;
}

void ShipPath::step_velocity(double t, double dt, double& vx, double& vy) const {
  const int i = segment(t);
  const int last = static_cast<int>(pts_.size()) - 1;
  if (i >= last || (i < 0 && (pts_.empty() || t + dt <= pts_.front().t_s))) {
    vx = vy = 0.0;  // resting before the start or after the end
    return;
  }
  if (i >= 0 && t + dt <= pts_[static_cast<std::size_t>(i) + 1].t_s) {
    velocity(t, vx, vy);  // within one segment: its exact velocity
    return;
  }
  double x0, y0, x1, y1;
  position(t, x0, y0);
  position(t + dt, x1, y1);
  vx = (x1 - x0) / dt;
  vy = (y1 - y0) / dt;
}

double ShipPath::heading(double t) const {
  const int segs = static_cast<int>(pts_.size()) - 1;
  if (segs < 1) return 0.0;
  auto moving = [&](int i) {
    const PathPoint& a = pts_[static_cast<std::size_t>(i)];
    const PathPoint& b = pts_[static_cast<std::size_t>(i) + 1];
    return b.t_s > a.t_s && (b.x_m != a.x_m || b.y_m != a.y_m);
  };
  auto angle = [&](int i) {
    const PathPoint& a = pts_[static_cast<std::size_t>(i)];
    const PathPoint& b = pts_[static_cast<std::size_t>(i) + 1];
    return std::atan2(b.y_m - a.y_m, b.x_m - a.x_m);
  };
  const int i = std::clamp(segment(t), -1, segs);
  if (i >= 0 && i < segs && moving(i)) return angle(i);
  for (int j = std::min(i, segs - 1); j >= 0; --j)
    if (moving(j)) return angle(j);
  for (int j = std::max(i, 0); j < segs; ++j)
    if (moving(j)) return angle(j);
  return 0.0;
}

std::vector<Ship> parse_ships(const JsonIn& root) {
  std::vector<Ship> ships;
  for (const JsonIn& j : root.array("ships")) {
    j.allow_only({"length_m", "beam_m", "draft_m", "blur_m", "path", "steering"});
    Ship s;
    s.hull.length_m = j.number("length_m", 1e-4, 1e4);
    s.hull.beam_m = j.number("beam_m", 1e-4, 1e4);
    s.hull.draft_m = j.number("draft_m", 0.0, 1e3);
    s.hull.blur_m = j.number("blur_m", s.hull.blur_m, -1.0, 1e3);
    const std::vector<JsonIn> pts = j.array("path");
    if (pts.empty()) j.fail("path", "a ship needs a path with at least one point");
    std::vector<PathPoint> path;
    for (const JsonIn& q : pts) {
      q.reject_renamed({{"t", "t_s"}});
      q.allow_only({"t_s", "x_m", "y_m"});
      PathPoint p{q.number("t_s", -1e9, 1e9), q.number("x_m", -1e9, 1e9), q.number("y_m", -1e9, 1e9)};
      if (!path.empty() && p.t_s < path.back().t_s) q.fail("t_s", "path times must not decrease");
      path.push_back(p);
    }
    s.path = ShipPath(std::move(path));
    if (auto st = j.optional_object("steering")) {
      st->allow_only({"max_speed_mps", "max_accel_mps2", "time_constant_s"});
      s.steering.max_speed_mps = st->number("max_speed_mps", s.steering.max_speed_mps, -1.0, 1e4);
      s.steering.max_accel_mps2 = st->number("max_accel_mps2", s.steering.max_accel_mps2, -1.0, 1e4);
      s.steering.time_constant_s = st->number("time_constant_s", s.steering.time_constant_s, 0.0, 1e4);
    }
    ships.push_back(std::move(s));
  }
  return ships;
}

// ---------------------------------------------------------------- kernels

void ship_kernels(double beta, double w, cd& phi1, cd& phi2) {
  const double a = beta - w;
  const cd iw(0.0, w);
  phi1 = std::exp(cd(0.0, -w)) * (-1.0 + iw * g_kernel(a, -1.0));
  phi2 = 1.0 + iw * g_kernel(a, +1.0);
}

cd ship_translation_factor(double beta, double w) {
  // beta (e^{-i beta} - e^{-i w}) / (beta - w) = beta e^{-i w} (e^{-i a} - 1) / a
  return beta * std::exp(cd(0.0, -w)) * h_kernel(beta - w);
}

double hull_spectrum(const HullParams& hull, double kx, double ky, double heading) {
  const double c = std::cos(heading), s = std::sin(heading);
  const double ka = kx * c + ky * s;   // along the heading
  const double kb = -kx * s + ky * c;  // across
  const double a = 0.5 * hull.length_m, b = 0.5 * hull.beam_m;
  const double q = std::sqrt(a * a * ka * ka + b * b * kb * kb);
  const double blur = hull.blur();
  return hull.draft_m * 2.0 * kPi * a * b * j1_over_q(q) * std::exp(-0.5 * (kx * kx + ky * ky) * blur * blur);
}

// ---------------------------------------------------------------- stage

ShipWaves::ShipWaves(const Water& water, int n, double length_m, int patch, std::vector<Ship> ships, PlanEffort effort)
    : water_(water),
      n_(n),
      p_(patch),
      dx_(length_m / n),
      ships_(std::move(ships)),
      buf_(static_cast<std::size_t>(patch) * patch),
      ph_(4 * static_cast<std::size_t>(patch)),
      inverse_(patch, patch, buf_.data(), buf_.data(), Fft2D::backward, effort) {
  if (patch < 2 || patch % 2 != 0 || patch > n)
    throw std::invalid_argument("ship waves: patch must be even and at most the grid size");
  const double half = 0.25 * p_ * dx_;
  for (std::size_t i = 0; i < ships_.size(); ++i) {
    const HullParams& h = ships_[i].hull;
    if (!(h.length_m > 0 && h.beam_m > 0 && h.draft_m >= 0))
      throw std::invalid_argument("ship " + std::to_string(i) +
                                  ": length and beam must be positive, draft not negative");
    const double reach = 0.5 * std::max(h.length_m, h.beam_m) + 3.0 * h.blur();
    if (reach > half)
      throw std::invalid_argument("ship " + std::to_string(i) + ": hull half-length plus 3 blur radii (" +
                                  std::to_string(reach) + " m) exceeds a quarter of the patch (" +
                                  std::to_string(half) + " m); enlarge the margin or the grid spacing");
  }
  kx_.resize(static_cast<std::size_t>(p_));
  for (int i = 0; i < p_; ++i) kx_[static_cast<std::size_t>(i)] = fft_wavenumber(i, p_, p_ * dx_);
  omega_.resize(static_cast<std::size_t>(p_) * p_);
  for (int r = 0; r < p_; ++r)
    for (int c = 0; c < p_; ++c)
      omega_[static_cast<std::size_t>(r) * p_ + c] = omega(water_, std::hypot(kx_[c], kx_[r]));
  cols_.resize(static_cast<std::size_t>(p_));
  cache_.resize(ships_.size());
  steer_.resize(ships_.size());
  last_.resize(ships_.size());
  motion_.resize(ships_.size());
  for (Cache& c : cache_) {
    c.g1 = AlignedBuffer<cfloat>(static_cast<std::size_t>(p_) * p_);
    c.g2 = AlignedBuffer<cfloat>(static_cast<std::size_t>(p_) * p_);
  }
}

std::size_t ShipWaves::bytes() const {
  return (buf_.size() + ph_.size() + 2 * cache_.size() * buf_.size() + store_.size() + delay_.size()) * sizeof(cfloat) +
         omega_.size() * sizeof(double);
}

void ShipWaves::check_step(double dt) const {
  const double limit = 0.25 * p_ * dx_;
  for (std::size_t i = 0; i < ships_.size(); ++i) {
    const auto& pts = ships_[i].path.points();
    for (std::size_t j = 1; j < pts.size(); ++j) {
      const double span = pts[j].t_s - pts[j - 1].t_s;
      const double d = std::hypot(pts[j].x_m - pts[j - 1].x_m, pts[j].y_m - pts[j - 1].y_m);
      // a jump (zero duration) or a step longer than the segment moves at most d per step
      const double per_step = span > 0.0 ? d * std::min(1.0, dt / span) : d;
      if (per_step > limit)
        throw std::invalid_argument("ship " + std::to_string(i) + ": moves " + std::to_string(per_step) +
                                    " m in one step (path segment " + std::to_string(j) +
                                    "), more than a quarter of the ship patch (" + std::to_string(limit) +
                                    " m); use a smaller dt or a larger margin");
    }
  }
}

// ---------------------------------------------------------------- steering

namespace {
// True when ship's last step ended at t (to rounding): its velocity and heading are the ones to
// continue from, not the path's at t (a steered ship has left its path).
template <class Last>
bool last_ended_at(const Last& l, double t) {
  return l.valid && std::abs(l.t1 - t) <= 1e-9 * std::max(1.0, std::abs(t));
}

// The scene's top speed, or sqrt(g length) (1 m/s without gravity).
double top_speed(const Ship& s, const Water& w) {
  if (s.steering.max_speed_mps > 0) return s.steering.max_speed_mps;
  const double fr1 = std::sqrt(w.gravity_mps2 * s.hull.length_m);
  return fr1 > 0 ? fr1 : 1.0;
}
}  // namespace

double ShipWaves::steer_speed_limit(int i, double dt) const {
  // check_step's bound: at most a quarter of the patch per step
  return std::min(top_speed(ships_[static_cast<std::size_t>(i)], water_), 0.25 * p_ * dx_ / dt);
}

double ShipWaves::steer_accel(int i) const {
  const Ship& s = ships_[static_cast<std::size_t>(i)];
  return s.steering.max_accel_mps2 > 0 ? s.steering.max_accel_mps2 : top_speed(s, water_) / 2.0;
}

bool ShipWaves::steer(int i, double t, double x, double y, double vx, double vy) {
  if (i < 0 || i >= ships()) return false;
  const double len = n_ * dx_;
  if (!(std::isfinite(t) && std::isfinite(x) && std::isfinite(y) && std::isfinite(vx) && std::isfinite(vy)))
    return false;
  if (!(x >= 0 && x <= len && y >= 0 && y <= len)) return false;
  const std::size_t k = static_cast<std::size_t>(i);
  Steer& st = steer_[k];
  if (!st.active) {
    // take over from the path at t without a jump in position, velocity or heading
    Ship& s = ships_[k];
    s.path.position(t, st.x, st.y);
    velocity_at(i, t, st.vx, st.vy);
    st.h = last_ended_at(last_[k], t) ? last_[k].h1 : s.path.heading(t);
    s.path.truncate_after(t);
    st.active = true;
  }
  st.tx = x, st.ty = y, st.tvx = vx, st.tvy = vy, st.tt = t;
  return true;
}

ShipPoseNow ShipWaves::pose(int i, double t) const {
  const std::size_t k = static_cast<std::size_t>(i);
  ShipPoseNow p;
  const Steer& st = steer_[k];
  if (st.active) {
    p.x_m = st.x, p.y_m = st.y, p.heading_rad = st.h, p.speed_mps = std::hypot(st.vx, st.vy);
    return p;
  }
  const ShipPath& path = ships_[k].path;
  path.position(t, p.x_m, p.y_m);
  p.heading_rad = path.heading(t);
  double vx, vy;
  velocity_at(i, t, vx, vy);
  p.speed_mps = std::hypot(vx, vy);
  return p;
}

void ShipWaves::velocity_at(int i, double t, double& vx, double& vy) const {
  const std::size_t k = static_cast<std::size_t>(i);
  if (last_ended_at(last_[k], t)) {
    vx = last_[k].vx, vy = last_[k].vy;
  } else {
    ships_[k].path.velocity(t, vx, vy);
  }
}

ShipWaves::Motion ShipWaves::motion(int i, double t, double dt) const {
  const std::size_t k = static_cast<std::size_t>(i);
  const Ship& s = ships_[k];
  const Steer& st = steer_[k];
  Motion m;
  if (!st.active) {
    s.path.position(t, m.x0, m.y0);
    s.path.position(t + dt, m.x1, m.y1);
    s.path.step_velocity(t, dt, m.vx, m.vy);
    m.h0 = s.path.heading(t);
    m.h1 = s.path.heading(t + dt);
    return m;
  }
  // steering (see steer()): the target point at the start of the step, clamped to the grid
  const double len = n_ * dx_;
  const double age = t - st.tt;
  const double px = std::clamp(st.tx + st.tvx * age, 0.0, len), py = std::clamp(st.ty + st.tvy * age, 0.0, len);
  const double ex = px - st.x, ey = py - st.y, e = std::hypot(ex, ey);
  const double a = steer_accel(i), vmax = steer_speed_limit(i, dt);
  const double tau = std::max(s.steering.time_constant_s, dt);
  const bool target_moves = st.tvx != 0.0 || st.tvy != 0.0;
  double dvx = st.tvx, dvy = st.tvy;  // desired velocity
  if (e > 0 && (target_moves || e > 0.05 * dx_)) {
    const double approach = std::min(e / tau, std::sqrt(2.0 * a * e));
    dvx += ex / e * approach;
    dvy += ey / e * approach;
  }
  const double dv = std::hypot(dvx, dvy);
  if (dv > vmax) dvx *= vmax / dv, dvy *= vmax / dv;
  double cx = dvx - st.vx, cy = dvy - st.vy;
  const double c = std::hypot(cx, cy), cmax = a * dt;
  if (c > cmax) cx *= cmax / c, cy *= cmax / c;
  if (c < 1e-3 * cmax) cx = cy = 0.0;  // rounding-level change: keep the kernels
  m.vx = st.vx + cx;
  m.vy = st.vy + cy;
  m.x0 = st.x;
  m.y0 = st.y;
  m.x1 = st.x + m.vx * dt;
  m.y1 = st.y + m.vy * dt;
  m.h0 = st.h;
  m.h1 = (m.vx != 0.0 || m.vy != 0.0) ? std::atan2(m.vy, m.vx) : st.h;
  return m;
}

void ShipWaves::rebuild(const Ship& s, Cache& c, double vx, double vy, double h0, double h1, double dt) {
  ++rebuilds_;
  c.vx = vx;
  c.vy = vy;
  c.h0 = h0;
  c.h1 = h1;
  c.dt = dt;
  const double norm = 1.0 / (dx_ * dx_ * static_cast<double>(p_) * p_);
  // P^2 modes, each a few complex exponentials and Bessel terms (~2 ms at P = 64, 8 ms at 128 on
  // one core): rebuilt every step while a steered ship accelerates or turns, so spread over threads
#pragma omp parallel for schedule(static)
  for (int r = 0; r < p_; ++r)
    for (int col = 0; col < p_; ++col) {
      const std::size_t m = static_cast<std::size_t>(r) * p_ + col;
      const double kx = kx_[static_cast<std::size_t>(col)], ky = kx_[static_cast<std::size_t>(r)];
      const double k = std::hypot(kx, ky);
      if (k == 0.0) {
        c.g1[m] = c.g2[m] = cfloat(0.0f, 0.0f);
        continue;
      }
      const double om = omega_[m];
      cd phi1, phi2;
      ship_kernels((kx * vx + ky * vy) * dt, om * dt, phi1, phi2);
      const double e0 = hull_spectrum(s.hull, kx, ky, h0);
      const double e1 = h1 == h0 ? e0 : hull_spectrum(s.hull, kx, ky, h1);
      const cd conv(0.0, -om / k * norm);  // -i omega / k, with 1/(dx^2 P^2)
      c.g1[m] = cfloat(conv * phi1 * e0);
      c.g2[m] = cfloat(conv * phi2 * e1);
    }
}

void ShipWaves::patch_spectrum(int i, double t, double dt, cfloat* out, int& row0, int& col0) {
  const Ship& s = ships_[static_cast<std::size_t>(i)];
  Cache& c = cache_[static_cast<std::size_t>(i)];
  const Motion mo = motion(i, t, dt);
  motion_[static_cast<std::size_t>(i)] = mo;
  const double x0 = mo.x0, y0 = mo.y0, x1 = mo.x1, y1 = mo.y1, vx = mo.vx, vy = mo.vy, h0 = mo.h0, h1 = mo.h1;
  if (c.dt != dt || c.vx != vx || c.vy != vy || c.h0 != h0 || c.h1 != h1) rebuild(s, c, vx, vy, h0, h1, dt);

  // patch centred on the cell nearest to the middle of the step
  const double mx = 0.5 * (x0 + x1), my = 0.5 * (y0 + y1);
  const long cc = std::lround(mx / dx_), rc = std::lround(my / dx_);
  const double d0x = x0 - cc * dx_, d0y = y0 - rc * dx_, d1x = x1 - cc * dx_, d1y = y1 - rc * dx_;
  cfloat* ex0 = ph_.data();
  cfloat* ey0 = ex0 + p_;
  cfloat* ex1 = ey0 + p_;
  cfloat* ey1 = ex1 + p_;
  for (int j = 0; j < p_; ++j) {
    const double k = kx_[static_cast<std::size_t>(j)];
    ex0[j] = cfloat(std::exp(cd(0.0, -k * d0x)));
    ey0[j] = cfloat(std::exp(cd(0.0, -k * d0y)));
    ex1[j] = cfloat(std::exp(cd(0.0, -k * d1x)));
    ey1[j] = cfloat(std::exp(cd(0.0, -k * d1y)));
  }
  const cfloat* g1 = c.g1.data();
  const cfloat* g2 = c.g2.data();
  for (int r = 0; r < p_; ++r) {
    const cfloat a = ey0[r], b = ey1[r];
    const std::size_t o = static_cast<std::size_t>(r) * p_;
    for (int j = 0; j < p_; ++j) out[o + j] = g1[o + j] * (a * ex0[j]) + g2[o + j] * (b * ex1[j]);
  }
  auto wrap = [&](long v) { return static_cast<int>(((v % n_) + n_) % n_); };
  row0 = wrap(rc);
  col0 = wrap(cc);
}

bool ShipWaves::add(cfloat* z, double t, double dt) { return add_rows(z, 0, n_, t, dt); }

bool ShipWaves::make_patch(int i, double t, double dt, int delay, int& r0, int& c0) {
  patch_spectrum(i, t, dt, buf_.data(), r0, c0);
  if (delay > 0) {
    // observed delay steps later: the spectral propagation of eq. 1, e^{-i omega delay dt}
    if (delay > max_delay_) throw std::logic_error("ShipWaves::gather: delay beyond reserve_gather");
    if (delay_dt_ != dt) build_delays(dt);
    const cfloat* f = delay_.data() + static_cast<std::size_t>(delay - 1) * buf_.size();
    for (std::size_t m = 0; m < buf_.size(); ++m) buf_[m] *= f[m];
  }
  inverse_.execute();
  if (poison_) {
    buf_[0] = cfloat(NAN, 0.0f);
    poison_ = false;
  }
  if (!all_finite(buf_.span())) return false;
  // the step is taken: commit the motion (steering state, last velocity and heading)
  const std::size_t k = static_cast<std::size_t>(i);
  const Motion& mo = motion_[k];
  last_[k] = Last{true, t + dt, mo.vx, mo.vy, mo.h1};
  Steer& st = steer_[k];
  if (st.active) {
    st.x = mo.x1, st.y = mo.y1, st.vx = mo.vx, st.vy = mo.vy, st.h = mo.h1;
  }
  return true;
}

void ShipWaves::scatter_patch(const cfloat* src0, int r0, int c0, cfloat* z, int row0, int rows) {
  // scatter-add with periodic wrap at the grid edge
  for (int j = 0; j < p_; ++j) cols_[static_cast<std::size_t>(j)] = ((c0 + fft_signed_index(j, p_)) % n_ + n_) % n_;
  for (int r = 0; r < p_; ++r) {
    const int row = ((r0 + fft_signed_index(r, p_)) % n_ + n_) % n_;
    if (row < row0 || row >= row0 + rows) continue;  // another rank's row
    cfloat* dst = z + static_cast<std::size_t>(row - row0) * n_;
    const cfloat* src = src0 + static_cast<std::size_t>(r) * p_;
    for (int j = 0; j < p_; ++j) dst[cols_[static_cast<std::size_t>(j)]] += src[j];
  }
}

bool ShipWaves::add_rows(cfloat* z, int row0, int rows, double t, double dt) {
  for (int i = 0; i < ships(); ++i) {
    int r0, c0;
    if (!make_patch(i, t, dt, 0, r0, c0)) return false;
    scatter_patch(buf_.data(), r0, c0, z, row0, rows);
  }
  return true;
}

void ShipWaves::reserve_gather(int k) {
  const int slots = std::max(1, k) * ships();
  if (slots > slots_) {
    store_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(slots) * buf_.size());
    slots_ = slots;
    pending_.reserve(static_cast<std::size_t>(slots));
  }
  if (k - 1 > max_delay_) {
    max_delay_ = k - 1;
    delay_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(max_delay_) * buf_.size());
    delay_dt_ = -1;
  }
}

void ShipWaves::build_delays(double dt) {
  const std::size_t pp = buf_.size();
  for (int d = 1; d <= max_delay_; ++d)
    for (std::size_t m = 0; m < pp; ++m)
      delay_[static_cast<std::size_t>(d - 1) * pp + m] = cfloat(std::exp(cd(0.0, -omega_[m] * d * dt)));
  delay_dt_ = dt;
}

bool ShipWaves::gather(double t, double dt, int delay) {
  for (int i = 0; i < ships(); ++i) {
    if (static_cast<int>(pending_.size()) >= slots_) throw std::logic_error("ShipWaves::gather: beyond reserve_gather");
    int r0, c0;
    if (!make_patch(i, t, dt, delay, r0, c0)) return false;
    const std::size_t slot = pending_.size();
    std::copy(buf_.data(), buf_.data() + buf_.size(), store_.data() + slot * buf_.size());
    pending_.push_back(Pending{slot, r0, c0});
  }
  return true;
}

void ShipWaves::scatter_rows(cfloat* z, int row0, int rows) {
  for (const Pending& q : pending_) scatter_patch(store_.data() + q.slot * buf_.size(), q.r0, q.c0, z, row0, rows);
  pending_.clear();
}

}  // namespace huygens
