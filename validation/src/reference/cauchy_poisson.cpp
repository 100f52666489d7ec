#include "huygens/validation/reference/cauchy_poisson.hpp"

#include <math.h>  // ::j0 (POSIX)

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <vector>

namespace huygens {

namespace {

// Gauss-Kronrod (7, 15) nodes and weights (QUADPACK qk15).
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
  double a, b, value, error;
  bool operator<(const Panel& o) const { return error < o.error; }
};

Panel gk15(const std::function<double(double)>& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = kWgk[7] * fc, g = kWg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double x = h * kXgk[j];
    const double s = f(c - x) + f(c + x);
    k += kWgk[j] * s;
    if (j % 2 == 1) g += kWg[j / 2] * s;
  }
  return Panel{a, b, k * h, std::abs((k - g) * h)};
}

}  // namespace

QuadratureResult integrate_gk15(const std::function<double(double)>& f, double a, double b, double abs_tol,
                                int initial_panels, int max_panels) {
  initial_panels = std::max(initial_panels, 1);
  std::vector<Panel> store;
  store.reserve(static_cast<std::size_t>(initial_panels) * 4);
  std::priority_queue<Panel> heap;
  QuadratureResult out;
  double value = 0, error = 0;
  for (int i = 0; i < initial_panels; ++i) {
    const Panel p = gk15(f, a + (b - a) * i / initial_panels, a + (b - a) * (i + 1) / initial_panels);
    value += p.value;
    error += p.error;
    heap.push(p);
  }
  out.evaluations = 15L * initial_panels;
  // bisect the worst panel until the summed error estimate meets the tolerance
  while (error > abs_tol && static_cast<int>(heap.size()) < max_panels) {
    const Panel w = heap.top();
    heap.pop();
    const double m = 0.5 * (w.a + w.b);
    const Panel l = gk15(f, w.a, m), r = gk15(f, m, w.b);
    out.evaluations += 30;
    value += l.value + r.value - w.value;
    error += l.error + r.error - w.error;
    heap.push(l);
    heap.push(r);
  }
  // re-sum to avoid the cancellation of the running update
  value = 0;
  error = 0;
  out.panels = static_cast<int>(heap.size());
  while (!heap.empty()) {
    value += heap.top().value;
    error += heap.top().error;
    heap.pop();
  }
  out.value = value;
  out.error = error;
  return out;
}

double bessel_j0(double x) { return ::j0(x); }

QuadratureResult cauchy_poisson_quadrature(const CauchyPoissonGaussian& g, double r_m, double t_s) {
  const double s2 = g.sigma_m * g.sigma_m;
  const double kmax = 9.5 / g.sigma_m;
  // eta = (1/2pi) int k (2 pi sigma^2 A e^{-k^2 sigma^2/2}) cos(omega t) J0(k r) dk
  auto f = [&](double k) {
    return k * std::exp(-0.5 * k * k * s2) * std::cos(omega(g.water, k) * t_s) * bessel_j0(k * r_m);
  };
  // start with about two panels per oscillation of the integrand
  const double phase = kmax * r_m + omega(g.water, kmax) * t_s;
  const int panels = std::clamp(static_cast<int>(phase / std::numbers::pi) + 16, 16, 20000);
  const double tol = g.rel_tolerance / s2;  // the integral is of order 1/sigma^2
  QuadratureResult q = integrate_gk15(f, 0.0, kmax, tol, panels);
  q.value *= s2 * g.amplitude_m;
  q.error *= s2 * std::abs(g.amplitude_m);
  return q;
}

double cauchy_poisson_eta(const CauchyPoissonGaussian& g, double r_m, double t_s) {
  return cauchy_poisson_quadrature(g, r_m, t_s).value;
}

double cauchy_poisson_center_gravity_series(double gravity, double sigma_m, double amplitude_m, double t_s) {
  const double q = std::sqrt(2.0) * gravity * t_s * t_s / sigma_m;
  double sum = 0;
  for (int n = 0; n < 400; ++n) {
    // term = (-1)^n Gamma(n/2 + 1) q^n / (2n)!, in logs to avoid overflow
    const double lg = std::lgamma(0.5 * n + 1.0) + (n ? n * std::log(q) : 0.0) - std::lgamma(2.0 * n + 1.0);
    const double term = std::exp(lg);
    sum += (n % 2 ? -term : term);
    if (n > 10 && term < 1e-18 * std::max(1.0, std::abs(sum))) break;
  }
  return amplitude_m * sum;
}

}  // namespace huygens
