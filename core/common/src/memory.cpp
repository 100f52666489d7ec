#include "huygens/common/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "huygens/common/program.hpp"

namespace huygens {

namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

// The first number in a file ("max" or a missing file: unlimited).
std::uint64_t read_number(const std::string& path) {
  std::ifstream f(path);
  std::string word;
  if (!(f >> word) || word == "max") return kUnlimited;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(word.c_str(), &end, 10);
  return *end ? kUnlimited : v;
}

std::uint64_t mem_available() {
  std::ifstream f("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (f >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return kUnlimited;
}

// The memory cgroup's room: limit - usage (v2 first, then v1), from /proc/self/cgroup's path.
std::uint64_t cgroup_room() {
  std::ifstream f("/proc/self/cgroup");
  std::string line;
  std::uint64_t room = kUnlimited;
  while (std::getline(f, line)) {
    const auto c1 = line.find(':'), c2 = line.find(':', c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) continue;
    const std::string controllers = line.substr(c1 + 1, c2 - c1 - 1), path = line.substr(c2 + 1);
    std::uint64_t limit = kUnlimited, usage = 0;
    if (controllers.empty()) {  // v2
      limit = read_number("/sys/fs/cgroup" + path + "/memory.max");
      usage = read_number("/sys/fs/cgroup" + path + "/memory.current");
    } else if (controllers.find("memory") != std::string::npos) {
      limit = read_number("/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes");
      if (limit == kUnlimited) limit = read_number("/sys/fs/cgroup/memory/memory.limit_in_bytes");
      usage = read_number("/sys/fs/cgroup/memory" + path + "/memory.usage_in_bytes");
    }
    if (limit != kUnlimited && usage != kUnlimited) room = std::min(room, limit > usage ? limit - usage : 0);
  }
  return room;
}

// The address-space limit (ulimit -v) less the address space already mapped.
std::uint64_t address_space_room() {
  rlimit lim{};
  if (getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return kUnlimited;
  std::ifstream f("/proc/self/statm");
  std::uint64_t pages = 0;
  f >> pages;
  const std::uint64_t used = pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
  return lim.rlim_cur > used ? lim.rlim_cur - used : 0;
}

}  // namespace

std::uint64_t MemoryEstimate::total() const {
  std::uint64_t t = 0;
  for (const Part& part : parts) t += part.bytes;
  return t;
}

std::string format_bytes(std::uint64_t bytes) {
  char buf[48];
  const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  if (mib < 1024.0)
    std::snprintf(buf, sizeof buf, "%.0f MiB", std::ceil(mib));
  else
    std::snprintf(buf, sizeof buf, "%.2f GiB", mib / 1024.0);
  return buf;
}

std::string MemoryEstimate::summary() const {
  std::ostringstream s;
  s << format_bytes(total()) << " (";
  bool first = true;
  for (const Part& part : parts) {
    if (part.bytes == 0) continue;
    s << (first ? "" : ", ") << part.name << " " << format_bytes(part.bytes);
    first = false;
  }
  s << ")";
  return s.str();
}

std::string MemoryEstimate::largest_part() const {
  const auto most =
      std::max_element(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.bytes < b.bytes; });
  if (most == parts.end()) return "";
  const std::string& key = most->key.empty() ? size_key : most->key;
  return "the largest part, " + most->name + " (" + format_bytes(most->bytes) + "), is set by " + key;
}

std::uint64_t available_memory() {
  std::uint64_t avail = std::min({mem_available(), cgroup_room(), address_space_room()});
  if (const char* cap = std::getenv("HUYGENS_MAX_MEMORY_GIB"); cap && *cap) {
    char* end = nullptr;
    const double gib = std::strtod(cap, &end);
    if (*end || !(gib >= 0) || !std::isfinite(gib))
      throw UsageError(std::string("HUYGENS_MAX_MEMORY_GIB must be a number of GiB >= 0, got '") + cap + "'");
    avail = std::min(avail, static_cast<std::uint64_t>(gib * 1024.0 * 1024.0 * 1024.0));
  }
  return avail;
}

namespace {
std::atomic<int> g_check_off{0};
}  // namespace

MemoryCheckOff::MemoryCheckOff() { ++g_check_off; }
MemoryCheckOff::~MemoryCheckOff() { --g_check_off; }

void require_memory(const MemoryEstimate& need) {
  if (g_check_off > 0) return;
  const std::uint64_t avail = available_memory();
  if (need.total() <= avail) return;
  throw ResourceError("the scene needs " + need.summary() + ", " + format_bytes(avail) + " available; " +
                      need.largest_part());
}

}  // namespace huygens
