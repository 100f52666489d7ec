#include "huygens/common/report.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdlib>

namespace huygens {

namespace {
// a number, or "-" (a number that is absent), is right-aligned
bool looks_numeric(const std::string& s) {
  if (s.empty()) return false;
  if (s == "-") return true;
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

std::string Table::text() const {
  std::vector<std::size_t> w(header_.size(), 0);
  for (std::size_t c = 0; c < header_.size(); ++c) w[c] = header_[c].size();
  for (const auto& r : rows_)
    for (std::size_t c = 0; c < r.size() && c < w.size(); ++c) w[c] = std::max(w[c], r[c].size());
  auto line = [&](const std::vector<std::string>& r, bool head) {
    std::string out;
    for (std::size_t c = 0; c < w.size(); ++c) {
      const std::string cell = c < r.size() ? r[c] : "";
      const std::string pad(w[c] - cell.size(), ' ');
      const bool right = !head && looks_numeric(cell);
      out += (c ? "  " : "") + (right ? pad + cell : cell + (c + 1 < w.size() ? pad : ""));
    }
    return out + "\n";
  };
  std::string out = line(header_, true);
  std::size_t total = 0;
  for (auto x : w) total += x;
  out += std::string(total + 2 * (w.size() - 1), '-') + "\n";
  for (const auto& r : rows_) out += line(r, false);
  return out;
}

std::string Table::csv() const {
  auto quote = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  };
  auto line = [&](const std::vector<std::string>& r) {
    std::string out;
    for (std::size_t c = 0; c < r.size(); ++c) out += (c ? "," : "") + quote(r[c]);
    return out + "\n";
  };
  std::string out = line(header_);
  for (const auto& r : rows_) out += line(r);
  return out;
}

std::string fmt(const char* format, ...) {
  va_list a;
  va_start(a, format);
  char buf[512];
  std::vsnprintf(buf, sizeof buf, format, a);
  va_end(a);
  return buf;
}

std::string num(double x, int digits) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  const double ax = std::fabs(x);
  if (ax != 0 && (ax < 1e-3 || ax >= 1e6)) return fmt("%.*e", digits - 1, x);
  return fmt("%.*g", digits, x);
}

Progress::Progress(std::string label, long long total)
    : label_(std::move(label)), total_(total), tty_(isatty(2) != 0), t0_(now_s()) {}

Progress::~Progress() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void Progress::update(long long done) {
  if (!tty_) return;
  const double t = now_s();
  // Draw only after the first second and at most 10 times a second.
  if (t - t0_ < 1.0 || (last_draw_ >= 0 && t - last_draw_ < 0.1)) return;
  last_draw_ = t;
  drawn_ = true;
  const double f = total_ > 0 ? std::min(1.0, static_cast<double>(done) / total_) : 0.0;
  const int width = 30;
  const int fill = static_cast<int>(f * width);
  const double eta = f > 0 ? (t - t0_) * (1 - f) / f : 0;
  std::fprintf(stderr, "\r%s [%s%s] %3.0f%% %lld/%lld  %.0fs left\033[K", label_.c_str(),
               std::string(fill, '#').c_str(), std::string(width - fill, '.').c_str(), 100 * f, done, total_, eta);
  std::fflush(stderr);
}

}  // namespace huygens
