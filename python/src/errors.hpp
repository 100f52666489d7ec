#pragma once
// The errors the package raises, as C++ exceptions that module.cpp translates into the Python
// classes of huygens/_errors.py (SceneError(ValueError), RunStopped(RuntimeError),
// MemoryRefused(MemoryError), CommandRefused(ValueError)), each carrying what the CLI prints.
// huygens::SceneError is translated as it is (its path()).
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "huygens/common/memory.hpp"

namespace huygens::python {

/// A run stopped by a non-finite value or a negative LBM depth: the stage (NonFiniteError's, or
/// "negative_depth") and the step, as `huygens run` prints them (exit code 3).
class RunStoppedError : public std::runtime_error {
 public:
  RunStoppedError(const std::string& message, std::string stage, std::int64_t step, double time_s)
      : std::runtime_error(message), stage(std::move(stage)), step(step), time_s(time_s) {}
  std::string stage;
  std::int64_t step;
  /// The simulated time of the last good state (unit: s).
  double time_s;
};

/// A scene refused before anything was allocated (exit code 4): the message of require_memory()
/// and its figures.
class MemoryRefusedError : public std::runtime_error {
 public:
  MemoryRefusedError(const std::string& message, MemoryEstimate need, std::uint64_t available)
      : std::runtime_error(message), need(std::move(need)), available_bytes(available) {}
  MemoryEstimate need;
  /// (unit: byte)
  std::uint64_t available_bytes;
};

/// A command the solver does not support or refused (Solver::apply returned false).
class CommandRefusedError : public std::runtime_error {
 public:
  CommandRefusedError(const std::string& message, std::string command)
      : std::runtime_error(message), command(std::move(command)) {}
  std::string command;
};

}  // namespace huygens::python
