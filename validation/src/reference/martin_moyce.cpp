#include "huygens/validation/reference/martin_moyce.hpp"

#include <algorithm>
#include <stdexcept>

#include "validation_data.hpp"

namespace huygens {

namespace {

// The next comma-separated field of `line` from `pos` (pos moves past the comma).
std::string field(std::string_view line, std::size_t& pos) {
  const std::size_t end = std::min(line.find(',', pos), line.size());
  std::string out(line.substr(pos, end - pos));
  pos = end < line.size() ? end + 1 : end;
  return out;
}

}  // namespace

std::vector<MartinMoycePoint> parse_martin_moyce(std::string_view csv) {
  std::vector<MartinMoycePoint> pts;
  std::size_t start = 0;
  while (start < csv.size()) {
    const std::size_t eol = std::min(csv.find('\n', start), csv.size());
    const std::string_view line = csv.substr(start, eol - start);
    start = eol + 1;
    if (line.empty() || line[0] == '#' || line.starts_with("a_in")) continue;
    std::size_t pos = 0;
    MartinMoycePoint p;
    p.series = field(line, pos);
    p.T = std::stod(field(line, pos));
    p.Z = std::stod(field(line, pos));
    pts.push_back(std::move(p));
  }
  return pts;
}

std::vector<MartinMoycePoint> martin_moyce_1952() {
  const std::string_view text = embedded::validation_data("martin_moyce_1952.csv");
  if (text.empty()) throw std::logic_error("martin_moyce_1952.csv is not embedded in the validation library");
  return parse_martin_moyce(text);
}

}  // namespace huygens
