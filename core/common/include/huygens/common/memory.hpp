#pragma once
// Memory checked before it is taken: each solver adds up the bytes its scene will allocate
// (grids, tables, patches, particles) from the parsed sizes, before allocating any of them,
// and a scene that needs more than the machine has left is refused (docs/robustness.md).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace huygens {

/// The bytes a scene's solver will allocate, by part, each with the scene key that sets its size.
struct MemoryEstimate {
  struct Part {
    std::string name;
    /// (unit: byte)
    std::uint64_t bytes = 0;
    /// JSON path of the key that sets this part's size, e.g. "$.ships"; "" = size_key.
    std::string key;
  };
  /// JSON path of the key that sets the size of the parts added without a key of their own, e.g.
  /// "$.grid.n".
  std::string size_key;
  /// The parts in allocation order.
  std::vector<Part> parts;

  void add(std::string part, std::uint64_t bytes, std::string key = "") {
    parts.push_back({std::move(part), bytes, std::move(key)});
  }
  std::uint64_t total() const;
  /// "1.25 GiB (propagator 0.75 GiB, stokes 0.5 GiB)".
  std::string summary() const;
  /// What a refusal names: the largest part, its size and the key that sets it, e.g. "the largest
  /// part, ship patches (13.7 GiB), is set by $.ships". "" for an empty estimate.
  std::string largest_part() const;
};

/// Bytes this process can still take: /proc/meminfo's MemAvailable, capped by the cgroup's
/// limit less its usage (v2 memory.max, or v1 memory.limit_in_bytes), by the address-space limit
/// (ulimit -v) less the mapped address space, and by the environment variable
/// HUYGENS_MAX_MEMORY_GIB when set (a cap a user chooses on a shared machine).
std::uint64_t available_memory();

/// Throws ResourceError ("needs X GiB (parts), Y GiB available; the largest part, P (Z GiB), is set
/// by KEY") when the estimate is larger than available_memory().
void require_memory(const MemoryEstimate& need);

/// While one lives (on any thread), require_memory() refuses nothing: `huygens run --dry-run`
/// parses a scene only to size it for other machines and allocates none of its grids.
class MemoryCheckOff {
 public:
  MemoryCheckOff();
  ~MemoryCheckOff();
  MemoryCheckOff(const MemoryCheckOff&) = delete;
  MemoryCheckOff& operator=(const MemoryCheckOff&) = delete;
};

/// Bytes as "123 MiB" or "1.25 GiB".
std::string format_bytes(std::uint64_t bytes);

}  // namespace huygens
