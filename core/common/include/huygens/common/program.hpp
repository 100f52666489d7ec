#pragma once
// What every Huygens program shares at its edges: the documented exit codes, strict parsing of
// command-line values, one top-level handler that turns any failure into a message and a code,
// and the stop request SIGINT/SIGTERM raise (docs/robustness.md).
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace huygens {

/// Exit codes of huygens, huygens-viz, huygens-bench and huygens-caustics-bench (README).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,     ///< a validation case or accuracy check failed, or a file could not be written
  kExitUsage = 2,      ///< bad command line or scene (the JSON path is named)
  kExitNonFinite = 3,  ///< the run stopped on a non-finite value (or a negative LBM depth)
  kExitResources = 4,  ///< the scene needs more memory than the machine has (refused before the run)
  kExitSigint = 130,   ///< stopped by SIGINT (128 + 2) after a clean stop
  kExitSigterm = 143,  ///< stopped by SIGTERM (128 + 15) after a clean stop
};

/// A bad command line (exit 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The machine cannot hold what was asked (exit 4); what() says what is needed and what is there.
class ResourceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An integer value of option `flag` in [lo, hi]; anything else (empty, trailing characters,
/// out of range, overflow) throws UsageError naming the flag, the text and the range.
long long parse_int_arg(std::string_view flag, const char* text, long long lo, long long hi);
/// A finite real value of option `flag` in [lo, hi] (NaN, Inf refused) or UsageError.
double parse_real_arg(std::string_view flag, const char* text, double lo, double hi);
/// A non-empty value of option `flag` (a file or folder name) or UsageError.
std::string nonempty_arg(std::string_view flag, const char* text);

/// A stop that SIGINT or SIGTERM asked for, thrown at a program's check point between two items
/// (a frame, a table, a case); what() says what was abandoned and what was kept.
class StopRequested : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Runs a program's body and returns its exit code. Every exception becomes a line
/// "NAME: ..." on stderr and its code: UsageError and SceneError 2, NonFiniteError 3,
/// ResourceError and std::bad_alloc 4, StopRequested 130 or 143 ("NAME: stopped by SIGINT: ..."),
/// anything else 1. Also installs a std::terminate handler
/// that prints the same kind of line (an exception that escapes a thread) and exits 1. First,
/// when neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT is set, sets GOMP_SPINCOUNT=3000 and executes
/// the program again with `argv` (libgomp reads it only at start; program.cpp says why).
int run_program(const char* name, char** argv, const std::function<int()>& body);

/// SIGINT/SIGTERM as a request to stop between steps (huygens run) or items (the viewer's frames,
/// the benches' tables): the first signal sets the request (and says so on stderr), a second one
/// ends the process at once by the signal's default action.
/// Also ignores SIGXFSZ, so a write past the file-size limit fails with a message (EFBIG).
namespace stop_request {
void install();
/// The signal that asked to stop (SIGINT or SIGTERM), 0 when none did.
int signal();
/// "SIGINT", "SIGTERM" or "" for signal().
const char* signal_name();
/// The exit code for a run that stopped on signal(): 130 or 143.
int exit_code();
/// Throws StopRequested(what) when a signal asked to stop: a program's check point.
void throw_if_requested(const std::string& what);
}  // namespace stop_request

}  // namespace huygens
