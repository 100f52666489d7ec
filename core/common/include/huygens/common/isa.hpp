#pragma once
// The instruction set the library was compiled for and the one the CPU it runs on offers, for
// the headers of benchmark reports (a speed figure names both; docs/performance.md).
#include <string>

namespace huygens {

/// The HUYGENS_ISA build option and the vector extensions the compiler enabled for this
/// library, e.g. "x86-64-v3 (AVX2 FMA)" or "native (AVX-512F AVX2 FMA)".
std::string build_isa();

/// The CPU's model name (/proc/cpuinfo) and the vector extensions it offers, e.g.
/// "Intel(R) Xeon(R) Processor (AVX-512F AVX2 FMA)".
std::string cpu_isa();

}  // namespace huygens
