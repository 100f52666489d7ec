#pragma once
// Cheaper variants of the Huygens validation cases for the test suite (the full cases are
// huygens_validation_cases() in validation.hpp): the Kelvin wake of paper 004 eq. 2, the
// capillary threshold and the Froude trend, at a smaller grid than `huygens validate` runs.
#include <vector>

#include "huygens/validation/validation.hpp"

namespace huygens {

/// The `kelvin` rows at Froude 0.4 on n x n cells of dx = min(2 pi U^2/g, hull length) / cells
/// (`huygens validate kelvin` runs Fr 0.3, 0.4, 0.5 at n = 512, 10 cells).
std::vector<ValidationRow> kelvin_validation_rows(int n, double cells);

/// The `capillary` row on an n x n grid of 1 mm cells (the validation uses n = 512).
std::vector<ValidationRow> capillary_validation_rows(int n);

/// The `froude_trend` rows for Fr 1, 2, 3 (the validation uses n = 512 and adds Fr 0.3 and 0.5):
/// the max-amplitude angle on n x n cells of 0.1 m; the outer envelope on the same run when it
/// holds >= 8 transverse wavelengths, else on n x n cells of 8.15 lambda / n (Fr >= 1: on the
/// field low-passed at 3 g/U^2).
std::vector<ValidationRow> froude_validation_rows(int n);

}  // namespace huygens
