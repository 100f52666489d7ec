// Every Huygens validation case of `huygens validate` passes (issue 2's list). These are the
// full cases, not reduced ones: together they take a few seconds of CPU.
#include <gtest/gtest.h>
#include <omp.h>

#include "huygens/fft.hpp"
#include "huygens/validation.hpp"

using namespace huygens;

namespace {
void expect_case_passes(const std::string& name) {
  // one thread: ctest runs tests side by side on 2 cores, and OpenMP/FFTW threads that spin
  // at barriers on an oversubscribed machine cost 10x the wall time (the results do not
  // depend on the thread count)
  omp_set_num_threads(1);
  fft_set_threads(1);
  bool found = false;
  for (const auto& c : huygens_validation_cases()) {
    if (c.name != name) continue;
    found = true;
    for (const auto& r : c.run())
      EXPECT_TRUE(r.pass) << r.case_name << ": " << r.quantity << " = " << r.measured << " (expected " << r.expected
                          << "), error " << r.error << " > tolerance " << r.tolerance;
  }
  EXPECT_TRUE(found) << name;
}
}  // namespace

TEST(HuygensValidation, FftRoundTripAndParseval) { expect_case_passes("fft"); }
TEST(HuygensValidation, PhaseSpeed) { expect_case_passes("phase_speed"); }
TEST(HuygensValidation, CauchyPoissonRing) { expect_case_passes("cauchy_poisson"); }
TEST(HuygensValidation, GroupVelocity) { expect_case_passes("group_velocity"); }
TEST(HuygensValidation, EnergyConservation) { expect_case_passes("energy"); }
TEST(HuygensValidation, AbsorptionByTheMargin) { expect_case_passes("absorption"); }
TEST(HuygensValidation, AbsorptionTimedCutoff) { expect_case_passes("absorption_tau"); }
