#!/usr/bin/env python3
"""The Kelvin wake angle measured from a field: a hull at Froude 0.4 on calm deep water, stepped by
the Huygens solver, its wake's outer half-angle read from sim.field("eta") with NumPy.

    python3 examples/kelvin_angle.py [--n 256] [--plot wake.png]

The shipped kelvin scene's hull (1 m long, 0.3 m beam, 5 cm draft, U = 1.253 m/s, Fr = U / sqrt(g L)
= 0.4) on an n x n grid of 0.1 m cells, started at x = 4 m on calm water and run 14.3 s
(D = 17.9 m). Behind a moving source in deep water every wave of the steady pattern satisfies
k.U = omega(k); its rays fill a wedge whose half-angle is arcsin(1/3) = 19.47 deg at any speed
(Kelvin 1887; huygens.reference.kelvin_cusp_angle_deg). Near that edge the wake is an Airy caustic.

The measurement (the method of `huygens validate kelvin`, validation/.../reference/kelvin.hpp,
written out here in NumPy):
 1. the analytic signal a = IFFT[2 FFT(eta) on the half-plane k.d > 0] (d the ship's heading): |a|
    is the wave envelope without the carrier;
 2. on lateral profiles at distances s behind the hull (3 transverse wavelengths to D/2, where the
    pattern is steady: the cusp waves recede from the hull at 2/3 U), the outermost lobe of |a| (at
    least 15 % of the profile's largest) and the point on its outer flank where |a| falls to
    Ai(0) / max Ai = 0.6628 of the lobe: there the Airy function's caustic line lies;
 3. a straight line n_c(s) = s tan(psi) + b through those points on each side; psi is the angle.
Asserted: |psi - psi_K| <= 0.5 deg, the validation's tolerance (its test asserts it at this
n = 256, 10 cells per transverse wavelength), psi_K the cusp angle of gravity-capillary waves at U
(19.51 deg; 19.47 without capillarity). The library's own measurement
(huygens.reference.measure_kelvin_wake) is printed beside it. Measured: 19.60 deg at n = 256 (the
library 19.60), 19.42 at n = 512 (the library 19.47, which ends its profiles where they leave the
grid). --plot FILE draws the field, the caustic points and the 19.47 deg lines.
"""
import argparse
import math
import sys

import numpy as np

import huygens
from huygens.reference import kelvin_cusp_angle_deg, kelvin_transverse_wavelength_m, measure_kelvin_wake

TOLERANCE_DEG = 0.5
AIRY_LEVEL = 0.66277  # Ai(0) / max Ai
LOBE_FRACTION = 0.15


def kelvin_scene(n):
    scene = huygens.scene("kelvin")
    length = 0.1 * n
    scene["grid"] = {"n": n, "length_m": length, "margin": max(16, n // 10)}
    ship = scene["ships"][0]
    speed = math.hypot(ship["path"][1]["x_m"] - ship["path"][0]["x_m"], 0.0) / ship["path"][1]["t_s"]
    start, travel = 4.0, length - 7.6  # the hull ends 3.6 m before the far edge
    ship["path"] = [{"t_s": 0.0, "x_m": start, "y_m": length / 2},
                    {"t_s": travel / speed, "x_m": start + travel, "y_m": length / 2}]
    return scene, speed, travel


def envelope(eta, dx, heading):
    """|a|: the analytic signal's modulus, waves travelling along k.d > 0 kept and doubled."""
    ky = np.fft.fftfreq(eta.shape[0], dx)[:, None]
    kx = np.fft.fftfreq(eta.shape[1], dx)[None, :]
    kd = kx * math.cos(heading) + ky * math.sin(heading)
    spectrum = np.fft.fft2(eta) * np.where(kd > 0, 2.0, np.where(kd == 0, 1.0, 0.0))
    return np.abs(np.fft.ifft2(spectrum))


def bilinear(field, x, y):
    """field at fractional cell coordinates (x along columns, y along rows)."""
    x0 = np.clip(np.floor(x).astype(int), 0, field.shape[1] - 2)
    y0 = np.clip(np.floor(y).astype(int), 0, field.shape[0] - 2)
    fx, fy = x - x0, y - y0
    return ((1 - fy) * ((1 - fx) * field[y0, x0] + fx * field[y0, x0 + 1])
            + fy * ((1 - fx) * field[y0 + 1, x0] + fx * field[y0 + 1, x0 + 1]))


def caustic_point(profile, n):
    """The outer flank's point of the outermost lobe where |a| falls to AIRY_LEVEL of the lobe."""
    peaks = [i for i in range(1, len(profile) - 1)
             if profile[i] >= profile[i - 1] and profile[i] > profile[i + 1]
             and profile[i] >= LOBE_FRACTION * profile.max()]
    if not peaks:
        return None
    i = peaks[-1]
    target = AIRY_LEVEL * profile[i]
    for j in range(i, len(profile) - 1):
        if profile[j + 1] < target:
            f = (profile[j] - target) / (profile[j] - profile[j + 1])
            return n[j] + f * (n[j + 1] - n[j])
    return None


def wake_angle(eta, dx, x0, ship, s_min, s_max):
    """psi (deg) from the caustic points of both sides, and the points (s, n) of each side."""
    env = envelope(eta, dx, ship["heading_rad"])
    d = np.array([math.cos(ship["heading_rad"]), math.sin(ship["heading_rad"])])
    side = np.array([-d[1], d[0]])
    angles, points = [], {}
    for sign in (1, -1):
        pts = []
        for s in np.arange(s_min, s_max, dx):
            n = np.arange(0.0, s * math.tan(math.radians(30.0)), dx / 2)
            px = ship["x_m"] - s * d[0] + sign * n * side[0]
            py = ship["y_m"] - s * d[1] + sign * n * side[1]
            nc = caustic_point(bilinear(env, (px - x0) / dx, (py - x0) / dx), n)
            if nc is not None:
                pts.append((s, nc))
        pts = np.array(pts)
        if len(pts) < 3:
            sys.exit(f"kelvin_angle: too few profiles ({len(pts)}) on a side: the grid is too small (n >= 256)")
        slope = np.polyfit(pts[:, 0], pts[:, 1], 1)[0]
        angles.append(math.degrees(math.atan(slope)))
        points[sign] = pts
    return float(np.mean(angles)), angles, points


def plot(path, eta, dx, x0, ship, points, psi):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    extent = [x0, x0 + dx * eta.shape[1], x0, x0 + dx * eta.shape[0]]
    lim = np.percentile(np.abs(eta), 99.5)
    fig, ax = plt.subplots(figsize=(8, 4.6))
    ax.imshow(eta, origin="lower", extent=extent, cmap="RdBu_r", vmin=-lim, vmax=lim)
    d = np.array([math.cos(ship["heading_rad"]), math.sin(ship["heading_rad"])])
    side = np.array([-d[1], d[0]])
    for sign, pts in points.items():
        xy = np.array([ship["x_m"], ship["y_m"]])[None, :] - pts[:, :1] * d + sign * pts[:, 1:] * side
        ax.plot(xy[:, 0], xy[:, 1], ".", ms=3, color="k")
    for angle, style in ((19.47, "k--"),):
        for sign in (1, -1):
            s = np.array([0.0, 12.0])
            ax.plot(ship["x_m"] - s * d[0] - sign * s * math.tan(math.radians(angle)) * d[1],
                    ship["y_m"] - s * d[1] + sign * s * math.tan(math.radians(angle)) * d[0], style, lw=0.8)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"Kelvin wake at Fr 0.4: caustic points (dots), measured half-angle {psi:.2f} deg; "
                 f"19.47 deg dashed", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"figure: {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=256, help="cells per side, 0.1 m each (the shipped scene: 512)")
    ap.add_argument("--plot", metavar="FILE", help="write the field with the measured points to FILE (PNG)")
    args = ap.parse_args()

    scene, speed, travel = kelvin_scene(args.n)
    sim = huygens.Simulation(scene, fast_plans=True)
    # to the last step the hull makes at full speed (the path ends inside the step after it)
    dt = scene["time"]["dt_s"]
    sim.run(until_s=dt * (math.floor(scene["ships"][0]["path"][1]["t_s"] / dt) - 1))
    (ship,) = sim.ship_poses()
    meta = sim.meta
    dx, x0 = meta["dx"], meta["visible"]["origin_m"][0]
    eta = sim.field("eta", copy=True)
    wavelength = kelvin_transverse_wavelength_m(speed)
    expected = kelvin_cusp_angle_deg(speed)
    s_min, s_max = 3 * wavelength, travel / 2
    psi, sides, points = wake_angle(eta, dx, x0, ship, s_min, s_max)
    library = measure_kelvin_wake(eta, dx, x0, x0, ship, s_max_m=s_max)
    print(f"Fr {speed / math.sqrt(9.81):.2f}, n = {args.n}, {sim.step_count} steps to t = {sim.time_s:.2f} s; "
          f"profiles {s_min:.1f} to {s_max:.1f} m behind the hull")
    print(f"outer half-angle (NumPy, this script): {psi:.2f} deg (sides {sides[0]:.2f}, {sides[1]:.2f}); "
          f"huygens.reference.measure_kelvin_wake: {library['envelope_angle_deg']:.2f} deg; "
          f"Kelvin: {expected:.2f} deg")
    if args.plot:
        plot(args.plot, eta, dx, x0, ship, points, psi)
    if not abs(psi - expected) <= TOLERANCE_DEG:
        sys.exit(f"kelvin_angle: FAILED: {psi:.2f} deg, {abs(psi - expected):.2f} deg from {expected:.2f}")
    print(f"kelvin_angle: passed: |{psi:.2f} - {expected:.2f}| deg <= {TOLERANCE_DEG}")


if __name__ == "__main__":
    main()
