#pragma once
// The commands of the `huygens` program; each returns its exit code (program.hpp) and throws
// UsageError, SceneError, IoError or ResourceError for run_program() to report.

#include <string>

namespace huygens {

/// Prints the usage text (huygens --help) to stdout, with the shipped scenes' names.
void print_usage();
/// huygens run SCENE [options]: argv holds the words after "run".
int cmd_run(int argc, char** argv);
/// huygens run SCENE --dry-run [--ranks P] [--rank-memory GIB]: the memory per rank (dry_run.cpp).
int cmd_dry_run(const std::string& scene_file, int ranks, double rank_gib);
/// huygens validate [CASE...] [--list].
int cmd_validate(int argc, char** argv);

}  // namespace huygens
