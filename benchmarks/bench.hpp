#pragma once
// Shared pieces of huygens-bench: the section registry, the context a section reports
// into, and timing helpers. Speed claims are ratios measured in the same run (docs/design.md 7).
#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "huygens/common/report.hpp"
#include "huygens/common/stats.hpp"  // median_seconds

namespace huygens::bench {

struct Context {
  /// CI-sized run (the whole --quick run stays under 3 minutes).
  bool quick = false;
  /// Parts of a section to run (e.g. "sph" from the argument "stress:sph"); empty = all.
  std::vector<std::string> parts;
  bool part(const std::string& name) const {
    return parts.empty() || std::find(parts.begin(), parts.end(), name) != parts.end();
  }
  /// True when the command line named this part (an opt-in part runs only then, not in `all`).
  bool named(const std::string& name) const { return std::find(parts.begin(), parts.end(), name) != parts.end(); }
  /// Folder of the files a part writes besides the tables (the --csv file's folder, else the working directory).
  std::string output_dir = ".";
  /// Thread counts to sweep (1 and the machine's count).
  std::vector<int> threads;
  /// Accuracy checks that failed (a --quick run exits non-zero when any did).
  int failures = 0;
  /// Prints a titled table and keeps its rows for --csv.
  void report(const std::string& section, const std::string& title, const Table& table);
  /// Records an accuracy check; a failure is printed and counted.
  void expect(bool ok, const std::string& what);

  std::vector<std::pair<std::string, Table>> tables;
};

using Section = std::function<void(Context&)>;

/// Pareto-optimal rows of a (time, error) set: true where no other row is at least as fast and
/// at least as accurate, and better in one of the two. Non-finite values are never optimal.
std::vector<bool> pareto_front(const std::vector<double>& time, const std::vector<double>& error);

/// A shipped scene's text by its file name ("default.json"), compiled into huygens-bench
/// (benchmarks/CMakeLists.txt, huygens_embed): the bench reads nothing from the source tree.
/// Throws std::runtime_error for a scene that was not embedded.
std::string shipped_scene(const std::string& name);

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Sections, one per file (bench_<name>.cpp).
void bench_huygens(Context&);
void bench_pipeline(Context&);
void bench_ships(Context&);
void bench_lbm(Context&);
void bench_sph(Context&);
void bench_accuracy(Context&);
void bench_skip(Context&);
void bench_stress(Context&);
void bench_interp(Context&);
void bench_render(Context&);
void bench_load(Context&);
void bench_mpi(Context&);
void bench_solvers(Context&);
// the solver parts of "stress" (called by bench_stress; `stress:huygens` etc. runs one)
void stress_huygens(Context&);
void stress_sph(Context&);
void stress_lbm(Context&);
// the parts "peers" and "peers46" of "sph" (bench_sph_peers.cpp): the 3D dam break at `nas` particles across
void sph_peers(Context&, const std::vector<int>& nas);

}  // namespace huygens::bench
