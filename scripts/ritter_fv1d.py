#!/usr/bin/env python3
"""Ritter's dry-bed dam break with a plain 1D finite-volume scheme (no lattice), for comparison
with the LBM solver's wet/dry pass (docs/lbm.md, "The front of a dam break onto a dry bed").

The scheme is the one the wet/dry pass uses on its HLL faces, in one dimension: MUSCL-Hancock
(van Leer 1979; Toro 2001 sec. 14.4) with minmod slopes of depth and velocity, first order on a
face with a dry side, HLL fluxes (Harten, Lax and van Leer 1983) with Davis's wave speeds and
the dry-bed speeds u - c, u + 2c (Toro 2001), a cell below min_depth dry (velocity 0, no exchange
with another dry cell). Same setup as lbm_ritter: 100 m, h0 = 1 m left of the dam at a third,
walls, dt = cfl dx / (2 sqrt(g h0)), run until the head is 0.1 of the way from the wall.

Prints the last wet cell's face against where the exact depth falls to 1e-4 m, the point where
the depth falls to 0.01 h0 (as lbm_ritter), the L1 depth error and the volume change. Options
change one ingredient at a time (the exact Riemann solver, the slope limiter, the reconstructed
variables, the last wet cell's slopes, a front velocity along the invariant u + 2c, a sub-cell
front in the last wet cell: --front, see front_faces), start from the exact state at t_s, or
compute the first t_s on an r times finer grid. --lake N runs N steps of a still lake with dry
shores on a curved bed instead (the surface is reconstructed and the faces use the hydrostatic
reconstruction, so the lake must stay still with every --front that describes the water behind by
its surface). Needs numpy (/usr/bin/python3).
Example: python3 scripts/ritter_fv1d.py --cells 1024 --start 2
"""
import argparse

import numpy as np

G = 9.81
H0 = 1.0
C0 = np.sqrt(G * H0)


def minmod(a, b):
    return np.where(a * b <= 0, 0.0, np.where(abs(a) < abs(b), a, b))


def mc(a, b):
    return np.where(a * b <= 0, 0.0, np.sign(a) * np.minimum(np.minimum(2 * abs(a), 2 * abs(b)), 0.5 * abs(a + b)))


def superbee(a, b):
    s, aa, bb = np.sign(a), abs(a), abs(b)
    return np.where(a * b <= 0, 0.0, s * np.maximum(np.minimum(2 * aa, bb), np.minimum(aa, 2 * bb)))


LIMITERS = {"minmod": minmod, "mc": mc, "superbee": superbee}


def flux(h, u):
    return h * u, h * u * u + 0.5 * G * h * h


def exact(x, t):
    """Ritter's depth and velocity at x (m from the dam), t > 0."""
    s = 2 * C0 - x / t
    fan = (x > -C0 * t) & (x < 2 * C0 * t)
    h = np.where(x <= -C0 * t, H0, np.where(fan, s * s / (9 * G), 0.0))
    return h, np.where(fan, 2 * (C0 + x / t) / 3, 0.0)


def hll(hl, ul, hr, ur, wl, wr):
    cl, cr = np.sqrt(G * hl), np.sqrt(G * hr)
    sl, sr = np.minimum(ul - cl, ur - cr), np.maximum(ul + cl, ur + cr)
    sl, sr = np.where(~wr, ul - cl, sl), np.where(~wr, ul + 2 * cl, sr)
    sl, sr = np.where(~wl, ur - 2 * cr, sl), np.where(~wl, ur + cr, sr)
    ml, pl = flux(hl, ul)
    mr, pr = flux(hr, ur)
    d = np.where(sr - sl == 0, 1.0, sr - sl)
    m = np.where(sl >= 0, ml, np.where(sr <= 0, mr, (sr * ml - sl * mr + sl * sr * (hr - hl)) / d))
    p = np.where(sl >= 0, pl, np.where(sr <= 0, pr, (sr * pl - sl * pr + sl * sr * (hr * ur - hl * ul)) / d))
    return m, p


def _f(hs, hk):  # the depth function of the exact solver (Toro 2001 ch. 5)
    shock = (hs - hk) * np.sqrt(0.5 * G * (hs + hk) / np.maximum(hs * hk, 1e-300))
    return np.where(hs > hk, shock, 2 * (np.sqrt(G * hs) - np.sqrt(G * hk)))


def _side(h, u, hs, us, sign):  # the state at x/t = 0 on one side of the contact
    c, cs = np.sqrt(G * h), np.sqrt(G * hs)
    s = u + sign * c * np.sqrt(0.5 * (hs + h) * hs / np.maximum(h * h, 1e-300))
    if sign < 0:
        fan = ((u + 2 * c) / 3) ** 2 / G, (u + 2 * c) / 3
        return (np.where(hs > h, np.where(s >= 0, h, hs), np.where(u - c >= 0, h, np.where(us - cs <= 0, hs, fan[0]))),
                np.where(hs > h, np.where(s >= 0, u, us), np.where(u - c >= 0, u, np.where(us - cs <= 0, us, fan[1]))))
    fan = ((2 * c - u) / 3) ** 2 / G, (u - 2 * c) / 3
    return (np.where(hs > h, np.where(s <= 0, h, hs), np.where(u + c <= 0, h, np.where(us + cs >= 0, hs, fan[0]))),
            np.where(hs > h, np.where(s <= 0, u, us), np.where(u + c <= 0, u, np.where(us + cs >= 0, us, fan[1]))))


def godunov(hl, ul, hr, ur, wl, wr):
    """Flux of the exact Riemann solution sampled at x/t = 0 (dry sides: one rarefaction)."""
    cl, cr = np.sqrt(G * hl), np.sqrt(G * hr)
    h = np.zeros_like(hl)
    u = np.zeros_like(hl)
    m = wl & ~wr  # rarefaction into the dry right side
    fan_h, fan_u = ((ul + 2 * cl) / 3) ** 2 / G, (ul + 2 * cl) / 3
    h = np.where(m, np.where(ul - cl >= 0, hl, np.where(ul + 2 * cl <= 0, 0, fan_h)), h)
    u = np.where(m, np.where(ul - cl >= 0, ul, np.where(ul + 2 * cl <= 0, 0, fan_u)), u)
    m = ~wl & wr
    fan_h, fan_u = ((2 * cr - ur) / 3) ** 2 / G, (ur - 2 * cr) / 3
    h = np.where(m, np.where(ur + cr <= 0, hr, np.where(ur - 2 * cr >= 0, 0, fan_h)), h)
    u = np.where(m, np.where(ur + cr <= 0, ur, np.where(ur - 2 * cr >= 0, 0, fan_u)), u)
    w = wl & wr
    if w.any():
        a, b, c, d = hl[w], ul[w], hr[w], ur[w]
        hs = np.maximum((0.5 * (np.sqrt(G * a) + np.sqrt(G * c)) + 0.25 * (b - d)) ** 2 / G, 1e-12)
        for _ in range(30):  # Newton with a numerical derivative
            f = _f(hs, a) + _f(hs, c) + d - b
            e = 1e-7 * hs
            hs = np.maximum(hs - f * e / (_f(hs + e, a) + _f(hs + e, c) + d - b - f), 1e-14)
        us = 0.5 * (b + d) + 0.5 * (_f(hs, c) - _f(hs, a))
        left, right = _side(a, b, hs, us, -1), _side(c, d, hs, us, +1)
        h[w] = np.where(us >= 0, left[0], right[0])
        u[w] = np.where(us >= 0, left[1], right[1])
    return flux(h, u)


def front_faces(hbar, behind, dx, kind):
    """Depth at the inner and outer face of a front cell (wet, a wet cell behind it, a dry one
    ahead) of mean depth hbar, the water taken to occupy only part of the cell where the profile
    says so, its extent from mass (the profile's mean over the cell is hbar). `behind`: the surface
    drop per cell of the water behind ("slope"), the drop of sqrt(g h) per cell ("fan"), or the
    surface at the inner face of the cell behind minus the front cell's bed ("cont", "fancont").
    "bckn": flat surface, as Bollermann, Chen, Kurganov & Noelle (2013, sec. 3) take it in a
    partially flooded cell; on a flat bed that is the whole cell at hbar, i.e. the default scheme.
    "slope": h = h_in - s xi (xi from the inner face) with the surface slope s of the water behind,
    cut at 0: h_in = hbar + s dx / 2 if h_out = hbar - s dx / 2 >= 0, else a wedge of length
    L = sqrt(2 hbar dx / s), h_in = s L, h_out = 0. "cont": h_in = max(behind, hbar) (the surface
    continuous at the inner face), linear: h_out = 2 hbar - h_in if >= 0, else a wedge of length
    L = 2 hbar dx / h_in. "fancont": c = sqrt(g h) linear instead (the shape of a simple wave's
    tip, h ~ (x_f - x)^2), c_in continuous: c_out = (sqrt(12 g hbar - 3 c_in^2) - c_in) / 2 if
    >= 0, else a tip of length L = 3 hbar dx / h_in. "fan": c linear with the slope k of c behind:
    c_in = k dx / 2 + sqrt(g hbar - k^2 dx^2 / 12) if c_out = c_in - k dx >= 0, else a tip of
    length L = (3 g hbar dx / k^2)^(1/3), c_in = k L (depth, not surface: flat bed only)."""
    h_in, h_out = hbar.copy(), hbar.copy()
    if kind == "slope":
        s = np.maximum(behind, 0.0) / dx
        full = hbar >= 0.5 * s * dx
        ss = np.where(s > 0, s, 1.0)
        L = np.sqrt(2 * hbar * dx / ss)
        h_in = np.where(s <= 0, hbar, np.where(full, hbar + 0.5 * s * dx, ss * L))
        h_out = np.where(s <= 0, hbar, np.where(full, hbar - 0.5 * s * dx, 0.0))
    elif kind == "cont":
        hi = np.maximum(behind, hbar)
        full = hi <= 2 * hbar
        h_in, h_out = hi, np.where(full, 2 * hbar - hi, 0.0)
    elif kind == "fancont":
        ci = np.sqrt(G * np.maximum(behind, hbar))
        full = G * hbar >= ci * ci / 3
        c_out = np.where(full, 0.5 * (np.sqrt(np.maximum(12 * G * hbar - 3 * ci * ci, 0.0)) - ci), 0.0)
        h_in, h_out = ci * ci / G, c_out * c_out / G
    elif kind == "fan":
        k = np.maximum(behind, 0.0) / dx
        kk = np.where(k > 0, k, 1.0)
        full = G * hbar >= kk * kk * dx * dx / 3
        c_full = 0.5 * kk * dx + np.sqrt(np.maximum(G * hbar - kk * kk * dx * dx / 12, 0.0))
        L = np.cbrt(3 * G * hbar * dx / (kk * kk))
        c_in = np.where(full, c_full, kk * L)
        c_out = np.where(full, c_full - kk * dx, 0.0)
        h_in = np.where(k <= 0, hbar, c_in * c_in / G)
        h_out = np.where(k <= 0, hbar, c_out * c_out / G)
    return h_in, h_out


def front_states(hg, ug, zg, wet, hp, hm, tip, tipl, a):
    """Depths at the faces of the front cells (tip: dry on the right, tipl: dry on the left) from
    front_faces; every array but hp, hm (cells -1..n) has the two ghosts each side. The water
    behind is described by its surface (depth + bed), so that a still lake keeps a flat surface
    (all but "fan", which takes the slope of sqrt(g h) and needs a flat bed)."""
    hc, zc = hg[1:-1], zg[1:-1]
    eta = hg + zg
    sg = np.sqrt(G * hg)
    for t, d in ((tip, 1), (tipl, -1)):
        back = lambda v, k=1: np.roll(v, k * d)[1:-1]  # the value k cells behind the front cell
        if a.front in ("cont", "fancont"):  # the surface at the inner face of the cell behind
            face = np.concatenate(([0], hp if d > 0 else hm, [0])) + zg
            behind, ok2 = back(face) - zc, np.ones_like(t)
        elif a.front == "fan":
            behind, ok2 = back(sg, 2) - back(sg), back(wet, 2)
        else:
            behind, ok2 = (back(eta, 2) - back(eta)) * (a.front == "slope"), back(wet, 2)
        h_in, h_out = front_faces(hc, np.where(ok2, behind, 0.0), 1.0, a.front)  # lengths in cells
        if d > 0:
            hp, hm = np.where(t, h_out, hp), np.where(t, h_in, hm)
        else:
            hm, hp = np.where(t, h_out, hm), np.where(t, h_in, hp)
    return hp, hm


def step(h, q, lam, a, z=None):
    """One MUSCL-Hancock step of the cell averages h, q (walls at both ends) over the bed z (one
    height per cell, m; flat if None): the surface h + z is reconstructed and the faces use the
    hydrostatic reconstruction of Audusse, Bouchut, Bristeau, Klein & Perthame (2004), so a still
    lake stays still; with z = 0 every number is that of the flat-bed scheme."""
    lim = LIMITERS[a.limiter]
    u = np.where(h >= a.min_depth, q / np.maximum(h, 1e-300), 0.0)
    z = np.zeros_like(h) if z is None else z
    hg = np.concatenate(([h[0], h[0]], h, [h[-1], h[-1]]))
    zg = np.concatenate(([z[0], z[0]], z, [z[-1], z[-1]]))
    ug = np.concatenate(([-u[0], -u[0]], u, [-u[-1], -u[-1]]))
    wet = hg >= a.min_depth
    cg = np.sqrt(G * hg)
    va, vb = {"hu": (hg + zg, ug), "cu": (cg, ug), "inv": (ug + 2 * cg, ug - 2 * cg)}[a.recon]
    dal, dar, dbl, dbr = va[1:-1] - va[:-2], va[2:] - va[1:-1], vb[1:-1] - vb[:-2], vb[2:] - vb[1:-1]
    sa, sb = 0.5 * lim(dal, dar), 0.5 * lim(dbl, dbr)
    ok = wet[1:-1] & wet[:-2] & wet[2:]
    sa, sb = np.where(ok, sa, 0), np.where(ok, sb, 0)
    tip = wet[1:-1] & wet[:-2] & ~wet[2:]
    if a.tip_onesided:  # the last wet cell takes the difference with the cell behind it
        sa, sb, ok = np.where(tip, 0.5 * dal, sa), np.where(tip, 0.5 * dbl, sb), ok | tip

    def to_hu(x, y):
        if a.recon == "hu":
            return np.maximum(x - zg[1:-1], 0), y
        if a.recon == "cu":
            return np.maximum(x, 0) ** 2 / G, y
        c = np.maximum((x - y) / 4, 0)
        return c * c / G, (x + y) / 2

    hp, up = to_hu(va[1:-1] + sa, vb[1:-1] + sb)
    hm, um = to_hu(va[1:-1] - sa, vb[1:-1] - sb)
    tipl = wet[1:-1] & wet[2:] & ~wet[:-2]  # front cells facing left
    if a.front != "none" and a.front_hancock:  # the front cell's faces evolved a half step as any cell's
        hp, hm = front_states(hg, ug, zg, wet, hp, hm, tip, tipl, a)
        up, um = np.where(tip | tipl, ug[1:-1], up), np.where(tip | tipl, ug[1:-1], um)
    mp, pp = flux(hp, up)
    mm, pm = flux(hm, um)
    hp2, hm2 = hp - 0.5 * lam * (mp - mm), hm - 0.5 * lam * (mp - mm)
    qp2, qm2 = hp * up - 0.5 * lam * (pp - pm), hm * um - 0.5 * lam * (pp - pm)
    okh = (hp2 > a.min_depth) & (hm2 > a.min_depth) & ok
    if a.front != "none" and a.front_hancock:
        okh = okh | ((tip | tipl) & (hp2 >= 0) & (hm2 >= 0))
    up = np.where(okh, qp2 / np.maximum(hp2, 1e-300), up)
    um = np.where(okh, qm2 / np.maximum(hm2, 1e-300), um)
    hp, hm = np.where(okh, hp2, hp), np.where(okh, hm2, hm)
    if a.front != "none" and not a.front_hancock:
        hp, hm = front_states(hg, ug, zg, wet, hp, hm, tip, tipl, a)
        up, um = np.where(tip | tipl, ug[1:-1], up), np.where(tip | tipl, ug[1:-1], um)
    hl, ul, hr, ur = hp[:-1], up[:-1], hm[1:], um[1:]
    wl, wr = wet[1:-2], wet[2:-1]
    first = ~(wl & wr)
    if a.front != "none":  # the front cell's own face values at its dry face and the one behind
        fr, fl = tip[:-1], tipl[1:]
        keep_l, keep_r = fr & ~wr, fl & ~wl
        hl0, ul0, hr0, ur0 = hl, ul, hr, ur
    if a.tip_onesided:
        first = first & ~(wl & ~wr)
    hl, ul = np.where(first, hg[1:-2], hl), np.where(first, ug[1:-2], ul)
    hr, ur = np.where(first | ~wr, hg[2:-1], hr), np.where(first | ~wr, ug[2:-1], ur)
    if a.front != "none":
        hl, ul = np.where(keep_l, hl0, hl), np.where(keep_l, ul0, ul)
        hr, ur = np.where(keep_r, hr0, hr), np.where(keep_r, ur0, ur)
    if a.order == 1:
        hl, ul, hr, ur = hg[1:-2], ug[1:-2], hg[2:-1], ug[2:-1]
    ul, ur = np.where(wl, ul, 0), np.where(wr, ur, 0)
    zs = np.maximum(zg[1:-2], zg[2:-1])  # hydrostatic reconstruction (Audusse et al. 2004, eq. 2.9)
    hl_s, hr_s = np.maximum(hl + zg[1:-2] - zs, 0.0), np.maximum(hr + zg[2:-1] - zs, 0.0)
    dpl, dpr = 0.5 * G * (hl * hl - hl_s * hl_s), 0.5 * G * (hr * hr - hr_s * hr_s)
    hl, hr = hl_s, hr_s
    fm, fp = (godunov if a.riemann == "exact" else hll)(hl, ul, hr, ur, wl, wr)
    if a.riemann == "hll-drybed":  # the exact dry-bed solution (closed form) where one side is dry
        gm, gp = godunov(hl, ul, hr, ur, wl & ~wr, wr & ~wl)
        fm, fp = np.where(wl & wr, fm, gm), np.where(wl & wr, fp, gp)
    dry = ~wl & ~wr
    fm, fp = np.where(dry, 0, fm), np.where(dry, 0, fp)
    fm[0] = fm[-1] = 0.0  # walls: no mass through, the momentum flux of the mirrored ghost
    h = np.maximum(h - lam * (fm[1:] - fm[:-1]), 0.0)
    q = q - lam * ((fp + dpl)[1:] - (fp + dpr)[:-1])  # the bed's pressure on each side (eq. 2.10)
    if a.tip_invariant > 0:  # u >= (u + 2c) of the cell behind - 2c in the last K wet cells
        w = np.nonzero(h >= a.min_depth)[0]
        for i in range(w.max() - a.tip_invariant + 1, w.max() + 1):
            if h[i - 1] >= a.min_depth and h[i] >= a.min_depth:
                inv = q[i - 1] / h[i - 1] + 2 * np.sqrt(G * h[i - 1])
                q[i] = h[i] * max(q[i] / h[i], inv - 2 * np.sqrt(G * h[i]))
    return h, q


def run(a):
    n, dx = a.cells, 100.0 / a.cells
    dt = a.cfl * dx / (2 * C0)
    dam = n // 3
    x0 = dam * dx
    steps = int(round(0.9 * x0 / C0 / dt))
    first = int(np.ceil(a.start / dt - 1e-9)) if a.start > 0 else 0
    if first > 0 and a.refine > 1:  # the first steps on an r times finer grid, then averaged
        r = a.refine
        h, q = np.zeros(n * r), np.zeros(n * r)
        h[: dam * r] = H0
        for _ in range(first * r):
            h, q = step(h, q, dt / dx, a)
        h, q = h.reshape(n, r).mean(1), q.reshape(n, r).mean(1)
    elif first > 0:  # the exact state, cell averages over 64 sub-samples
        xs = (np.arange(n)[:, None] + (np.arange(64)[None, :] + 0.5) / 64) * dx - x0
        he, ue = exact(xs, first * dt)
        h, q = he.mean(1), (he * ue).mean(1)
    else:
        h, q = np.where(np.arange(n) < dam, H0, 0.0), np.zeros(n)
    q, h = np.where(h < a.min_depth, 0, q), np.where(h < a.min_depth, 0, h)
    vol = h.sum()
    for _ in range(first, steps):
        h, q = step(h, q, dt / dx, a)
    t = steps * dt
    front = (np.nonzero(h >= 1e-4)[0].max() + 1) * dx - x0
    target = (2 * C0 - 3 * np.sqrt(G * 1e-4)) * t
    he, _ = exact((np.arange(n) + 0.5) * dx - x0, t)
    l1 = np.abs(h - he).sum() / he.sum()
    c = np.nonzero((h[:-1] >= 0.01) & (h[1:] < 0.01))[0].max() + 1  # as lbm_ritter: last crossing of 0.01 h0
    x01 = (c - 0.5 + (h[c - 1] - 0.01) / (h[c - 1] - h[c])) * dx - x0
    x01e = (2 * C0 - 3 * np.sqrt(G * 0.01)) * t
    print(f"{a.cells} cells, {steps} steps, t = {t:.3f} s: last wet cell's face {front:.3f} m, exact h = 1e-4 m "
          f"at {target:.3f} m, error {100 * (front - target) / target:+.2f} % ({(target - front) / dx:.1f} cells); "
          f"h = 0.01 h0 at {x01:.3f} m ({100 * (x01 - x01e) / x01e:+.2f} %); L1 {l1:.2e}; "
          f"volume change {(h.sum() - vol) / vol:+.1e}")


def run_lake(a):
    """A still lake in a bowl with dry shores on both sides (bed z = ((x - 50 m) / 40 m)^2, surface
    0.5 m, shores at 50 -+ 28.3 m), a.steps steps: it must stay still (velocity and surface change to
    round-off) and keep its volume."""
    n, dx = a.cells, 100.0 / a.cells
    x = (np.arange(n) + 0.5) * dx
    z = ((x - 50.0) / 40.0) ** 2
    h = np.maximum(0.5 - z, 0.0)
    h = np.where(h < a.min_depth, 0.0, h)
    q = np.zeros(n)
    vol = h.sum()
    lam = a.cfl / (2 * C0)  # dt / dx with the Ritter case's dt
    for _ in range(a.lake):
        h, q = step(h, q, lam, a, z)
    w = h >= a.min_depth
    print(f"still lake, {n} cells, {a.lake} steps: max |u| {np.abs(q[w] / h[w]).max():.1e} m/s, max |surface - 0.5 m| "
          f"{np.abs(h[w] + z[w] - 0.5).max():.1e} m, wet cells {w.sum()} (at start {(np.maximum(0.5 - z, 0) >= a.min_depth).sum()}), "
          f"volume change {(h.sum() - vol) / vol:+.1e}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--cells", type=int, default=1024)
    p.add_argument("--cfl", type=float, default=0.5, help="dt = cfl dx / (2 sqrt(g h0))")
    p.add_argument("--min-depth", type=float, default=1e-4, help="dry threshold of the scheme (m)")
    p.add_argument("--order", type=int, default=2, choices=(1, 2))
    p.add_argument("--riemann", default="hll", choices=("hll", "exact", "hll-drybed"))
    p.add_argument("--limiter", default="minmod", choices=sorted(LIMITERS))
    p.add_argument("--recon", default="hu", choices=("hu", "cu", "inv"),
                   help="slopes of depth and u, of sqrt(g h) and u, or of u +- 2 sqrt(g h)")
    p.add_argument("--tip-onesided", action="store_true", help="one-sided slopes in the last wet cell")
    p.add_argument("--tip-invariant", type=int, default=0, metavar="K",
                   help="front velocity along u + 2c in the last K wet cells")
    p.add_argument("--front", default="none", choices=("none", "bckn", "slope", "cont", "fan", "fancont"),
                   help="sub-cell wet/dry front in the last wet cell (see front_faces)")
    p.add_argument("--front-hancock", action="store_true",
                   help="with --front: the front cell's face states take the Hancock half step too")
    p.add_argument("--start", type=float, default=0.0, help="start from the exact state at this time (s)")
    p.add_argument("--refine", type=int, default=1, help="with --start: compute up to it r times finer")
    p.add_argument("--lake", type=int, default=0, metavar="STEPS",
                   help="instead of Ritter: a still lake with dry shores on a curved bed for STEPS steps")
    a = p.parse_args()
    if a.lake > 0 and a.recon != "hu":
        p.error("--lake needs --recon hu (the surface is what stays flat)")
    run_lake(a) if a.lake > 0 else run(a)


if __name__ == "__main__":
    main()
