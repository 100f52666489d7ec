#include "huygens/common/program.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

#include "huygens/common/finite.hpp"
#include "huygens/common/scene.hpp"

namespace huygens {

namespace {

std::string range_text(long long lo, long long hi) {
  return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

[[noreturn]] void bad_value(std::string_view flag, const char* text, const std::string& want) {
  throw UsageError(std::string(flag) + " needs " + want + ", got '" + (text ? text : "") + "'");
}

const char* g_program = "huygens";

[[noreturn]] void on_terminate() {
  std::string what = "an unknown failure";
  if (auto e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& x) {
      what = x.what();
    } catch (...) {
    }
  }
  std::fprintf(stderr, "%s: internal error: %s (please report)\n", g_program, what.c_str());
  std::_Exit(kExitFailed);
}

}  // namespace

long long parse_int_arg(std::string_view flag, const char* text, long long lo, long long hi) {
  const std::string want = "an integer in " + range_text(lo, hi);
  if (!text || !*text) bad_value(flag, text, want);
  char* end = nullptr;
  errno = 0;
  const long long x = std::strtoll(text, &end, 10);
  if (*end || errno == ERANGE || x < lo || x > hi) bad_value(flag, text, want);
  return x;
}

double parse_real_arg(std::string_view flag, const char* text, double lo, double hi) {
  char range[64];
  std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
  const std::string want = std::string("a number in ") + range;
  if (!text || !*text) bad_value(flag, text, want);
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text, &end);
  if (*end || errno == ERANGE || !std::isfinite(x) || x < lo || x > hi) bad_value(flag, text, want);
  return x;
}

std::string nonempty_arg(std::string_view flag, const char* text) {
  if (!text || !*text) bad_value(flag, text, "a non-empty name");
  return text;
}

// OpenMP waits: spin briefly, then sleep, unless the user chose (OMP_WAIT_POLICY or
// GOMP_SPINCOUNT). libgomp's own default spins ~300000 iterations at every barrier: on a loaded
// machine a thread spins away its time slice waiting for a partner the kernel descheduled, and
// 2 threads ran 10-40x slower than 1; purely passive waits pay a futex wake per region on a
// quiet machine (the LBM channel gained nothing from a second thread). 3000 iterations keep both
// (the "load" section of huygens-bench; docs/robustness.md). libgomp reads the variables once,
// when it is loaded, so the program sets the default and executes itself again (once: the
// variable is then set); if that fails it runs on with libgomp's default.
void default_omp_waits(char** argv) {
  if (!argv || getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
  setenv("GOMP_SPINCOUNT", "3000", 0);
  execv("/proc/self/exe", argv);
}

int run_program(const char* name, char** argv, const std::function<int()>& body) {
  default_omp_waits(argv);
  g_program = name;
  std::set_terminate(on_terminate);
  try {
    return body();
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s: %s (see %s --help)\n", name, e.what(), name);
    return kExitUsage;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s: scene error: %s\n", name, e.what());
    return kExitUsage;
  } catch (const RunStopped& e) {
    std::fprintf(stderr, "%s: run stopped: %s\n", name, e.what());
    return kExitNonFinite;
  } catch (const StopRequested& e) {
    std::fprintf(stderr, "%s: stopped by %s: %s\n", name, stop_request::signal_name(), e.what());
    return stop_request::exit_code();
  } catch (const ResourceError& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return kExitResources;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory (an allocation failed; the memory estimate missed it: please report)\n",
                 name);
    return kExitResources;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return kExitFailed;
  }
}

namespace stop_request {

namespace {
volatile std::sig_atomic_t g_signal = 0;

void on_signal(int sig) {
  if (g_signal != 0) {  // the second request: the default action, at once
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
  static const char msg[] = "\nstop requested: finishing the current item (signal again to stop at once)\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
}
}  // namespace

void install() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // an interrupted write() continues: no half-written file from a signal
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

int signal() { return g_signal; }

const char* signal_name() { return g_signal == SIGINT ? "SIGINT" : g_signal == SIGTERM ? "SIGTERM" : ""; }

int exit_code() { return 128 + g_signal; }

void throw_if_requested(const std::string& what) {
  if (g_signal != 0) throw StopRequested(what);
}

}  // namespace stop_request

}  // namespace huygens
