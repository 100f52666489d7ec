#!/usr/bin/env python3
"""The sunlight a dumped height field lets through onto a flat floor, by counting photons: an
independent check of the viewer's caustics (docs/viz.md, "What the pictures show").

Reads DIR/eta_NNNNNN.npy and DIR/meta.json of `huygens run SCENE --dump DIR` (float32 heights,
m, rows = y, the visible region), sends one parallel ray per sub-sample of every cell (bilinear
heights, central-difference slopes) from the sun through the surface, refracts it by Snell's law
(index 1.333) and histograms where it meets the floor `depth` metres below the rest level. Flat
water gives 1 everywhere (each ray carries the same flux; Fresnel transmission, within 2 % of its
flat value up to slopes of 0.3 at the sun heights used here, is left out). The histogram is
shifted back along the refracted sun ray to the surface point above it, which is where a viewer
standing where the sun is (the pool look puts it there) sees that floor point.
Prints min / mean / max of the light in the window (metres of the grid) and, with --png, writes
the light there (0 black, 2 white). Needs numpy and PIL (/usr/bin/python3).
Example: huygens run kelvin --steps 300 --dump /tmp/k --dump-every 300
         python3 scripts/floor_light.py /tmp/k --step 300 --window 24 28 24.6 26.6
"""
import argparse
import json
import pathlib

import numpy as np

N_WATER = 1.333


def refracted(gx, gy, d):
    """Snell: the refracted direction of the downward ray d at normals (-gx, -gy, 1)/norm."""
    n = np.stack([-gx, -gy, np.ones_like(gx)], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    eta = 1.0 / N_WATER
    cos_i = -(n @ d)
    k = 1.0 - eta**2 * (1.0 - cos_i**2)
    return eta * d + (eta * cos_i - np.sqrt(k))[..., None] * n


def floor_light(eta, dx, depth, d, sub, hull=None):
    """Light on the floor (flat water = 1), in floor cells of size dx, seen from above. `hull`
    (x, y, heading, length, beam relative to cell (0, 0); m, rad) blocks the rays that meet the
    surface inside its waterline ellipse (the ship's shadow, with the hull's height neglected)."""
    rows, cols = eta.shape
    gy, gx = np.gradient(eta, dx)
    f = (np.arange(rows * sub) + 0.5) / sub - 0.5
    i0 = np.clip(np.floor(f).astype(int), 0, rows - 2)
    w = np.clip(f - i0, 0.0, 1.0)
    fj = (np.arange(cols * sub) + 0.5) / sub - 0.5
    j0 = np.clip(np.floor(fj).astype(int), 0, cols - 2)
    wj = np.clip(fj - j0, 0.0, 1.0)

    def up(a):  # bilinear up-sampling to the sub-samples
        r = a[i0] * (1 - w)[:, None] + a[i0 + 1] * w[:, None]
        return r[:, j0] * (1 - wj)[None, :] + r[:, j0 + 1] * wj[None, :]

    e, sx, sy = up(eta), up(gx), up(gy)
    t = refracted(sx, sy, d)
    length = (-depth - e) / t[..., 2]
    x = (fj[None, :] * dx) + length * t[..., 0]
    y = (f[:, None] * dx) + length * t[..., 1]
    flat = refracted(np.zeros(1), np.zeros(1), d)[0]
    shift = -depth / flat[2] * flat[:2]
    ix = np.round((x - shift[0]) / dx).astype(int)
    iy = np.round((y - shift[1]) / dx).astype(int)
    ok = (ix >= 0) & (ix < cols) & (iy >= 0) & (iy < rows)
    if hull is not None:
        hx, hy, heading, length, beam = hull
        u = (fj[None, :] * dx - hx) * np.cos(heading) + (f[:, None] * dx - hy) * np.sin(heading)
        v = -(fj[None, :] * dx - hx) * np.sin(heading) + (f[:, None] * dx - hy) * np.cos(heading)
        ok &= (2 * u / length) ** 2 + (2 * v / beam) ** 2 > 1.0
    light = np.zeros((rows, cols))
    np.add.at(light, (iy[ok], ix[ok]), 1.0 / sub**2)
    return light


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dir", help="dump folder of `huygens run --dump`")
    p.add_argument("--step", type=int, required=True, help="the dumped step NNNNNN")
    p.add_argument("--depth", type=float, default=3.0, help="floor below the rest level (m; the pool look's 3 m)")
    p.add_argument("--elevation", type=float, default=55.0, help="sun elevation (deg; kelvin's start-up view)")
    p.add_argument("--azimuth", type=float, default=-90.0, help="direction towards the sun (deg from +x; -90: -y)")
    p.add_argument("--window", type=float, nargs=4, metavar=("X0", "X1", "Y0", "Y1"), help="report window (m)")
    p.add_argument("--hull", type=float, nargs=5, metavar=("X", "Y", "HEADING", "LENGTH", "BEAM"),
                   help="a ship's waterline ellipse that shades the surface (m, deg)")
    p.add_argument("--sub", type=int, default=4, help="rays per cell along each axis")
    p.add_argument("--png", help="write the window's light as a grey image (2 = white)")
    a = p.parse_args()
    folder = pathlib.Path(a.dir)
    meta = json.loads((folder / "meta.json").read_text())
    eta = np.load(folder / f"eta_{a.step:06d}.npy").astype(float)
    dx = meta["dx"]
    x0, y0 = meta["visible"]["origin_m"]
    el, az = np.radians(a.elevation), np.radians(a.azimuth)
    d = -np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    hull = None
    if a.hull:
        hx, hy, heading, length, beam = a.hull
        hull = (hx - x0, hy - y0, np.radians(heading), length, beam)
    light = floor_light(eta, dx, a.depth, d, a.sub, hull)
    X0, X1, Y0, Y1 = a.window or (x0, x0 + eta.shape[1] * dx, y0, y0 + eta.shape[0] * dx)
    c0, c1 = int((X0 - x0) / dx), int(np.ceil((X1 - x0) / dx))
    r0, r1 = int((Y0 - y0) / dx), int(np.ceil((Y1 - y0) / dx))
    win = light[r0:r1, c0:c1]
    print(f"light seen through the surface, x {X0:g}..{X1:g} m, y {Y0:g}..{Y1:g} m, floor {a.depth:g} m down, "
          f"sun {a.elevation:g} deg up at azimuth {a.azimuth:g} deg: min {win.min():.3f}, mean {win.mean():.3f}, "
          f"max {win.max():.3f} (flat water 1)")
    if a.png:
        from PIL import Image
        img = np.clip(win[::-1] / 2.0, 0, 1) * 255  # north up
        Image.fromarray(img.astype(np.uint8)).resize((win.shape[1] * 4, win.shape[0] * 4), Image.NEAREST).save(a.png)
        print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
