// huygens.reference: the analytic solutions and measured data the validation cases compare against
// (validation/include/huygens/validation/reference/), for examples and users' own checks.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>

#include "huygens/validation/reference/cauchy_poisson.hpp"
#include "huygens/validation/reference/kelvin.hpp"
#include "huygens/validation/reference/martin_moyce.hpp"

namespace huygens::python {

namespace py = pybind11;

namespace {

Water water(double g, double sigma, double rho, std::optional<double> depth) {
  Water w;
  w.gravity_mps2 = g;
  w.surface_tension_npm = sigma;
  w.density_kgpm3 = rho;
  w.depth_m = depth ? *depth : std::numeric_limits<double>::infinity();
  return w;
}

py::array_t<double> cauchy_poisson(const py::array_t<double, py::array::c_style | py::array::forcecast>& r, double t,
                                   double sigma, double amp, double g, double st, double rho,
                                   std::optional<double> depth) {
  CauchyPoissonGaussian cp;
  cp.water = water(g, st, rho, depth);
  cp.sigma_m = sigma;
  cp.amplitude_m = amp;
  py::array_t<double> out(std::vector<py::ssize_t>(r.shape(), r.shape() + r.ndim()));
  const double* in = r.data();
  double* o = out.mutable_data();
  const py::ssize_t n = r.size();
  {
    py::gil_scoped_release release;
#pragma omp parallel for schedule(dynamic, 4)
    for (py::ssize_t i = 0; i < n; ++i) o[i] = cauchy_poisson_eta(cp, in[i], t);
  }
  return out;
}

py::dict measure_wake(const py::array_t<float, py::array::c_style | py::array::forcecast>& eta, double dx_m,
                      double x0_m, double y0_m, const py::dict& ship, double s_min_m, double s_max_m, double g) {
  if (eta.ndim() != 2) throw py::value_error("measure_kelvin_wake: eta must be 2-D (rows = y, cols = x)");
  WakeGrid grid{static_cast<int>(eta.shape(0)), static_cast<int>(eta.shape(1)), dx_m, x0_m, y0_m};
  WakeTrack track{ship["x_m"].cast<double>(), ship["y_m"].cast<double>(), ship["heading_rad"].cast<double>(),
                  ship["speed_mps"].cast<double>()};
  WakeOptions opt;
  opt.s_min_m = s_min_m;
  opt.s_max_m = s_max_m;
  opt.gravity_mps2 = g;
  WakeMeasurement w;
  {
    py::gil_scoped_release release;
    w = measure_kelvin_wake(eta.data(), grid, track, opt);
  }
  return py::dict(py::arg("envelope_angle_deg") = w.envelope_angle_deg,
                  py::arg("max_amplitude_angle_deg") = w.max_amplitude_angle_deg,
                  py::arg("transverse_wavelength_m") = w.transverse_wavelength_m, py::arg("profiles") = w.profiles,
                  py::arg("s_min_m") = w.s_min_m, py::arg("s_max_m") = w.s_max_m);
}

py::list martin_moyce() {
  py::list out;
  for (const MartinMoycePoint& p : martin_moyce_1952())
    out.append(py::dict(py::arg("series") = p.series, py::arg("T") = p.T, py::arg("Z") = p.Z));
  return out;
}

}  // namespace

void bind_reference(py::module_& m) {
  m.def("cauchy_poisson_eta", &cauchy_poisson, py::arg("r_m"), py::arg("t_s"), py::kw_only(), py::arg("sigma_m") = 0.1,
        py::arg("amplitude_m") = 0.01, py::arg("gravity_mps2") = 9.81, py::arg("surface_tension_npm") = 0.072,
        py::arg("density_kgpm3") = 1000.0, py::arg("depth_m") = py::none(),
        R"(The exact linear ring wave of a Gaussian hump released from rest (Cauchy-Poisson), eta(r, t) in m.

eta(r, t) = (1 / 2 pi) int_0^inf k eta0^(k) cos(omega(k) t) J0(k r) dk with
eta0^(k) = 2 pi sigma^2 A exp(-k^2 sigma^2 / 2) and the gravity-capillary
omega(k) (depth_m None: deep water), by adaptive Gauss-Kronrod quadrature to
1e-10 A: the reference of `huygens validate cauchy_poisson`. r_m: distances
(an array or a number, m); returns an array of r_m's shape.)");
  m.def(
      "kelvin_cusp_angle_deg",
      [](double u, double g, double st, double rho, std::optional<double> depth) {
        return kelvin_cusp_angle(water(g, st, rho, depth), u);
      },
      py::arg("speed_mps"), py::kw_only(), py::arg("gravity_mps2") = 9.81, py::arg("surface_tension_npm") = 0.072,
      py::arg("density_kgpm3") = 1000.0, py::arg("depth_m") = py::none(),
      "The half-angle of a Kelvin wake's cusp line behind a source at speed_mps (deg): arcsin(1/3) = 19.47 deg in "
      "deep gravity water at any speed; finite depth widens it.");
  m.def(
      "kelvin_transverse_wavelength_m",
      [](double u, double g, double st, double rho, std::optional<double> depth) {
        return kelvin_transverse_wavelength(water(g, st, rho, depth), u);
      },
      py::arg("speed_mps"), py::kw_only(), py::arg("gravity_mps2") = 9.81, py::arg("surface_tension_npm") = 0.072,
      py::arg("density_kgpm3") = 1000.0, py::arg("depth_m") = py::none(),
      "The wavelength of a Kelvin wake's transverse waves, 2 pi / k with omega(k) = k U (2 pi U^2 / g in deep "
      "gravity water) (m).");
  m.def("measure_kelvin_wake", &measure_wake, py::arg("eta"), py::arg("dx_m"), py::arg("x0_m"), py::arg("y0_m"),
        py::arg("ship"), py::kw_only(), py::arg("s_min_m") = -1.0, py::arg("s_max_m") = -1.0,
        py::arg("gravity_mps2") = 9.81,
        R"(Measures a Kelvin wake in a heightfield as `huygens validate kelvin` does (validation/.../kelvin.hpp).

eta: rows x cols (y, x), cell (r, c) at (x0_m + c dx_m, y0_m + r dx_m); ship: a
dict with x_m, y_m, heading_rad, speed_mps (Simulation.ship_poses()[i]).
s_min_m / s_max_m: the distances behind the hull measured (< 0: 3 transverse
wavelengths / as far as the wedge stays on the grid; for a ship started a
distance D ago use at most D / 2). Returns envelope_angle_deg (the outer
caustic's half-angle), max_amplitude_angle_deg, transverse_wavelength_m,
profiles, s_min_m, s_max_m; NaN where too few profiles were usable.)");
  m.def("martin_moyce_1952", &martin_moyce,
        "The measured dam-break surge fronts of Martin & Moyce (1952), Figure 3 (a column a wide, 2a high): dicts "
        "with series (the column width a in inches, '1.125' or '2.25'), T = t sqrt(2 g / a) and Z = front / a.");
}

}  // namespace huygens::python
