#pragma once
// The commands of the `huygens` program; each returns its exit code (program.hpp) and throws
// UsageError, SceneError, IoError or ResourceError for run_program() to report.

namespace huygens {

/// The usage text (huygens --help).
extern const char* const kUsage;
/// huygens run SCENE [options]: argv holds the words after "run".
int cmd_run(int argc, char** argv);
/// huygens validate [CASE...] [--list].
int cmd_validate(int argc, char** argv);

}  // namespace huygens
