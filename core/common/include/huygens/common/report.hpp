#pragma once
// Plain-text reports for the programs: tables whose columns line up, the same rows as
// CSV, and a progress bar on stderr (only when stderr is a terminal).
#include <cstdio>
#include <string>
#include <vector>

namespace huygens {

class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  /// Aligned text: numbers right-aligned, text left-aligned, a rule under the header.
  std::string text() const;
  /// RFC 4180 CSV with the header line.
  std::string csv() const;
  const std::vector<std::vector<std::string>>& rows() const { return rows_; }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// printf-style formatting into a std::string.
std::string fmt(const char* format, ...) __attribute__((format(printf, 1, 2)));
/// A number in a compact fixed or scientific form with `digits` significant digits.
std::string num(double x, int digits = 4);

/// A progress bar on stderr, drawn only when stderr is a terminal and the run is long.
class Progress {
 public:
  Progress(std::string label, long long total);
  ~Progress();
  void update(long long done);

 private:
  std::string label_;
  long long total_;
  bool tty_;
  double t0_;
  double last_draw_ = -1;
  bool drawn_ = false;
};

}  // namespace huygens
