// The all-wet fused pull stream-collide pass (paper 002 eq. 1-4 with the well-balanced or the naive
// bed term), vectorised for the build's ISA, with an AVX-512 copy chosen at run time in an AVX2
// build.
#include <cstddef>

#include "huygens/lbm/shallow.hpp"
#include "lattice_cell.hpp"

// A second copy of the all-wet kernel with AVX-512 (span_kernel_wide): GCC, in an AVX2 + FMA build
// without AVX-512 (x86-64-v3), so both copies contract the same products into FMAs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__AVX2__) && defined(__FMA__) && \
    !defined(__AVX512F__)
#define HUYGENS_LBM_WIDE_CLONE 1
#else
#define HUYGENS_LBM_WIDE_CLONE 0
#endif

namespace huygens {

using namespace lbm_cell;

namespace {

// Pointers and constants of the fused pass (stream_collide).
struct KernelArgs {
  const float* src;     // populations of this step (9 planes)
  float* dst;           // post-collision populations (9 planes)
  const float* hold;    // depth of this step
  float* hnew;          // new depth
  const float* z;       // bed
  std::ptrdiff_t S, P;  // row stride and plane size (floats)
  Collision k;
  float k1, k5;  // centred bed term constants g/6, g/24
};

// One fluid row span [b, e) of the fused pull stream-collide pass (pull, bed term, collide, store).
// Mode 0: flat bed; 1: well-balanced centred bed term; 2: naive bed term. Force: a nonzero
// external acceleration (without it the force terms are left out of the collision). Returns the
// number of cells below h_min (also NaN).
template <int Mode, bool Force>
[[gnu::always_inline]] inline float span_body(const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  const std::ptrdiff_t S = a.S, P = a.P;
  const float* __restrict hold = a.hold;
  float* __restrict hnew = a.hnew;
  const float* __restrict z = a.z;
  // f_a(x) pulls f*_a(x - e_a): pa[c] = plane a at c - (ey S + ex).
  const float* __restrict p0 = a.src;
  const float* __restrict p1 = a.src + 1 * P - 1;
  const float* __restrict p2 = a.src + 2 * P - S;
  const float* __restrict p3 = a.src + 3 * P + 1;
  const float* __restrict p4 = a.src + 4 * P + S;
  const float* __restrict p5 = a.src + 5 * P - S - 1;
  const float* __restrict p6 = a.src + 6 * P - S + 1;
  const float* __restrict p7 = a.src + 7 * P + S + 1;
  const float* __restrict p8 = a.src + 8 * P + S - 1;
  float* __restrict d0 = a.dst;
  float* __restrict d1 = a.dst + 1 * P;
  float* __restrict d2 = a.dst + 2 * P;
  float* __restrict d3 = a.dst + 3 * P;
  float* __restrict d4 = a.dst + 4 * P;
  float* __restrict d5 = a.dst + 5 * P;
  float* __restrict d6 = a.dst + 6 * P;
  float* __restrict d7 = a.dst + 7 * P;
  float* __restrict d8 = a.dst + 8 * P;
  float bad = 0.0f;
#pragma omp simd reduction(+ : bad)
  for (std::ptrdiff_t c = b; c < e; ++c) {
    Cell9 f{p0[c], p1[c], p2[c], p3[c], p4[c], p5[c], p6[c], p7[c], p8[c]};
    if constexpr (Mode == 1) add_centred_bed(f, hold, z, c, S, a.k1, a.k5);
    if constexpr (Mode == 2) add_naive_bed(f, hold, z, c, S, a.k.g);
    float h;
    const Cell9 o = collide<false, Force>(f, a.k, h, bad);
    d0[c] = o.f0;
    d1[c] = o.f1;
    d2[c] = o.f2;
    d3[c] = o.f3;
    d4[c] = o.f4;
    d5[c] = o.f5;
    d6[c] = o.f6;
    d7[c] = o.f7;
    d8[c] = o.f8;
    hnew[c] = h;
  }
  return bad;
}

// The span loop compiled for the build's instruction set ...
template <int Mode, bool Force>
float span_kernel(const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  return span_body<Mode, Force>(a, b, e);
}

#if HUYGENS_LBM_WIDE_CLONE
// ... and once more for x86-64-v4 (AVX-512: 16 floats a vector, 32 vector registers) when the build
// is below it: the same operations lane by lane (the results are bitwise the same), half the
// vector instructions and no register spills, which the bed kernel needs to keep up with the
// memory (docs/lbm.md, "Speed"). Chosen at run time by lbm_kernel_isa().
template <int Mode, bool Force>
[[gnu::target("avx512f,avx512bw,avx512dq,avx512vl,avx512cd,prefer-vector-width=512")]] float span_kernel_wide(
    const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  return span_body<Mode, Force>(a, b, e);
}
#endif

bool wide_kernel_allowed = true;  // lbm_allow_wide_kernel

bool cpu_has_wide_kernel() {
#if HUYGENS_LBM_WIDE_CLONE
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
#else
  return false;
#endif
}

bool use_wide_kernel() {
  static const bool has = cpu_has_wide_kernel();
  return has && wide_kernel_allowed;
}

}  // namespace

const char* lbm_kernel_isa() { return use_wide_kernel() ? "x86-64-v4 copy (AVX-512, chosen at run time)" : "build's"; }

void lbm_allow_wide_kernel(bool allowed) { wide_kernel_allowed = allowed; }

// The fused pull stream-collide pass over the fluid row spans, OpenMP over spans.
template <int Mode, bool Force>
void LbmShallow::stream_collide(int& flagged) {
  const KernelArgs a{fa_.data(),
                     fb_.data(),
                     ha_.data(),
                     hb_.data(),
                     z_.data(),
                     static_cast<std::ptrdiff_t>(stride_),
                     static_cast<std::ptrdiff_t>(plane_),
                     Collision{omega_, g_, ax_, ay_, hmin_, href_},
                     g_ / 6.0f,
                     g_ / 24.0f};
  float (*span)(const KernelArgs&, std::ptrdiff_t, std::ptrdiff_t) = span_kernel<Mode, Force>;
#if HUYGENS_LBM_WIDE_CLONE
  if (use_wide_kernel()) span = span_kernel_wide<Mode, Force>;
#endif
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
  int total = 0;
  const bool par = ncells_ >= 16384;  // small lattices: a thread team costs more than it saves
#pragma omp parallel for schedule(static) reduction(+ : total) if (par)
  for (int s = 0; s < nspans; ++s) total += static_cast<int>(span(a, spans[s].begin, spans[s].end));
  flagged = total;
}

// The all-wet pass: flat bed, well-balanced centred bed term or the naive one; with or without an
// external force.
void LbmShallow::all_wet_kernel(int& flagged) {
  const int mode = !has_bed_ ? 0 : p_.bed_force == LbmBedForce::centred ? 1 : 2;
  const bool force = ax_ != 0.0f || ay_ != 0.0f;
  switch (mode * 2 + (force ? 1 : 0)) {
    case 0:
      return stream_collide<0, false>(flagged);
    case 1:
      return stream_collide<0, true>(flagged);
    case 2:
      return stream_collide<1, false>(flagged);
    case 3:
      return stream_collide<1, true>(flagged);
    case 4:
      return stream_collide<2, false>(flagged);
    default:
      return stream_collide<2, true>(flagged);
  }
}

}  // namespace huygens
