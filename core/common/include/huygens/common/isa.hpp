#pragma once
// The instruction set the library was compiled for and the one the CPU it runs on offers, and the
// machine line the timing reports start with (a speed figure names the CPU, its vector
// extensions, the build's instruction set, the threads and the load; docs/performance.md).
#include <string>

namespace huygens {

/// The HUYGENS_ISA build option and the vector extensions the compiler enabled for this
/// library, e.g. "x86-64-v3 (AVX2 FMA)" or "native (AVX-512F AVX2 FMA)".
std::string build_isa();

/// The CPU's model name (/proc/cpuinfo) and the vector extensions it offers, e.g.
/// "Intel(R) Xeon(R) Processor (AVX-512F AVX2 FMA)".
std::string cpu_isa();

/// The 1-minute load average of the machine (getloadavg), -1 when it cannot be read.
double load_average();

/// The first line of a timing report: "machine: " the CPU and its vector extensions, its cores,
/// the build's instruction set, the compiler, FFTW, `threads` (the OpenMP threads the run uses)
/// and the 1-minute load average now (getloadavg), e.g. "machine: AMD EPYC 7763 (AVX2 FMA), 2 cores, built
/// for x86-64-v3 (AVX2 FMA), g++ 12.2.0, fftw-3.3.10-sse2-avx, OpenMP threads 2, load average 1.52".
std::string machine_line(int threads);

}  // namespace huygens
