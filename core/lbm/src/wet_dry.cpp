// The wet/dry pass (paper 002 with wet/dry links; HLL faces where the flow is fast and thin): the
// faces, the outflow limiter, the cell update with its mass kept, run while a cell is dry.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>

#include "huygens/lbm/shallow.hpp"
#include "lattice_cell.hpp"

namespace huygens {

using namespace lbm_cell;

namespace {

// pulled, p2 = f*_abar(c) its own (shifted values). Returns what c receives unlimited (p1 plus the
// centred bed term on a wet-wet face, k = lambda_a g / 6; p2 on a closed face; on an open wet-dry
// face the wet cell's mirror mc, the dry cell the rest p1 + p2 - mn) and sets the net flux into c,
// F = v - p2. n computes the same face from the same floats with the roles of p1 and p2 swapped and
// the bed term negated, so the face exchanges water and makes none. A ghost neighbour streams
// (its image decides the same way); a wall ghost (hn < 0) passes its bounce-back.
[[gnu::always_inline]] inline float wet_dry_face(float p1, float p2, float hc, float zc, float hn, float zn, float k,
                                                 float hmin, bool ghost, float mc, float mn, float& flux,
                                                 double& exact) {
  const bool wc = hc >= hmin, wn = hn >= hmin;
  const bool closed = (wc != wn) & (wc ? hc + zc <= zn + hmin : hn + zn <= zc + hmin);
  const float bed = (wc & wn) ? -k * (hc + hn) * (zc - zn) : 0.0f;
  const bool stream = (wc == wn) | ghost;
  const float open = stream ? p1 + bed : wc ? mc : p1 + p2 - mn;
  const float v = ghost & (hn < 0.0f) ? p1 : closed ? p2 : open;  // hn < 0: a wall ghost
  // the same value before rounding: n's share is then exactly p1 + p2 minus it (mass accounting)
  const double dopen = stream ? double(p1) + bed : wc ? double(mc) : double(p1) + p2 - mn;
  exact = ghost & (hn < 0.0f) ? double(p1) : closed ? double(p2) : dopen;
  flux = v - p2;
  return v;
}

// What a wet cell (depth h, lattice velocity u) receives on link a from a dry neighbour: its own
// equilibrium population of that link without the pressure part lambda_a g h^2 / 6, i.e. an empty
// neighbour moving with it (shifted by ks). The dry cell receives the rest of the pair.
[[gnu::always_inline]] inline float dry_mirror(int a, float h, float ux, float uy, float ks) {
  const float eu = static_cast<float>(kEx[a]) * ux + static_cast<float>(kEy[a]) * uy;
  return static_cast<float>(kLambda[a]) * h *
             (eu * (1.0f / 3.0f) + 0.5f * eu * eu - (ux * ux + uy * uy) * (1.0f / 6.0f)) -
         ks;
}

// Lattice velocity of cell c from its post-collision populations (shifted: the shifts carry no
// momentum), 0 when dry.
[[gnu::always_inline]] inline void cell_velocity(const float* src, std::ptrdiff_t P, std::ptrdiff_t c, float h,
                                                 float hmin, float& ux, float& uy) {
  const float f1 = src[P + c], f2 = src[2 * P + c], f3 = src[3 * P + c], f4 = src[4 * P + c];
  const float f5 = src[5 * P + c], f6 = src[6 * P + c], f7 = src[7 * P + c], f8 = src[8 * P + c];
  const float ih = h >= hmin ? 1.0f / h : 0.0f;
  ux = ((f1 + f5 + f8) - (f3 + f6 + f7)) * ih;
  uy = ((f2 + f5 + f6) - (f4 + f7 + f8)) * ih;
}

// A dry cell (h < h_min) puts all its water at rest: f*_a = 0 (stored -ks_a) and the rest population
// gains what arrived on the moving links, f*_0 = f_0 + sum (f_a + ks_a): a dry cell nothing reached
// keeps its populations bit for bit (recomputing f*_0 from h would add a rounding every step).
[[gnu::always_inline]] inline Cell9 rest_if_dry(const Cell9& f, const Cell9& o, float h, float hmin, const Cell9& ks) {
  const bool dry = h < hmin;
  const float r0 = f.f0 + ((((f.f1 + ks.f1) + (f.f2 + ks.f2)) + ((f.f3 + ks.f3) + (f.f4 + ks.f4))) +
                           (((f.f5 + ks.f5) + (f.f6 + ks.f6)) + ((f.f7 + ks.f7) + (f.f8 + ks.f8))));
  return {dry ? r0 : o.f0,     dry ? -ks.f1 : o.f1, dry ? -ks.f2 : o.f2, dry ? -ks.f3 : o.f3, dry ? -ks.f4 : o.f4,
          dry ? -ks.f5 : o.f5, dry ? -ks.f6 : o.f6, dry ? -ks.f7 : o.f7, dry ? -ks.f8 : o.f8};
}

// Froude number above which a wet cell's faces take the HLL flux in the wet/dry pass: a D2Q9
// lattice relaxes to the equilibrium through the speeds -1, 0, +1, and the relaxation is
// dissipative only while the wave speeds u - c and u + c interlace with them (Liu's
// subcharacteristic condition: u - c <= 0 <= u + c), i.e. only subcritical flow. At u = c the
// BGK lattice holds an entropy-violating expansion jump, beyond it (a dry-bed dam break from the
// dam to the front) it is anti-diffusive (docs/lbm.md).
constexpr float kFvFroude = 0.8f;

// A cell's state as the HLL link flux sees it: depth, surface h + z_b (m), lattice velocity.
struct LinkState {
  float h, eta, ux, uy;
};

// The LBM equilibrium fluxes of link pair a (a, abar) of a uniform state: mass m = f_a - f_abar =
// (2/3) lambda_a h (e_a.u) along e_a and momentum pi = f_a + f_abar = 2 lambda_a h (g h/6 +
// (e_a.u)^2/2 - u.u/6) (lattice units), what streaming a uniform equilibrium exchanges.
[[gnu::always_inline]] inline void link_flux(int a, const LinkState& s, float g, float& m, float& pi) {
  const float eu = static_cast<float>(kEx[a]) * s.ux + static_cast<float>(kEy[a]) * s.uy;
  const float lam = static_cast<float>(kLambda[a]);
  m = lam * (2.0f / 3.0f) * s.h * eu;
  pi = 2.0f * lam * s.h * (g * s.h * (1.0f / 6.0f) + 0.5f * eu * eu - (s.ux * s.ux + s.uy * s.uy) * (1.0f / 6.0f));
}

// HLL flux (Harten, Lax and van Leer 1983; the wave speeds of Davis 1988, min / max of u -+ c over
// both sides; the dry-bed speeds u +- 2c of Toro 2001) of link pair a from L = x - e_a to R = x, in the link's own 1D
// problem: speeds in link lengths per step, (e_a.u)/|e_a|^2 +- c/|e_a|, conserved link variables kappa_a (eta, e_a.J)
// with kappa_a = (2/3) lambda_a |e_a|^2, so a uniform state gets exactly the LBM exchange (link_flux) and a 1D flow the
// physical flux split 2/3, 1/6, 1/6 over the three links that cross a face. The mass dissipation acts on the surface
// eta (still water over a bed exchanges nothing). Returns the mass into R and the momentum flux along e_a. Not inlined:
// both cells of a face call it with the same arguments, so they get the same floats (mass is exchanged).
[[gnu::noinline]] void hll_link(int a, LinkState L, LinkState R, float g, float hmin, float& m, float& pi) {
  const bool diag = a >= 5;
  const float e2 = diag ? 2.0f : 1.0f, ie = diag ? 0.70710678f : 1.0f, kap = diag ? 1.0f / 3.0f : 2.0f / 3.0f;
  const float ex = static_cast<float>(kEx[a]), ey = static_cast<float>(kEy[a]);
  const float sl = (ex * L.ux + ey * L.uy) / e2, sr = (ex * R.ux + ey * R.uy) / e2;
  const float cl = std::sqrt(g * L.h) * ie, cr = std::sqrt(g * R.h) * ie;
  float lo = std::min(sl - cl, sr - cr), hi = std::max(sl + cl, sr + cr);
  if (R.h < hmin) lo = sl - cl, hi = sl + 2.0f * cl;
  if (L.h < hmin) lo = sr - 2.0f * cr, hi = sr + cr;
  float ml, pl, mr, pr;
  link_flux(a, L, g, ml, pl);
  link_flux(a, R, g, mr, pr);
  if (lo >= 0.0f) {
    m = ml, pi = pl;
  } else if (hi <= 0.0f) {
    m = mr, pi = pr;
  } else {
    const float d = 1.0f / (hi - lo), ss = lo * hi * kap;
    const float ql = L.h * (ex * L.ux + ey * L.uy), qr = R.h * (ex * R.ux + ey * R.uy);
    m = (hi * ml - lo * mr + ss * (R.eta - L.eta)) * d;
    pi = (hi * pl - lo * pr + ss * (qr - ql)) * d;
  }
}

// minmod slope limiter (Roe 1986): the smaller one-sided difference, 0 at an extremum.
[[gnu::always_inline]] inline float minmod(float l, float r) {
  return l * r <= 0.0f ? 0.0f : std::abs(l) < std::abs(r) ? l : r;
}

// A wet cell's state and its minmod slopes [along x, along y][surface, u_x, u_y].
struct CellSlopes {
  LinkState s;
  float sl[2][3];
};

// The limiter plane packs a cell's theta (0..1) and its flag (Froude above kFvFroude) as theta + 2.
[[gnu::always_inline]] inline bool fv_flag(float packed) { return packed >= 2.0f; }
[[gnu::always_inline]] inline float fv_theta(float packed) { return packed >= 2.0f ? packed - 2.0f : packed; }

// One face of the wet/dry pass as cell c sees it on link a: what c receives unlimited (v, LBM
// faces), c's own outgoing population p2, the net mass into c (flux) and, on an HLL face, the
// momentum flux along e_a including c's bed term (pi); img is the real cell behind the face.
struct WdFace {
  float v, p2, flux, pi;
  double vx;  // v before rounding (LBM faces)
  std::ptrdiff_t img;
  bool fv;
};

}  // namespace

// Pointers and constants of the wet/dry pass; face() evaluates one face the same way for the
// limiter and the update, so both cells of a face and both passes agree.
struct LbmShallow::WetDryView {
  const float* src;
  const float* h;
  const float* z;
  const float* flags;  // >= 2: the cell's faces take the HLL flux
  const std::uint8_t* solid;
  const float* shift;
  std::ptrdiff_t P, S, pad;
  std::ptrdiff_t off[9];
  float kb[9];
  float g, hmin;
  int nx, ny;
  bool px, py;
  bool slip[4];                          // left, right, bottom, top are free-slip (specular) sides
  std::ptrdiff_t first_row, image_slot;  // global row of lattice row 0; lattice row of the image row

  // The real cell behind n: n if fluid, the periodic image of a ghost, else -1 (walls, obstacles,
  // mirror and open sides keep their ghost rules).
  std::ptrdiff_t image(std::ptrdiff_t n) const {
    if (!solid[n]) return n;
    if (h[n] < 0.0f || !(px || py)) return -1;
    std::ptrdiff_t row = row_of(n), col = n % S - pad;
    if (px) col = (col + nx) % nx;
    if (py) row = (row + ny) % ny;
    if (row < 0 || row >= ny || col < 0 || col >= nx) return -1;
    const std::ptrdiff_t m = at(row, col);
    return solid[m] ? -1 : m;
  }
  // The real cell k links along e_a from the fluid cell at (r0, c0), else -1: periodic sides wrap,
  // beyond one free-slip side it is the mirror image (flip: 1 the image's x velocity is reversed, 2
  // its y velocity; what the specular ghost rule streams); beyond two sides (a corner ghost bounces
  // back), a wall or an open side, or outside this rank's lattice rows there is none.
  std::ptrdiff_t along(std::ptrdiff_t r0, std::ptrdiff_t c0, int a, int k, int& flip) const {
    std::ptrdiff_t row = r0 + k * kEy[a], col = c0 + k * kEx[a];
    if (px) col = (col % nx + nx) % nx;
    if (py) row = (row % ny + ny) % ny;
    flip = 0;
    const bool xo = col < 0 || col >= nx, yo = row < 0 || row >= ny;
    if (xo && yo) return -1;
    // reflected until inside (twice in a channel one cell wide: the image of the image)
    for (int i = 0; i < 2 && (col < 0 || col >= nx); ++i) {
      if (!slip[col < 0 ? 0 : 1]) return -1;
      col = col < 0 ? -1 - col : 2 * std::ptrdiff_t(nx) - 1 - col;
      flip ^= 1;
    }
    for (int i = 0; i < 2 && (row < 0 || row >= ny); ++i) {
      if (!slip[row < 0 ? 2 : 3]) return -1;
      row = row < 0 ? -1 - row : 2 * std::ptrdiff_t(ny) - 1 - row;
      flip ^= 2;
    }
    if (row < 0 || row >= ny || col < 0 || col >= nx) return -1;
    if ((xo || yo) && (row - first_row < 0 || row - first_row >= image_slot)) return -1;
    const std::ptrdiff_t m = at(row, col);
    return solid[m] ? -1 : m;
  }
  // Global row of lattice index n (not the image row) and the lattice index of (global row, col):
  // lattice row 0 is global row first_row (row0 - halo); a row beyond the halo is the image row.
  std::ptrdiff_t row_of(std::ptrdiff_t n) const { return n / S + first_row; }
  std::ptrdiff_t at(std::ptrdiff_t row, std::ptrdiff_t col) const {
    std::ptrdiff_t lr = row - first_row;
    if (lr < 0 || lr >= image_slot) lr = image_slot;
    return lr * S + pad + col;
  }
  LinkState state(std::ptrdiff_t x, int flip = 0) const {
    float ux, uy;
    cell_velocity(src, P, x, h[x], hmin, ux, uy);
    return {h[x], h[x] + z[x], flip == 1 ? -ux : ux, flip == 2 ? -uy : uy};
  }
  using Slopes = CellSlopes;
  Slopes slopes(std::ptrdiff_t x) const;
  // The slopes of the cells one cell's faces need, each computed once.
  struct SlopeCache {
    const WetDryView* v;
    std::ptrdiff_t id[12];
    Slopes k[12];
    int n = 0;
    const Slopes& get(std::ptrdiff_t x) {
      for (int i = 0; i < n; ++i)
        if (id[i] == x) return k[i];
      const int i = n < 12 ? n++ : 11;
      id[i] = x;
      k[i] = v->slopes(x);
      return k[i];
    }
  };
  void muscl(int a, std::ptrdiff_t l, int fl, std::ptrdiff_t r, int fr, SlopeCache& cache, float& m, float& pi) const;
  void slip_face(int a, std::ptrdiff_t row, std::ptrdiff_t col, std::ptrdiff_t u, int flip, SlopeCache& cache,
                 WdFace& f) const;
  // The HLL flux through a free-slip side into the fluid cell at (row, col) on link a, whose
  // neighbour x - e_a is a specular ghost: the link's 1D problem between the mirror image of the
  // cell the ghost copies and the cell. Both cells a reflected link pair joins call it for the
  // same (row, col, a), so they get the same floats.
  void slip_link(std::ptrdiff_t row, std::ptrdiff_t col, int a, SlopeCache& cache, float& m, float& pi) const {
    int fl;
    const std::ptrdiff_t l = along(row, col, a, -1, fl);
    muscl(a, l, fl, at(row, col), 0, cache, m, pi);
  }
  float mirror(int a, std::ptrdiff_t w) const {  // only used when w is wet and its neighbour dry
    float ux, uy;
    cell_velocity(src, P, w, h[w], hmin, ux, uy);
    return dry_mirror(a, h[w], ux, uy, shift[a]);
  }
  // The faces of cell c (row, col known), a = 1..8: HLL on an open face with a dry side or a
  // flagged cell (canonical orientation: links 1, 2, 5, 6 from the neighbour, so both cells call
  // muscl with the same arguments; through a free-slip side see slip_face), no exchange between
  // dry cells, else the LBM rules.
  void faces(std::ptrdiff_t c, std::ptrdiff_t row, std::ptrdiff_t col, WdFace* out) const {
    std::ptrdiff_t img[9], mir[9] = {};
    int flip[9] = {};
    for (int a = 1; a < 9; ++a) {
      img[a] = image(c - off[a]);
      mir[a] = img[a] < 0 ? along(row, col, a, -1, flip[a]) : -1;  // a free-slip side's ghost
      if (flip[a] != 1 && flip[a] != 2) mir[a] = -1;
    }
    SlopeCache cache{this, {}, {}};
    for (int a = 1; a < 9; ++a) out[a] = face(c, a, row, col, img[a], mir[a], flip[a], cache);
  }
  WdFace face(std::ptrdiff_t c, int a, std::ptrdiff_t row, std::ptrdiff_t col, std::ptrdiff_t img, std::ptrdiff_t mir,
              int flip, SlopeCache& cache) const {
    const std::ptrdiff_t n = c - off[a];
    const int b = kOpp[a];
    WdFace f{0.0f, src[b * P + c], 0.0f, 0.0f, 0.0, img, false};
    const float hc = h[c], zc = z[c], hn = h[n], zn = z[n];
    const bool wc = hc >= hmin, wn = hn >= hmin;
    const std::ptrdiff_t u = img >= 0 ? img : mir;  // the real cell behind the face
    if (u >= 0 && !wc && !wn) {                     // dry land: no exchange (a film below h_min stays put)
      f.img = u;
      f.fv = true;
      return f;
    }
    if (u >= 0) {
      const float zu = z[u];
      const bool closed = (wc != wn) && (wc ? hc + zc <= zu + hmin : hn + zu <= zc + hmin);
      if (!closed && (wc != wn || fv_flag(flags[c]) || fv_flag(flags[u]))) {
        if (img < 0) {
          slip_face(a, row, col, u, flip, cache, f);
        } else if (a == 1 || a == 2 || a == 5 || a == 6) {
          muscl(a, u, 0, c, 0, cache, f.flux, f.pi);
        } else {
          float m;
          muscl(b, c, 0, u, 0, cache, m, f.pi);
          f.flux = -m;
        }
        if (wc && wn) f.pi += -kb[a] * (hc + hn) * (zc - zu);
        f.fv = true;
        return f;
      }
    }
    const bool mixed = !solid[n] && wc != wn;
    f.v = wet_dry_face(src[a * P + n], f.p2, hc, zc, hn, zn, kb[a], hmin, solid[n] != 0, mixed ? mirror(a, c) : 0.0f,
                       mixed ? mirror(b, n) : 0.0f, f.flux, f.vx);
    return f;
  }
};

// A wet cell's minmod slopes of surface and velocity along x and along y from its four axis
// neighbours (a dry or missing pair: none along that axis; through a free-slip side the mirror
// image). Not inlined: every face of the cell uses the same floats.
[[gnu::noinline]] LbmShallow::WetDryView::Slopes LbmShallow::WetDryView::slopes(std::ptrdiff_t x) const {
  Slopes k{state(x), {}};
  const std::ptrdiff_t row = row_of(x), col = x % S - pad;
  for (int d = 0; d < 2; ++d) {
    int fm, fp;
    const std::ptrdiff_t m = along(row, col, d + 1, -1, fm), p = along(row, col, d + 1, 1, fp);
    if (m < 0 || p < 0 || h[m] < hmin || h[p] < hmin) continue;
    const LinkState l = state(m, fm), r = state(p, fp);
    k.sl[d][0] = minmod(k.s.eta - l.eta, r.eta - k.s.eta);
    k.sl[d][1] = minmod(k.s.ux - l.ux, r.ux - k.s.ux);
    k.sl[d][2] = minmod(k.s.uy - l.uy, r.uy - k.s.uy);
  }
  return k;
}

namespace {

// The face value of a cell with slopes k towards (dx, dy), the components of +-e_a (flip: of its
// mirror image, as along()), second order in space and time (MUSCL-Hancock, van Leer 1979; Toro
// 2001 sec. 14.4 and 16.5): the slopes extrapolated to the face centre (a diagonal link's: the
// corner), then half a step of the 2D shallow-water equations in primitive form from both
// slopes, h_t = -(u.grad h + h div u), u_t = -(u.grad u + g grad eta). The depth follows the
// surface (still water stays still). The predictor sees both directions: one along the link only
// (each link's own 1D equations) misses the transverse terms, and its link pressure h (g h - u_perp^2)/2
// is negative across a supercritical flow: a thin sheet grew transverse waves (docs/lbm.md).
// Not inlined: both cells of a face call it with the same arguments and get the same floats.
[[gnu::noinline]] LinkState extrapolate(const CellSlopes& k, int flip, int dx, int dy, float g, float hmin) {
  if (flip == 1) dx = -dx;
  if (flip == 2) dy = -dy;
  const LinkState& s = k.s;
  const float(&sl)[2][3] = k.sl;
  const float fx = 0.5f * static_cast<float>(dx), fy = 0.5f * static_cast<float>(dy);
  const float de = fx * sl[0][0] + fy * sl[1][0];
  LinkState o{std::max(0.0f, s.h + de), s.eta + de, s.ux + fx * sl[0][1] + fy * sl[1][1],
              s.uy + fx * sl[0][2] + fy * sl[1][2]};
  const float ht = -(s.ux * sl[0][0] + s.uy * sl[1][0] + s.h * (sl[0][1] + sl[1][2]));
  const float uxt = -(s.ux * sl[0][1] + s.uy * sl[1][1] + g * sl[0][0]);
  const float uyt = -(s.ux * sl[0][2] + s.uy * sl[1][2] + g * sl[1][0]);
  const float h1 = o.h + 0.5f * ht;
  if (h1 > hmin) o = {h1, o.eta + 0.5f * ht, o.ux + 0.5f * uxt, o.uy + 0.5f * uyt};
  if (flip == 1) o.ux = -o.ux;
  if (flip == 2) o.uy = -o.uy;
  return o;
}

}  // namespace

// Second-order HLL flux of link a from cell l (flip fl) to cell r (flip fr): face values when both
// are wet, first order on a face with a dry side. Not inlined (see extrapolate).
[[gnu::noinline]] void LbmShallow::WetDryView::muscl(int a, std::ptrdiff_t l, int fl, std::ptrdiff_t r, int fr,
                                                     SlopeCache& cache, float& m, float& pi) const {
  LinkState L = state(l, fl), R = state(r, fr);
  if (L.h >= hmin && R.h >= hmin) {
    L = extrapolate(cache.get(l), fl, kEx[a], kEy[a], g, hmin);
    R = extrapolate(cache.get(r), fr, -kEx[a], -kEy[a], g, hmin);
  }
  hll_link(a, L, R, g, hmin, m, pi);
}

// An HLL face of cell c (row, col) on link a through a free-slip side, u the cell the ghost
// copies (flip: the side's axis, 1 x, 2 y). The side reflects link a of u into link a of c: the
// pair exchanges water between c and u (u the cell behind the face for the limiter). It is
// computed once in a canonical orientation, the link whose component along the side is positive
// (the receiving cell's flux m; the partner books -m and the same momentum flux, by the mirror
// symmetry); a link normal to the side reflects into itself and passes no water.
void LbmShallow::WetDryView::slip_face(int a, std::ptrdiff_t row, std::ptrdiff_t col, std::ptrdiff_t u, int flip,
                                       SlopeCache& cache, WdFace& f) const {
  const int partner = flip == 2 ? kMirrorX[a] : kMirrorY[a];
  const int along_side = flip == 2 ? kEx[a] : kEy[a];
  float m;
  if (along_side >= 0) {
    slip_link(row, col, a, cache, m, f.pi);
    f.flux = partner == a ? 0.0f : m;
  } else {
    slip_link(row_of(u), u % S - pad, partner, cache, m, f.pi);
    f.flux = -m;
  }
  f.img = u;
  f.fv = true;
}

LbmShallow::WetDryView LbmShallow::wet_dry_view(const float* flags) const {
  const std::ptrdiff_t S = static_cast<std::ptrdiff_t>(stride_);
  WetDryView w{
      fa_.data(),
      ha_.data(),
      z_.data(),
      flags,
      solid_.data(),
      shift_f_.data(),
      static_cast<std::ptrdiff_t>(plane_),
      S,
      static_cast<std::ptrdiff_t>(kPad),
      {0, 1, S, -1, -S, S + 1, S - 1, -S - 1, -S + 1},
      {},
      g_,
      hmin_,
      p_.cols,
      p_.rows,
      p_.left == LbmSide::periodic,
      p_.bottom == LbmSide::periodic,
      {p_.left == LbmSide::slip, p_.right == LbmSide::slip, p_.bottom == LbmSide::slip, p_.top == LbmSide::slip},
      row0_ - halo_,
      rows_ + 2 * halo_};
  for (int a = 1; a < 9; ++a) w.kb[a] = a < 5 ? g_ / 6 : g_ / 24;
  return w;
}

// Flags (into the next-depth plane, free until the update writes it) the wet cells whose Froude
// number exceeds kFvFroude: their faces take the HLL flux.
void LbmShallow::flag_supercritical() {
  const std::ptrdiff_t P = static_cast<std::ptrdiff_t>(plane_);
  const float* src = fa_.data();
  const float* hold = ha_.data();
  float* flags = hb_.data();
  const float hmin = hmin_, f2 = kFvFroude * kFvFroude * g_;
  auto flag = [&](std::ptrdiff_t c) {
    float ux, uy;
    cell_velocity(src, P, c, hold[c], hmin, ux, uy);
    flags[c] = hold[c] >= hmin && ux * ux + uy * uy > f2 * hold[c] ? 2.0f : 0.0f;
  };
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
#pragma omp parallel for schedule(static) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) flag(c);
  // several ranks: the first halo rows and the image row too (their faces with this rank's cells)
  for (const Span& sp : halo_spans_)
    for (std::ptrdiff_t c = sp.begin; c < sp.end; ++c) flag(c);
}

// Net outflow limiter of the wet/dry pass: theta_c = min(1, h_c / O_c), O_c the sum of c's
// outgoing face fluxes; a face's flux is scaled by the theta of the cell it drains, so no depth
// goes negative (h_new >= h_c - theta_c O_c >= 0). Stored as theta + 2 for a flagged cell; ghosts
// take their image's value.
void LbmShallow::outflow_limiter() {
  const WetDryView view = wet_dry_view(hb_.data());
  float* theta = theta_.data();
  const float keep = hmin_ / 16.0f;
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
#pragma omp parallel for schedule(static) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) {
      WdFace fc[9];
      view.faces(c, view.row_of(c), c % view.S - view.pad, fc);
      float out = 0.0f;
      for (int a = 1; a < 9; ++a) out += fc[a].flux < 0.0f ? -fc[a].flux : 0.0f;
      const float avail = view.h[c] - keep;  // a film h_min/16 stays: float rounding never crosses 0
      const float th = out <= avail ? 1.0f : avail > 0.0f ? avail / out : 0.0f;
      theta[c] = th + (fv_flag(view.flags[c]) ? 2.0f : 0.0f);
    }
  exchange_theta();  // the halo rows' theta (several ranks; halo.cpp)
  for (const Rule& r : rules_) theta[r.s] = r.up != kNone ? theta[r.up] : 1.0f;
}

namespace {

// Makes the nine floats sum to `mass` (double) as closely as floats allow: the rounding left by
// the collision goes into the rest population, what that rounds off into the opposite pairs of
// links in equal halves (no momentum: still water stays still). Returns what the floats could not
// take, mass - sum op (under half a float ulp of the cell's smallest population touched), which
// the caller carries to the cell's next step (compensated storage, Kahan 1965; docs/lbm.md).
double keep_mass(double mass, float* op) {
  double sum = 0.0;
  for (int a = 0; a < 9; ++a) sum += op[a];
  double r = mass - sum;
  const float n0 = static_cast<float>(op[0] + r);
  r -= double(n0) - double(op[0]);
  op[0] = n0;
  for (int a = 1; a < 9 && r != 0.0; a += a == 2 || a == 6 ? 3 : 1) {  // pairs (1,3) (2,4) (5,7) (6,8)
    const int b = kOpp[a];
    const float na = static_cast<float>(op[a] + 0.5 * r), nb = static_cast<float>(op[b] + 0.5 * r);
    r -= (double(na) - double(op[a])) + (double(nb) - double(op[b]));
    op[a] = na;
    op[b] = nb;
  }
  return r;
}

// The post-collision state of a cell the HLL update reached: the shifted equilibrium of depth h
// and momentum (jx, jy) (lattice units, speed capped at sqrt(umax2); a film below h_min keeps its
// momentum too, so water entering dry land arrives moving) plus the force lambda_a h (e_a . a)/3,
// the rest population taking h - H minus the others so the populations sum to the depth.
Cell9 equilibrium_cell(float h, float jx, float jy, const Collision& k, const float* ks) {
  const float ih = h > 0.0f ? 1.0f / h : 0.0f;
  float ux = jx * ih, uy = jy * ih;
  const float u2 = ux * ux + uy * uy, r = u2 > k.umax2 ? std::sqrt(k.umax2 / u2) : 1.0f;
  ux *= r;
  uy *= r;
  const float gx = h * (1.0f / 3.0f) * k.ax, gy = h * (1.0f / 3.0f) * k.ay;
  const float force[9] = {
      0, gx, gy, -gx, -gy, 0.25f * (gx + gy), 0.25f * (gy - gx), -0.25f * (gx + gy), -0.25f * (gy - gx)};
  float f[9], rest = h - k.href;
  for (int a = 1; a < 9; ++a) {
    const float eu = static_cast<float>(kEx[a]) * ux + static_cast<float>(kEy[a]) * uy;
    f[a] = static_cast<float>(kLambda[a]) * h *
               (k.g * h * (1.0f / 6.0f) + eu * (1.0f / 3.0f) + 0.5f * eu * eu - (ux * ux + uy * uy) * (1.0f / 6.0f)) -
           ks[a];
    rest -= f[a];
    f[a] += force[a];
  }
  return {rest, f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8]};
}

}  // namespace

// One cell of the wet/dry pass. Without an HLL face: limited exchanges, collision with |u| <= u_max.
// With one: the finite-volume update h += sum M_a, J += sum e_a Pi_a over its faces (an LBM face
// exchanges M = v - p2, Pi = v + p2, what streaming moves), then the equilibrium of (h, J) is
// collided. Dry cells to rest. Returns the new depth.
float LbmShallow::wet_dry_cell(const WetDryView& view, std::ptrdiff_t c, float* dst, float* carry) const {
  const std::ptrdiff_t P = view.P;
  const float* theta = theta_.data();
  const float* src = view.src;
  const Collision k{omega_, g_, ax_, ay_, hmin_, href_, umax_ * umax_};
  const float* shp = view.shift;
  const Cell9 ks{shp[0], shp[1], shp[2], shp[3], shp[4], shp[5], shp[6], shp[7], shp[8]};
  WdFace fc[9];
  view.faces(c, view.row_of(c), c % view.S - view.pad, fc);
  bool any = false;
  for (int a = 1; a < 9; ++a) any = any || fc[a].fv;
  float fp[9] = {src[c]};
  bool fed = false;  // water arrived over an HLL face
  float hs = src[c] + shp[0], jx = 0.0f, jy = 0.0f;
  // the stored (shifted) populations' new sum, exact to double rounding, plus what the cell's
  // floats could not hold last step (the carry plane, when there is one)
  double mass = double(src[c]) + (carry != nullptr ? double(carry[c]) : 0.0);
  for (int a = 1; a < 9; ++a) {
    const float own = src[a * P + c];
    mass += own;
    hs += own + shp[a];
    jx += static_cast<float>(kEx[a]) * own;
    jy += static_cast<float>(kEy[a]) * own;
  }
  for (int a = 1; a < 9; ++a) {
    const WdFace& f = fc[a];
    const std::ptrdiff_t other = f.fv ? f.img : c - view.off[a];
    // the drained cell's theta, chosen by the sign of the unrounded exchange (both cells see it)
    const double fx = f.fv ? double(f.flux) : f.vx - double(f.p2);
    const float th = fv_theta(fx < 0.0 ? theta[c] : theta[other]);
    const float v = th >= 1.0f ? f.v : f.p2 + th * f.flux;
    fp[a] = v;
    const float m = f.fv ? th * f.flux : v - f.p2, pi = f.fv ? th * f.pi : v + f.p2;
    fed = fed || (f.fv && m > 0.0f);
    mass += f.fv ? double(th) * f.flux : double(th) * (f.vx - f.p2);  // -(the neighbour's) exactly
    hs += m;
    jx += static_cast<float>(kEx[a]) * pi;
    jy += static_cast<float>(kEy[a]) * pi;
  }
  float h = hs, unused = 0.0f;
  const Cell9 f{fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7], fp[8]};
  Cell9 o;
  if (!any)
    o = rest_if_dry(f, collide<true>(f, k, h, unused), h, hmin_, ks);
  else if (hs >= hmin_ || fed)
    o = equilibrium_cell(hs, jx, jy, k, shp);
  else  // dry and nothing arrived: at rest
    o = Cell9{hs - href_ + (((ks.f1 + ks.f2) + (ks.f3 + ks.f4)) + ((ks.f5 + ks.f6) + (ks.f7 + ks.f8))),
              -ks.f1,
              -ks.f2,
              -ks.f3,
              -ks.f4,
              -ks.f5,
              -ks.f6,
              -ks.f7,
              -ks.f8};
  float op[9] = {o.f0, o.f1, o.f2, o.f3, o.f4, o.f5, o.f6, o.f7, o.f8};
  const double left = keep_mass(mass, op);
  if (carry != nullptr) carry[c] = static_cast<float>(left);
  for (int a = 0; a < 9; ++a) dst[a * P + c] = op[a];
  return any ? static_cast<float>(mass + href_) : h;
}

// The wet/dry pass (while a cell is dry): flags, limiter, then every cell by wet_dry_cell.
// `dry` counts h < h_min, `bad` counts h < 0 or NaN.
void LbmShallow::stream_collide_wet_dry(int& dry, int& bad) {
  exchange_second_rows();  // several ranks: the MUSCL slopes read two rows beyond the slab (halo.cpp)
  flag_supercritical();
  outflow_limiter();
  const WetDryView view = wet_dry_view(theta_.data());
  float* dst = fb_.data();
  float* hnew = hb_.data();
  float* carry = carry_.size() != 0 ? carry_.data() : nullptr;
  const float hmin = hmin_;
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
  int ndry = 0, nbad = 0;
#pragma omp parallel for schedule(static) reduction(+ : ndry, nbad) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) {
      const float h = wet_dry_cell(view, c, dst, carry);
      ndry += h < hmin ? 1 : 0;
      nbad += h >= 0.0f ? 0 : 1;
      hnew[c] = h;
    }
  dry = ndry;
  bad = nbad;
}

}  // namespace huygens
