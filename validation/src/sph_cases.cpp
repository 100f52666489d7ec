// SPH validation cases (paper 000): kernels, hydrostatic column, Martin & Moyce dam break,
// no leakage, heightfield extraction. `huygens validate` runs the full versions below; the
// tests run the same functions at smaller sizes.
#include "huygens/validation/sph_cases.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include "huygens/common/report.hpp"
#include "huygens/sph/surface.hpp"
#include "huygens/sph/system.hpp"

namespace huygens {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kG = 9.81f;

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

// radial integral 4 pi int_0^h r^2 f(r) dr by the midpoint rule
template <class F>
double radial_integral(double h, F f) {
  const int n = 200000;
  double s = 0;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * h / n;
    s += r * r * f(r);
  }
  return 4 * kPi * s * h / n;
}

// least-squares fit p(z) = a + b z (a in Pa, b in Pa/m) over the particles deeper than one support radius below the
// top, from the positions and pressures the system holds
void pressure_fit(const SphSystem& s, double& a, double& b) {
  float ztop = 0.f;
  for (float z : s.z()) ztop = std::max(ztop, z);
  double sw = 0, sz = 0, sp = 0, szz = 0, szp = 0;
  for (std::size_t i = 0; i < s.count(); ++i) {
    if (s.z()[i] > ztop - s.support()) continue;
    const double z = s.z()[i], pr = s.pressure()[i];
    sw += 1;
    sz += z;
    sp += pr;
    szz += z * z;
    szp += z * pr;
  }
  b = (sw * szp - sz * sp) / (sw * szz - sz * sz);
  a = (sp - b * sz) / sw;
}

}  // namespace

std::vector<ValidationRow> sph_kernel_rows(float support_factor) {
  const std::string c = "sph_kernels";
  std::vector<ValidationRow> rows;
  const float dx = 1.f, h = support_factor * dx;
  SphKernels k(h);
  // continuum normalisation of each kernel
  rows.push_back(check(c, "poly6 integral (1)", radial_integral(h, [&](double r) { return k.poly6(float(r * r)); }), 1,
                       rel(radial_integral(h, [&](double r) { return k.poly6(float(r * r)); }), 1), 1e-3));
  const double isp = radial_integral(h, [&](double r) { return k.spiky(float(r)); });
  rows.push_back(check(c, "spiky integral (1)", isp, 1, rel(isp, 1), 1e-3));
  const double ivi = radial_integral(h, [&](double r) { return k.viscosity(float(r)); });
  rows.push_back(check(c, "viscosity integral (1)", ivi, 1, rel(ivi, 1), 1e-3));
  // Lattice sums (criterion: 1 % at the default spacing). Each kernel is checked in
  // the role the solver uses it in, with the particle volume V = m / rho0 = dx^3 / S6 of the mass
  // normalisation (S6 = poly6 lattice sum): poly6 VALUE (density), spiky GRADIENT (first moment
  // -sum V W'(r) x^2 / r: the gradient of a linear field), viscosity LAPLACIAN (second moment
  // 1/2 sum V x^2 lap W: the Laplacian of x^2). The VALUES of spiky (cusp at r = 0) and viscosity
  // (singular at r = 0) are never used; their lattice sums converge to 1 only as h/dx grows
  // (errors 24 % and 55 % at h = 2 dx, rows kept at 1 %), shown at h = 8 dx and 20 dx.
  auto lattice = [](float hf, double& s6, double& ssp, double& svi, double& moment, double& lap2, double& anti) {
    SphKernels kk(hf);
    s6 = ssp = svi = moment = lap2 = anti = 0;
    const int R = static_cast<int>(std::ceil(hf)) + 1;
    for (int i = -R; i <= R; ++i)
      for (int j = -R; j <= R; ++j)
        for (int l = -R; l <= R; ++l) {
          const float r2 = float(i * i + j * j + l * l), r = std::sqrt(r2);
          s6 += kk.poly6(r2);
          ssp += kk.spiky(r);
          if (r > 0) svi += kk.viscosity(r);
          lap2 += 0.5 * kk.viscosity_lap(r) * double(i * i);
          if (r > 0 && r < hf) {
            moment += -kk.spiky_dr(r) * float(i * i) / r;
            const float gx = kk.spiky_dr(r) * float(i) / r, gmx = kk.spiky_dr(r) * float(-i) / r;
            anti = std::max(anti, double(std::fabs(gx + gmx)));
          }
        }
  };
  double s6, ssp, svi, moment, lap2, anti;
  lattice(h, s6, ssp, svi, moment, lap2, anti);
  const std::string at = " at h = " + num(support_factor, 3) + " dx";
  rows.push_back(check(c, "poly6 value lattice sum" + at + " (density) (1)", s6, 1, rel(s6, 1), 0.01));
  // raw kernel moment with V = dx^3 (the solver divides the gradient by each particle's measured moment)
  rows.push_back(
      check(c, "spiky gradient first moment on the lattice, V = dx^3" + at + " (1)", moment, 1, rel(moment, 1), 0.05));
  // reported: on the particle lattice at h = 2 dx the sum carries a discretisation error of 2 %
  // (it oscillates with h/dx: 0.954 at 3 dx, 1.008 at 4 dx, 1.0002 at 8 dx), which scales the
  // viscous term of a flow on the lattice by 0.979; checked for convergence at 8 dx below
  rows.push_back(report_only(c, "viscosity Laplacian second moment, V = m/rho0" + at + " (lattice error) (1)",
                             lap2 / s6, 1, rel(lap2 / s6, 1)));
  rows.push_back(check(c, "spiky gradient antisymmetry |grad W(r) + grad W(-r)| (1/m^4)", anti, 0, anti, 1e-7));
  // reported, not judged: the solver uses spiky and viscosity only through their gradient and
  // Laplacian, so their value sums at h = 2 dx are no target (the convergence rows below are)
  rows.push_back(report_only(c, "spiky value lattice sum" + at + " (unused: cusp at 0) (1)", ssp, 1, rel(ssp, 1)));
  rows.push_back(report_only(c, "viscosity value lattice sum without r = 0" + at + " (unused: singular) (1)", svi, 1,
                             rel(svi, 1)));
  double t6, tsp, tvi, tm, tl, ta;
  lattice(8.f, t6, tsp, tvi, tm, tl, ta);
  rows.push_back(check(c, "spiky value lattice sum at h = 8 dx (convergence) (1)", tsp, 1, rel(tsp, 1), 0.01));
  rows.push_back(
      check(c, "viscosity Laplacian second moment at h = 8 dx (convergence) (1)", tl / t6, 1, rel(tl / t6, 1), 0.01));
  lattice(20.f, t6, tsp, tvi, tm, tl, ta);
  rows.push_back(check(c, "viscosity value lattice sum at h = 20 dx (convergence, error ~ 3 (dx/h)^2) (1)", tvi, 1,
                       rel(tvi, 1), 0.01));
  return rows;
}

namespace {

// The column's figures from one start.
struct ColumnRun {
  double bottom = 0, gradient = 0, expected = 0;  // p(z) fit a and -b, the weight per area (Pa, Pa/m, Pa)
  double compression = 0, mean_error = 0;         // max(rho/rho0 - 1), mean |rho/rho0 - 1| below the surface layer
  double still = 0;                               // largest speed below the surface layer over the hold (m/s)
};

// Moves every particle of the start lattice by up to eps (m) along each axis, uniformly at random from `seed`.
void perturb_positions(SphSystem& s, unsigned seed, float eps) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-eps, eps);
  std::vector<float> x(s.x().begin(), s.x().end()), y(s.y().begin(), s.y().end()), z(s.z().begin(), s.z().end());
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] += u(rng);
    y[i] += u(rng);
    z[i] += u(rng);
  }
  s.set_particles(x, y, z);
}

// the largest speed over the particles deeper than one support radius below the top (m/s)
float max_speed_below_surface(const SphSystem& s) {
  float ztop = 0.f, v2 = 0.f;
  for (float z : s.z()) ztop = std::max(ztop, z);
  for (std::size_t i = 0; i < s.count(); ++i)
    if (s.z()[i] <= ztop - s.support())
      v2 = std::max(v2, s.vx()[i] * s.vx()[i] + s.vy()[i] * s.vy()[i] + s.vz()[i] * s.vz()[i]);
  return std::sqrt(v2);
}

// density figures of the end state (ColumnRun::compression, mean_error)
void column_density(const SphSystem& s, float rho0, ColumnRun& out) {
  float ztop = 0.f;
  for (float z : s.z()) ztop = std::max(ztop, z);
  double mean_err = 0;
  std::size_t ni = 0;
  for (std::size_t i = 0; i < s.count(); ++i) {
    const double rho_err = s.density()[i] / rho0 - 1.0;
    out.compression = std::max(out.compression, rho_err);
    if (s.z()[i] > ztop - s.support()) continue;
    mean_err += std::fabs(rho_err);
    ++ni;
  }
  out.mean_error = mean_err / double(std::max<std::size_t>(ni, 1));
}

// One start of the column: seed 0 the lattice as placed, else perturbed by up to 1e-7 m per axis.
ColumnRun run_column(const SphParams& p, double settle_s, double relax_s, double hold_s, unsigned seed) {
  SphSystem s(p);
  if (seed != 0) perturb_positions(s, seed, 1e-7f);
  s.set_damping(20.f);
  while (s.time() < settle_s) s.step();
  s.set_damping(0.f);
  // free relaxation: out of the initial cubic lattice the particles rearrange into a stable packing, in
  // events of ~1e-2 sqrt(g H) at irregular times for several seconds (velocity damping only slows it down)
  while (s.time() < settle_s + relax_s) s.step();
  const double t0 = s.time();
  ColumnRun out;
  std::int64_t k = 0;
  // the pressure fit p(z) = a + b z, averaged over the hold (every 16th step): a single step's fit of the DFSPH
  // column swings by +-2.5 % (standard deviation 1-1.7 %) as the packing rearranges (docs/sph.md, "DFSPH at the walls")
  double a = 0, b = 0, sa = 0, sb = 0;
  int nfit = 0;
  while (s.time() < t0 + hold_s) {
    s.step();
    out.still = std::max(out.still, double(max_speed_below_surface(s)));
    if (++k % 16 != 0) continue;
    pressure_fit(s, a, b);
    sa += a;
    sb += b;
    ++nfit;
  }
  s.refresh();
  pressure_fit(s, a, b);
  out.bottom = (sa + a) / (nfit + 1);
  out.gradient = -(sb + b) / (nfit + 1);
  column_density(s, p.rest_density_kgpm3, out);
  // the weight per floor area N m g / A: exact for any packing. (No row against rho0 g H: with
  // m = rho0 / sum_lattice W (system.cpp) it is N m g / A = rho0 g H / (dx^3 sum_lattice W), a kernel
  // constant, 1 + 3e-5 for DFSPH's cubic spline at h = 2 dx, so such a row repeats this one.)
  out.expected = s.count() * double(s.mass()) * kG / (p.container_m[0] * p.container_m[1]);
  return out;
}

// The column's judged rows from one start.
std::vector<ValidationRow> column_rows(const std::string& c, const ColumnRun& r, double rho0, double ref, bool df,
                                       const std::string& still) {
  return {check(c, "bottom pressure from the p(z) fit, mean over the hold (Pa) vs weight/area", r.bottom, r.expected,
                rel(r.bottom, r.expected), 0.02),
          check(c, "pressure gradient -dp/dz, mean over the hold (Pa/m) vs rho0 g", r.gradient, rho0 * kG,
                rel(r.gradient, rho0 * kG), 0.02),
          check(c, "max compression max(rho/rho0 - 1) (1)", r.compression, 0, r.compression, 0.01),
          // DFSPH solves for the density: 0.1 % (WCSPH: 1 %, the Mach number of its sound speed)
          check(c, "mean |rho/rho0 - 1| below the surface layer (1)", r.mean_error, 0, r.mean_error, df ? 0.001 : 0.01),
          check(c, still, r.still / ref, 0, r.still / ref, 0.01)};
}

}  // namespace

std::vector<ValidationRow> sph_hydrostatic_rows(int nx, int nz, double settle_s, double relax_s, double hold_s,
                                                SphMethod method, int starts) {
  const bool df = method == SphMethod::dfsph;
  const std::string c = df ? "sph_hydrostatic_dfsph" : "sph_hydrostatic";
  const float dx = 0.005f;
  SphParams p;
  p.method = method;
  p.spacing_m = dx;
  p.container_m = {nx * dx, nx * dx, 2.f * nz * dx};
  p.fluid.push_back({{0, 0, 0}, {nx * dx, nx * dx, nz * dx}});
  starts = std::max(starts, 1);
  std::vector<ColumnRun> runs(static_cast<std::size_t>(starts));
  std::vector<std::exception_ptr> failed(runs.size());
  // the starts are independent runs (each below kSphParallelMin particles, so one thread each)
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < starts; ++k) {
    try {
      runs[std::size_t(k)] = run_column(p, settle_s, relax_s, hold_s, unsigned(k));
    } catch (...) {
      failed[std::size_t(k)] = std::current_exception();
    }
  }
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  const double ref = std::sqrt(kG * nz * dx), rho0 = p.rest_density_kgpm3;
  const std::string still = "max speed below the surface layer over " + num(hold_s, 3) + " s / sqrt(g H), worst of " +
                            std::to_string(starts) + " starts (1)";
  // each row: the worst start (largest error)
  std::vector<ValidationRow> rows = column_rows(c, runs[0], rho0, ref, df, still);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const auto other = column_rows(c, runs[k], rho0, ref, df, still);
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (!(other[i].error <= rows[i].error)) rows[i] = other[i];
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    rows.push_back(report_only(c,
                               "max speed below the surface layer / sqrt(g H), start " + std::to_string(k) +
                                   (k == 0 ? " (the lattice)" : " (lattice + up to 1e-7 m per axis)") + " (1)",
                               runs[k].still / ref, 0, runs[k].still / ref));
  return rows;
}

namespace {

struct DamRun {
  std::vector<double> T, Z;
  bool finite = true;
  double vmax_ratio = 0;
  std::size_t outside = 0;   // most particle centres outside the container at any step
  std::size_t through = 0;   // most particle centres past the first boundary layer (dx/2 beyond a wall)
  double compression = 0;    // largest mean over particles of max(0, rho/rho0 - 1) at any step
  double excursion = -1e30;  // largest distance of a centre beyond a container face at any step (dx; < 0: inside)
};

// particles whose centre lies outside the box [-e, L + e] (no clamp: only the boundary particles
// keep them in; e = 0: beyond a wall face, e = dx/2: past the first layer of boundary particles)
std::size_t count_outside(const SphSystem& s, const std::array<float, 3>& L, float e = 0.f) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.count(); ++i)
    n += !(s.x()[i] >= -e && s.x()[i] <= L[0] + e && s.y()[i] >= -e && s.y()[i] <= L[1] + e && s.z()[i] >= -e &&
           s.z()[i] <= L[2] + e);
  return n;
}

// the largest signed distance of a particle centre beyond a face of the box [0, L] (m; negative: every centre is
// inside, by at least its magnitude)
double largest_excursion(const SphSystem& s, const std::array<float, 3>& L) {
  float e = -1e30f;
  for (std::size_t i = 0; i < s.count(); ++i)
    e = std::max({e, -s.x()[i], s.x()[i] - L[0], -s.y()[i], s.y()[i] - L[1], -s.z()[i], s.z()[i] - L[2]});
  return e;
}

// mean over the particles of max(0, rho_i/rho0 - 1): the densities of the last step's neighbour pass (DFSPH:
// at the positions the previous step's constant-density solve reached), the quantity whose prediction that
// solve drives below SphParams::dfsph_density_error (Bender and Koschier 2015, Alg. 3)
double mean_compression(const SphSystem& s, float rho0) {
  double sum = 0;
  for (float r : s.density()) sum += std::max(0.0, double(r) / rho0 - 1.0);
  return s.count() ? sum / double(s.count()) : 0.0;
}

// dam break: column width a, height aspect a, `na` particles across, 4 layers thick between free-slip walls, in a
// box container_len a long and 4 a high
DamRun run_dam(int na, double T_end, double t_end, float container_len, SphMethod method = SphMethod::wcsph,
               float aspect = 2.f) {
  const float a = 0.05715f, dx = a / na;
  SphParams p;
  p.method = method;
  p.spacing_m = dx;
  p.container_m = {container_len * a, 4 * dx, 4 * a};
  p.fluid.push_back({{0, 0, 0}, {a, 4 * dx, aspect * a}});
  SphSystem s(p);
  DamRun out;
  const double Ts = std::sqrt(2 * kG / a), vref = std::sqrt(2 * kG * 2 * a);
  const double stop = std::max(T_end / Ts, t_end);
  auto front = [&]() {
    float fx = 0.f;
    for (float x : s.x()) fx = std::max(fx, x);
    return (fx + 0.5f * dx) / a;
  };
  out.T.push_back(0);
  out.Z.push_back(front());
  try {
    while (s.time() < stop) {
      s.step();
      // every step: an impact's speed peak lasts a few steps (sampling every 8th step read 1.44 at
      // 8 across where every step reads 1.49)
      out.vmax_ratio = std::max(out.vmax_ratio, s.max_speed() / vref);
      out.outside = std::max(out.outside, count_outside(s, p.container_m));
      out.through = std::max(out.through, count_outside(s, p.container_m, 0.5f * dx));
      out.excursion = std::max(out.excursion, largest_excursion(s, p.container_m) / dx);
      out.compression = std::max(out.compression, mean_compression(s, p.rest_density_kgpm3));
      if (s.steps() % 8 == 0) {
        out.T.push_back(s.time() * Ts);
        out.Z.push_back(front());
      }
    }
  } catch (const std::exception&) {
    out.finite = false;
  }
  return out;
}

double interp(const std::vector<double>& X, const std::vector<double>& Y, double x) {
  auto it = std::lower_bound(X.begin(), X.end(), x);
  if (it == X.begin()) return Y.front();
  if (it == X.end()) return Y.back();
  const std::size_t i = static_cast<std::size_t>(it - X.begin());
  const double f = (x - X[i - 1]) / (X[i] - X[i - 1]);
  return Y[i - 1] + f * (Y[i] - Y[i - 1]);
}

// The heightfield of paper 000 eq. 5-6 on cells of the particle spacing, with the support
// radius and the iso value that puts a flat lattice's surface half a spacing above its top.
SphHeightfield default_heightfield(const SphSystem& s, const SphParams& p, float dx, SphSurfaceParams& sp) {
  sp.cell_m = dx;
  sp.radius_m = s.support();
  sp.iso = sph_flat_iso(sp.radius_m, dx);
  SphHeightfield hf;
  sph_heightfield_init(sp, p.container_m[0], p.container_m[1], hf);
  sph_extract_heightfield(sp, s.grid(), s.x().data(), s.y().data(), s.z().data(), hf);
  return hf;
}

}  // namespace

std::vector<ValidationRow> sph_dam_break_rows(int na, double T_end, const std::vector<MartinMoycePoint>& measured,
                                              SphMethod method) {
  const std::string c = method == SphMethod::dfsph ? "sph_dam_break_dfsph" : "sph_dam_break";
  if (measured.empty()) return {check(c, "no measured points given", 0, 1, 1, 0)};
  const DamRun run = run_dam(na, T_end + 0.05, 0.0, 8.f, method);
  std::vector<ValidationRow> rows;
  for (const auto& pt : measured) {
    if (pt.T > T_end || pt.T > 5.0) continue;
    const double zs = interp(run.T, run.Z, pt.T);
    const std::string q = "front z/a at T = " + num(pt.T, 4) + " (series a = " + pt.series + " in)";
    // reported: the early front of an instant release on a free-slip floor runs ahead of the measured one
    // (docs/sph.md, "Limits": the lead grows with resolution)
    if (pt.T <= kMartinMoyceEarlyT)
      rows.push_back(report_only(c, q + " (early: instant release, no floor friction)", zs, pt.Z, rel(zs, pt.Z)));
    else
      rows.push_back(check(c, q, zs, pt.Z, rel(zs, pt.Z), pt.T <= 3.0 ? 0.08 : 0.10));
  }
  // DFSPH: the density its constant-density solve reaches, within 6 times that solve's tolerance on the
  // mean error of its linearised prediction (SphParams::dfsph_density_error; docs/sph.md)
  if (method == SphMethod::dfsph) {
    const double tol = 6.0 * double(SphParams{}.dfsph_density_error);
    rows.push_back(check(c, "largest mean compression mean(max(0, rho/rho0 - 1)) at a step (1)", run.compression, 0,
                         run.compression, tol));
  }
  if (!run.finite) rows.push_back(check(c, "run stayed finite", 0, 1, 1, 0));
  return rows;
}

std::vector<ValidationRow> sph_leakage_rows(int na, double t_end, float container_len) {
  const std::string c = "sph_no_leakage";
  const DamRun run = run_dam(na, 0.0, t_end, container_len);
  const std::string at =
      " (" + std::to_string(na) + " across a, box " + num(container_len, 3) + " a long, " + num(t_end, 3) + " s)";
  std::vector<ValidationRow> rows;
  const double out = double(run.outside), through = double(run.through);
  rows.push_back(check(c, "most particle centres beyond a wall face at any step (no clamp)" + at, out, 0, out, 0));
  rows.push_back(check(c, "most particle centres past the first boundary layer (dx/2 beyond a wall)" + at, through, 0,
                       through, 0));
  rows.push_back(check(c, "non-finite values (1 = yes)" + at, run.finite ? 0 : 1, 0, run.finite ? 0 : 1, 0));
  rows.push_back(check(c, "max speed / sqrt(2 g H)" + at, run.vmax_ratio, 0, run.vmax_ratio, 1.5));
  return rows;
}

std::vector<ValidationRow> sph_containment_rows(int na, float aspect, float container_len, double t_end,
                                                SphMethod method) {
  const std::string c = method == SphMethod::dfsph ? "sph_no_leakage_dfsph" : "sph_no_leakage";
  const DamRun run = run_dam(na, 0.0, t_end, container_len, method, aspect);
  const std::string at = " (" + std::to_string(na) + " across a, column " + num(aspect, 3) + " a high, box " +
                         num(container_len, 3) + " a long, " + num(t_end, 3) + " s)";
  const double e = run.excursion, out = double(run.outside);
  return {check(c, "largest distance of a particle centre beyond a container face at any step (dx; < 0: inside)" + at,
                e, 0, std::max(e, 0.0), 0),
          check(c, "most particle centres beyond a container face at any step" + at, out, 0, out, 0),
          check(c, "non-finite values (1 = yes)" + at, run.finite ? 0 : 1, 0, run.finite ? 0 : 1, 0)};
}

std::vector<ValidationRow> sph_obstacle_rows(float dx, double t_end) {
  const std::string c = "sph_no_leakage";
  SphParams p;
  p.spacing_m = dx;
  p.container_m = {0.6f, 0.2f, 0.3f};
  p.fluid.push_back({{0.f, 0.f, 0.f}, {0.15f, 0.2f, 0.2f}});
  // the wedge of scenes/meshes/wedge.obj, 0.1 m long and wide, 0.08 m high, ridge along y
  const char* wedge =
      "v 0 0 0\nv 0.1 0 0\nv 0.05 0 0.08\nv 0 0.1 0\nv 0.1 0.1 0\nv 0.05 0.1 0.08\n"
      "f 1 2 3\nf 4 6 5\nf 1 4 5 2\nf 1 3 6 4\nf 2 5 6 3\n";
  SphObstacle mesh;
  SphMesh m = sph_parse_obj(wedge, "wedge.obj");
  for (auto& v : m.vertices) v = {v[0] + 0.25f, v[1] + 0.f, v[2]};
  mesh.set_mesh(std::move(m));
  SphObstacle sphere;
  sphere.type = SphObstacle::Type::sphere;
  sphere.sphere_centre_m = {0.3f, 0.15f, 0.05f};
  sphere.radius_m = 0.04f;
  SphObstacle cyl;
  cyl.type = SphObstacle::Type::cylinder;
  cyl.centre_m = {0.45f, 0.1f};
  cyl.radius_m = 0.03f;
  cyl.z1_m = 0.12f;
  SphObstacle box;
  box.min_m = {0.52f, 0.f, 0.f};
  box.max_m = {0.56f, 0.2f, 0.04f};
  p.obstacles = {mesh, sphere, cyl, box};
  SphSystem s(p);
  std::size_t inside = 0, deep = 0, outside = 0, through = 0;
  bool finite = true;
  try {
    while (s.time() < t_end) {
      s.step();
      std::size_t in = 0, dp = 0;
      for (std::size_t i = 0; i < s.count(); ++i)
        for (const auto& o : p.obstacles) {
          in += o.blocks(s.x()[i], s.y()[i], s.z()[i], 0.f);
          dp += o.blocks(s.x()[i], s.y()[i], s.z()[i], -0.5f * dx);
        }
      inside = std::max(inside, in);
      deep = std::max(deep, dp);
      outside = std::max(outside, count_outside(s, p.container_m));
      through = std::max(through, count_outside(s, p.container_m, 0.5f * dx));
    }
  } catch (const std::exception&) {
    finite = false;
  }
  const std::string at = " (dam break onto a mesh wedge, sphere, cylinder, box; " + std::to_string(s.count()) +
                         " particles, dx " + num(dx, 3) + " m, " + num(t_end, 3) + " s)";
  auto row = [&](const std::string& what, std::size_t v) { return check(c, what + at, double(v), 0, double(v), 0); };
  return {row("most particle centres inside an obstacle's surface at any step", inside),
          row("most particle centres past an obstacle's first boundary layer (deeper than dx/2)", deep),
          row("most particle centres beyond a container wall face at any step", outside),
          row("most particle centres past the container's first boundary layer (dx/2 beyond a wall)", through),
          row("non-finite values (1 = yes)", finite ? 0 : 1)};
}

namespace {

// A flat pool of n x n x depth particles settled (velocity damping) for settle_s: mean
// extracted height against volume / area, and the normals away from the walls.
void flat_pool_rows(const std::string& c, int n, int depth, double settle_s, float dx,
                    std::vector<ValidationRow>& rows) {
  SphParams p;
  p.spacing_m = dx;
  p.container_m = {n * dx, n * dx, 3.f * depth * dx};
  p.fluid.push_back({{0, 0, 0}, {n * dx, n * dx, depth * dx}});
  SphSystem s(p);
  s.set_damping(20.f);
  while (s.time() < settle_s) s.step();
  s.refresh();
  SphSurfaceParams sp;
  const SphHeightfield hf = default_heightfield(s, p, dx, sp);
  double mean = 0;
  for (float v : hf.height) mean += v;
  mean /= double(hf.height.size());
  const double expected = double(s.count()) * dx * dx * dx / (p.container_m[0] * p.container_m[1]);
  rows.push_back(check(c, "flat settled pool: mean height (m) vs volume/area", mean, expected,
                       std::fabs(mean - expected), 0.5 * dx));
  // normals over the interior columns: within R of a wall phi lacks the particles beyond it and the
  // extracted surface dips (a known limit of eq. 5 at container walls)
  double nz_min = 1;
  const std::size_t m = static_cast<std::size_t>(std::ceil(sp.radius_m / sp.cell_m));
  for (std::size_t r = m; r + m < hf.rows; ++r)
    for (std::size_t col = m; col + m < hf.cols; ++col)
      nz_min = std::min(nz_min, double(hf.normal[3 * (r * hf.cols + col) + 2]));
  rows.push_back(
      check(c, "flat settled pool: min normal z over columns >= R from the walls (1)", nz_min, 1, 1 - nz_min, 0.1));
}

// A static lattice filling z < z0 + slope x, 2n x n columns: fitted slope and mean normal of the
// extracted surface over the columns two support radii from the x walls.
void tilted_surface_rows(const std::string& c, int n, int depth, float slope, float dx,
                         std::vector<ValidationRow>& rows) {
  const int nxl = 2 * n;
  SphParams p;
  p.spacing_m = dx;
  p.container_m = {nxl * dx, n * dx, (depth + slope * nxl + 4) * dx};
  SphSystem s(p);
  std::vector<float> X, Y, Z;
  const float z0 = depth * dx;
  for (int i = 0; i < nxl; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < 4 * depth + nxl; ++k) {
        const float x = (i + 0.5f) * dx, y = (j + 0.5f) * dx, z = (k + 0.5f) * dx;
        if (z < z0 + slope * x) {
          X.push_back(x);
          Y.push_back(y);
          Z.push_back(z);
        }
      }
  s.set_particles(X, Y, Z);
  SphSurfaceParams sp;
  const SphHeightfield hf = default_heightfield(s, p, dx, sp);
  // least-squares slope over interior columns (two support radii from the x walls)
  double sw = 0, sx = 0, sh = 0, sxx = 0, sxh = 0;
  for (std::size_t r = 0; r < hf.rows; ++r)
    for (std::size_t col = 0; col < hf.cols; ++col) {
      const double x = (col + 0.5) * dx;
      if (x < 2 * s.support() || x > p.container_m[0] - 2 * s.support()) continue;
      const double hv = hf.height[r * hf.cols + col];
      sw += 1;
      sx += x;
      sh += hv;
      sxx += x * x;
      sxh += x * hv;
    }
  const double b = (sw * sxh - sx * sh) / (sw * sxx - sx * sx);
  rows.push_back(check(c, "tilted surface: fitted slope dh/dx (1)", b, slope, rel(b, slope), 0.05));
  // mean normal over the same interior columns (the lattice surface is a staircase column by column)
  double nxs = 0;
  int cnt = 0;
  for (std::size_t r = 0; r < hf.rows; ++r)
    for (std::size_t col = 0; col < hf.cols; ++col) {
      const double x = (col + 0.5) * dx;
      if (x < 2 * s.support() || x > p.container_m[0] - 2 * s.support()) continue;
      nxs += hf.normal[3 * (r * hf.cols + col)];
      ++cnt;
    }
  nxs /= std::max(cnt, 1);
  const double nx_expected = -slope / std::sqrt(1.0 + slope * slope);
  rows.push_back(
      check(c, "tilted surface: mean normal x component (1)", nxs, nx_expected, std::fabs(nxs - nx_expected), 0.05));
}

}  // namespace

std::vector<ValidationRow> sph_heightfield_rows(int n, int depth, double settle_s, float slope) {
  const std::string c = "sph_heightfield";
  std::vector<ValidationRow> rows;
  const float dx = 0.005f;
  flat_pool_rows(c, n, depth, settle_s, dx, rows);
  tilted_surface_rows(c, n, depth, slope, dx, rows);
  return rows;
}

std::vector<ValidationCase> sph_validation_cases() {
  return {
      {"sph_kernels", "sph", "poly6/spiky/viscosity normalisation on a lattice and in the continuum; antisymmetry",
       [] { return sph_kernel_rows(2.0f); }},
      {"sph_hydrostatic", "sph",
       "column 6 x 6 x 16 settled (1 s damped, 14 s free), then 4 s held, from 4 starts (the lattice, 3 moved by up "
       "to 1e-7 m; worst start): bottom pressure, density error, stillness below the surface layer",
       [] { return sph_hydrostatic_rows(6, 16, 1.0, 14.0, 4.0); }},
      {"sph_dam_break", "sph", "surge front vs Martin & Moyce (1952), both series, 16 particles across a, T <= 5",
       [] { return sph_dam_break_rows(16, 5.0, martin_moyce_1952()); }},
      {"sph_hydrostatic_dfsph", "sph",
       "DFSPH: the column of sph_hydrostatic (1 s damped, 14 s free, 4 s held, 4 starts): bottom pressure 2 %, "
       "density error 0.1 %",
       [] { return sph_hydrostatic_rows(6, 16, 1.0, 14.0, 4.0, SphMethod::dfsph); }},
      {"sph_dam_break_dfsph", "sph", "DFSPH: the surge front of sph_dam_break (Martin & Moyce 1952, 16 across, T <= 5)",
       [] { return sph_dam_break_rows(16, 5.0, martin_moyce_1952(), SphMethod::dfsph); }},
      {"sph_no_leakage", "sph",
       "dam break: no particle leaves the box, finite, max speed < 1.5 sqrt(2 g H); 10 s at 8 across in a 4a box, "
       "and the shipped scene's set-up (16 across, 8a box) over its wall impact (1 s; stress:sph runs it 10 s)",
       [] {
         auto rows = sph_leakage_rows(8, 10.0, 4.f);
         auto shipped = sph_leakage_rows(16, 1.0, 8.f);
         rows.insert(rows.end(), shipped.begin(), shipped.end());
         auto obstacles = sph_obstacle_rows(0.01f, 1.0);
         rows.insert(rows.end(), obstacles.begin(), obstacles.end());
         return rows;
       }},
      {"sph_no_leakage_dfsph", "sph",
       "DFSPH: dam breaks at 10, 16, 20 and 24 across, columns 2a and a high, 4a box, 1 s (impact, jet, return "
       "wave): no particle centre beyond a container face at any step, finite",
       [] {
         std::vector<ValidationRow> rows;
         for (const float aspect : {2.f, 1.f})
           for (const int na : {10, 16, 20, 24}) {
             auto r = sph_containment_rows(na, aspect, 4.f, 1.0, SphMethod::dfsph);
             rows.insert(rows.end(), r.begin(), r.end());
           }
         return rows;
       }},
      {"sph_heightfield", "sph", "heightfield of eq. 5-6: flat settled pool height = volume/area, tilted slope",
       [] { return sph_heightfield_rows(16, 8, 0.5, 0.25f); }},
  };
}

}  // namespace huygens
