// Build and CPU instruction sets: see huygens/common/isa.hpp.
#include "huygens/common/isa.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "huygens/common/fft.hpp"

#ifndef HUYGENS_ISA_NAME
#define HUYGENS_ISA_NAME "unknown"
#endif

namespace huygens {

namespace {

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace

std::string build_isa() {
  std::string s;
#if defined(__AVX512F__)
  s += " AVX-512F";
#endif
#if defined(__AVX2__)
  s += " AVX2";
#endif
#if defined(__FMA__)
  s += " FMA";
#endif
#if !defined(__AVX2__) && defined(__AVX__)
  s += " AVX";
#endif
#if !defined(__AVX__) && defined(__SSE4_2__)
  s += " SSE4.2";
#endif
#if !defined(__AVX__) && !defined(__SSE4_2__) && defined(__SSE2__)
  s += " SSE2";
#endif
  return std::string(HUYGENS_ISA_NAME) + " (" + (s.empty() ? std::string("scalar") : s.substr(1)) + ")";
}

std::string cpu_isa() {
  std::string s;
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) s += " AVX-512F";
  if (__builtin_cpu_supports("avx2")) s += " AVX2";
  if (__builtin_cpu_supports("fma")) s += " FMA";
  if (s.empty() && __builtin_cpu_supports("sse4.2")) s += " SSE4.2";
#endif
  return cpu_model() + (s.empty() ? std::string() : " (" + s.substr(1) + ")");
}

double load_average() {
  double load[1];
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

std::string machine_line(int threads) {
#if defined(__clang__)
  const std::string compiler = std::string("clang ") + __clang_version__;
#else
  const std::string compiler = std::string("g++ ") + __VERSION__;
#endif
  const double load = load_average();
  char load_text[32] = "unknown";
  if (load >= 0) std::snprintf(load_text, sizeof load_text, "%.2f", load);
  return "machine: " + cpu_isa() + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores, built for " +
         build_isa() + ", " + compiler + ", " + fft_version() + ", OpenMP threads " + std::to_string(threads) +
         ", load average " + load_text;
}

}  // namespace huygens
