#pragma once
// Measured dam-break surge fronts of Martin & Moyce (1952), Figure 3 (data/martin_moyce_1952.csv,
// compiled into the library; citation in data/README.md): a water column a wide and 2a high
// collapsing on a dry floor, front position Z = z / a against T = t sqrt(2 g / a).
#include <string>
#include <string_view>
#include <vector>

namespace huygens {

/// One measured front position.
struct MartinMoycePoint {
  /// The series: the experiment's column width a in inches, as printed ("1.125" or "2.25").
  std::string series;
  /// Dimensionless time t sqrt(2 g / a) (unit: 1).
  double T = 0;
  /// Front distance from the back wall over a (unit: 1).
  double Z = 0;
};

/// Parses the table's CSV text: empty lines, '#' comment lines and the header line (a_in,T,Z)
/// are skipped; every other line is `series,T,Z`. Throws std::invalid_argument on a bad number.
std::vector<MartinMoycePoint> parse_martin_moyce(std::string_view csv);

/// The embedded table, both series in file order.
std::vector<MartinMoycePoint> martin_moyce_1952();

}  // namespace huygens
