// The ghost rules of the sides and obstacles (periodic, walls, Zou-He inflow, outflow) and the ghost
// populations and depths they set before each step.
#include <algorithm>
#include <cstddef>

#include "huygens/lbm/shallow.hpp"
#include "lattice_cell.hpp"

namespace huygens {

using namespace lbm_cell;

// The ghost rules of this rank's fluid cells; on several ranks also the rules of the cells up to
// two rows beyond its own that set a ghost depth in its lattice (set_ghost_depths replays them in
// one process's order, so every ghost depth a kernel reads is the one one process writes last).
void LbmShallow::build_rules(const LbmFields& in) {
  rules_ = make_rules(row0_, row0_ + rows_, row0_ - halo_, row0_ + rows_ + halo_, in.solid);
  if (ranks_ > 1) {
    const int first = row0_ + 1, last = row0_ + rows_ - 2;  // inner rows
    inner_rules_ = make_rules(first, last + 1, row0_ - halo_, row0_ + rows_ + halo_, in.solid);
    for (const Rule& r : make_rules(row0_, first, row0_ - halo_, row0_ + rows_ + halo_, in.solid))
      edge_rules_.push_back(r);
    for (const Rule& r : make_rules(last + 1, row0_ + rows_, row0_ - halo_, row0_ + rows_ + halo_, in.solid))
      edge_rules_.push_back(r);
  }
  if (ranks_ > 1)
    depth_rules_ = make_rules(std::max(0, row0_ - 2), std::min(p_.rows, row0_ + rows_ + 2), row0_ - halo_,
                              row0_ + rows_ + halo_, in.solid);
}

// The rules of the fluid cells of global rows [r0, r1) whose ghost lies in rows [s0, s1), in one
// process's order (rows, columns, links; copies before inflow/outflow). `solid` is the global
// obstacle mask (empty: none).
std::vector<LbmShallow::Rule> LbmShallow::make_rules(int r0, int r1, int s0, int s1,
                                                     const std::vector<std::uint8_t>& solid) const {
  const int nx = p_.cols, ny = p_.rows;
  const LbmSide sides[4] = {p_.left, p_.right, p_.bottom, p_.top};
  auto inside = [&](int r, int c) { return r >= 0 && r < ny && c >= 0 && c < nx; };
  auto fluid = [&](int r, int c) {
    return inside(r, c) && (solid.empty() || !solid[static_cast<std::size_t>(r) * nx + c]);
  };
  std::vector<Rule> rules;
  for (int r = r0; r < r1; ++r)
    for (int c = 0; c < nx; ++c) {
      if (!fluid(r, c)) continue;
      const std::uint32_t x = static_cast<std::uint32_t>(idx(r, c));
      for (int a = 1; a < 9; ++a) {
        int sr = r - kEy[a], sc = c - kEx[a];
        if (fluid(sr, sc) || sr < s0 || sr >= s1) continue;
        Rule rule{};
        rule.a = static_cast<std::uint8_t>(a);
        rule.x = x;
        rule.s = static_cast<std::uint32_t>(idx(sr, sc));
        rule.dst = static_cast<std::uint32_t>(a * plane_ + rule.s);
        rule.up = kNone;
        rule.kind = 0;
        const std::uint32_t bounce = static_cast<std::uint32_t>(kOpp[a] * plane_ + x);
        rule.src = bounce;
        if (!inside(sr, sc)) {
          // Wrap periodic directions first.
          if ((sc < 0 || sc >= nx) && p_.left == LbmSide::periodic) sc = (sc + nx) % nx;
          if ((sr < 0 || sr >= ny) && p_.bottom == LbmSide::periodic) sr = (sr + ny) % ny;
          const bool xo = sc < 0 || sc >= nx, yo = sr < 0 || sr >= ny;
          if (!xo && !yo) {
            if (fluid(sr, sc)) {
              rule.src = static_cast<std::uint32_t>(a * plane_ + idx(sr, sc));
              rule.up = static_cast<std::uint32_t>(idx(sr, sc));
            }
          } else {
            // A corner ghost belongs to the inflow / outflow side if there is one, else it bounces.
            const int xside = sc < 0 ? 0 : 1;
            const bool open_x = xo && (sides[xside] == LbmSide::inflow || sides[xside] == LbmSide::outflow);
            if (xo && yo && !open_x) {
              rules.push_back(rule);
              continue;
            }
            const int side = xo ? xside : (sr < 0 ? 2 : 3);
            const LbmSide kind = sides[side];
            if (kind == LbmSide::slip) {
              const int mr = xo ? sr : sr + kEy[a], mc = xo ? sc + kEx[a] : sc;
              const int b = xo ? kMirrorX[a] : kMirrorY[a];
              if (fluid(mr, mc)) {
                rule.src = static_cast<std::uint32_t>(b * plane_ + idx(mr, mc));
                rule.up = static_cast<std::uint32_t>(idx(mr, mc));  // the link it really travelled
              }
            } else if (kind == LbmSide::inflow) {
              rule.kind = 1;
              rule.src = x;
            } else if (kind == LbmSide::outflow) {
              if (p_.outflow_depth_m > 0) {
                rule.kind = 2;
                rule.src = x;
              } else {
                const int mc = sc < 0 ? 0 : nx - 1;
                if (fluid(sr, mc)) {
                  rule.src = static_cast<std::uint32_t>(a * plane_ + idx(sr, mc));
                  rule.up = static_cast<std::uint32_t>(idx(sr, mc));
                }
              }
            }
          }
        }
        rules.push_back(rule);
      }
    }
  std::stable_partition(rules.begin(), rules.end(), [](const Rule& r) { return r.kind == 0; });
  return rules;
}

void LbmShallow::set_ghost_depths() {
  // A ghost takes the depth of the cell whose populations it carries (periodic image, mirror,
  // zero-gradient copy) or of the cell it feeds (Zou-He), so the wet/dry rule sees the real face;
  // wall and obstacle ghosts are marked -1 (their value, the bounce-back, passes unchanged).
  float* h = ha_.data();
  for (const Rule& r : ranks_ > 1 ? depth_rules_ : rules_)
    h[r.s] = r.up != kNone ? h[r.up] : r.kind != 0 ? h[r.x] : -1.0f;
}

void LbmShallow::fill_ghosts(bool wet_dry) {
  float* f = fa_.data();
  const float* h = ha_.data();
  const float* z = z_.data();
  const bool comp = has_bed_ && p_.bed_force == LbmBedForce::centred;
  const float hmin = hmin_;
  // the wet/dry pass adds the bed term on wet-wet faces only
  auto wet = [&](std::uint32_t a, std::uint32_t b) { return !wet_dry || (h[a] >= hmin && h[b] >= hmin); };
  const double q = p_.inflow_discharge_m2s * p_.dt_s / p_.cell_m;  // h u_lat (unit: m)
  for (const Rule& r : rules_) {  // copies first, then inflow/outflow (they read the copies)
    float v;
    if (r.kind == 0) {
      v = f[r.src];
    } else {
      // Zou-He for shallow water: the unknown populations of x are set from the ones x pulls
      // this step so that h u_x = q (inflow) or h = h_out (outflow) and h u_y is unchanged.
      // On shifted populations the formulas are the same (opposite links share their shift).
      const std::ptrdiff_t S = static_cast<std::ptrdiff_t>(stride_);
      auto pulled = [&](int b) { return static_cast<double>(f[b * plane_ + r.x - (kEy[b] * S + kEx[b])]); };
      const double ns = 0.5 * (pulled(4) - pulled(2));  // (f_S - f_N) / 2
      double m;
      if (r.kind == 1) {
        m = q;
        v = static_cast<float>(r.a == 1   ? pulled(3) + 2.0 * m / 3.0
                               : r.a == 5 ? pulled(7) + m / 6.0 + ns
                                          : pulled(6) + m / 6.0 - ns);
      } else {
        const double known = pulled(0) + pulled(2) + pulled(4) + 2.0 * (pulled(1) + pulled(5) + pulled(8));
        m = known + href_ - p_.outflow_depth_m;  // h u = K - h_out
        v = static_cast<float>(r.a == 3   ? pulled(1) - 2.0 * m / 3.0
                               : r.a == 6 ? pulled(8) - m / 6.0 + ns
                                          : pulled(5) - m / 6.0 - ns);
      }
    }
    if (comp) {
      const float k = static_cast<float>(kLambda[r.a]) * g_ * (1.0f / 6.0f);
      if (wet(r.x, r.s)) v -= -k * (h[r.x] + h[r.s]) * (z[r.x] - z[r.s]);  // the kernel adds this back
      if (r.up != kNone && wet(r.x, r.up)) v += -k * (h[r.x] + h[r.up]) * (z[r.x] - z[r.up]);
    }
    f[r.dst] = v;
  }
}

}  // namespace huygens
