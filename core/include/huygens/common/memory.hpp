#pragma once
// Memory checked before it is taken: each solver adds up the bytes its scene will allocate
// (grids, tables, patches, particles) from the parsed sizes, before allocating any of them,
// and a scene that needs more than the machine has left is refused (docs/robustness.md).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace huygens {

/// The bytes a scene's solver will allocate, by part.
struct MemoryEstimate {
  /// JSON path of the key that sets the size (named in a refusal), e.g. "$.grid.n".
  std::string size_key;
  /// (part, bytes) in allocation order (unit: byte).
  std::vector<std::pair<std::string, std::uint64_t>> parts;

  void add(std::string part, std::uint64_t bytes) { parts.emplace_back(std::move(part), bytes); }
  std::uint64_t total() const;
  /// "1.25 GiB (propagator 0.75 GiB, stokes 0.5 GiB)".
  std::string summary() const;
};

/// Bytes this process can still take: /proc/meminfo's MemAvailable, capped by the cgroup's
/// limit less its usage (v2 memory.max, or v1 memory.limit_in_bytes), by the address-space limit
/// (ulimit -v) less the mapped address space, and by the environment variable
/// HUYGENS_MAX_MEMORY_GIB when set (a cap a user chooses on a shared machine).
std::uint64_t available_memory();

/// Throws ResourceError ("needs X GiB, Y GiB available; KEY sets the size") when the estimate
/// is larger than available_memory().
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
