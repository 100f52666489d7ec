#pragma once
// Commands from the UI thread to the simulation thread (docs/design.md 2): a small POD variant
// that travels over an SpscQueue<Command> and is applied by the runner at a step boundary.
// Every alternative is trivially copyable (no strings, no heap), so pushing one is a plain
// copy of a few dozen bytes. Positions are in metres in the full grid's frame (origin at
// the corner of cell 0,0; x along columns), as in scene files (docs/design.md 6).
#include <cstdint>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

namespace huygens {

/// A short name carried by value (parameter or feature names), at most 31 characters.
struct CommandName {
  char text[32] = {};
  CommandName() = default;
  /// Throws std::invalid_argument for names longer than 31 characters (never truncates).
  CommandName(std::string_view s) {  // NOLINT(google-explicit-constructor): reads as a string
    if (s.size() >= sizeof(text))
      throw std::invalid_argument("command name longer than 31 characters: " + std::string(s));
    std::memcpy(text, s.data(), s.size());
  }
  CommandName(const char* s) : CommandName(std::string_view(s)) {}  // NOLINT(google-explicit-constructor)
  std::string_view view() const { return {text, std::strlen(text)}; }
  bool operator==(std::string_view s) const { return view() == s; }
};

namespace cmd {

/// Drop a stone: a sudden Gaussian elevation disturbance (docs/design.md 3.3) at (x, y).
struct Drop {
  /// Centre, x (unit: m).
  float x_m = 0;
  /// Centre, y (unit: m).
  float y_m = 0;
  /// Radius of the stone, the Gaussian's sigma (unit: m).
  float radius_m = 0.05f;
  /// Depth of the depression it makes (positive = down; unit: m).
  float depth_m = 0.01f;
};

/// Steer a ship: the position it should head for and its velocity there.
struct ShipTarget {
  /// Index of the ship in the scene's "ships" array.
  std::int32_t ship = 0;
  /// Target position, x (unit: m).
  float x_m = 0;
  /// Target position, y (unit: m).
  float y_m = 0;
  /// Target velocity, x (unit: m/s).
  float vx_mps = 0;
  /// Target velocity, y (unit: m/s).
  float vy_mps = 0;
};

/// Stop stepping (frames stay available; the display clock freezes).
struct Pause {};
/// Continue after Pause (the display clock resumes where it stopped).
struct Resume {};
/// Take exactly one step while paused.
struct StepOnce {};
/// Restart the scene from its initial state.
struct Reset {};

/// Set a named parameter. Runner parameters: "time_scale" (simulated s per wall s);
/// anything else goes to the solver (Solver::apply), which may refuse it.
struct SetParam {
  CommandName name;
  /// New value, in the parameter's own unit.
  double value = 0;
};

/// Switch a named feature on or off. Runner feature: "realtime" (pace to the wall clock);
/// anything else goes to the solver (e.g. "stokes", "wind"), which may refuse it.
struct Toggle {
  CommandName feature;
  bool on = true;
};

}  // namespace cmd

using Command = std::variant<cmd::Drop, cmd::ShipTarget, cmd::Pause, cmd::Resume, cmd::StepOnce, cmd::Reset,
                             cmd::SetParam, cmd::Toggle>;
static_assert(std::is_trivially_copyable_v<Command>, "commands must be plain data");

/// The alternative's name ("drop", "ship_target", "pause", ...), for messages.
inline const char* command_kind(const Command& c) {
  static constexpr const char* kNames[] = {"drop",      "ship_target", "pause",     "resume",
                                           "step_once", "reset",       "set_param", "toggle"};
  static_assert(std::size(kNames) == std::variant_size_v<Command>);
  return kNames[c.index()];
}

}  // namespace huygens
