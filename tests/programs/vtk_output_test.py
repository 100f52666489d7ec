#!/usr/bin/env python3
"""`huygens run --dump-format both` writes VTK files that VTK's own readers read back equal to the
.npy dumps of the same run (docs/design.md 6, "ParaView output").

    vtk_output_test.py --cli PATH

Runs a small SPH, LBM and Huygens scene (the Huygens one with interpolated display frames) and
for every dump reads each .vti with vtkXMLImageDataReader and each .vtu with
vtkXMLUnstructuredGridReader (Debian's python3-vtk9), compares every value with the .npy of the
same field and step (exactly: both are float32), the .vti's spacing and origin with meta.json's
"dx" and "visible"/"origin_m", and the DataSets of run.pvd (parsed as XML: VTK 9.1 has no .pvd
reader, ParaView has) with meta.json's times. A negative control changes one value in a copy of a
.vti and expects the comparison to find it; a run with --dump-format vtk writes the same VTK files
and no .npy. Exits 77 (skipped) only when VTK's Python package cannot be imported.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLUnstructuredGridReader
except ImportError as e:
    print(f"SKIP: NumPy or VTK's Python package is not importable by {sys.executable} ({e}); "
          "scripts/install-deps.sh installs Debian's python3-numpy and python3-vtk9 for /usr/bin/python3")
    sys.exit(77)

FAILURES = []
TOTALS = {"values": 0, "arrays": 0, "files": 0, "max_diff": 0.0}
NONZERO = {}  # field name -> whether any dump had a value other than 0 (a test of all zeros proves little)

SPH = {"solver": "sph", "sph": {
    "spacing_m": 0.01, "container_m": [0.12, 0.08, 0.1],
    "fluid": [{"min_m": [0.0, 0.0, 0.0], "max_m": [0.05, 0.08, 0.06]}],
    "time": {"dt_max_s": 0.001}, "surface": {"cell_m": 0.005}}}
LBM = {"solver": "lbm", "lbm": {
    "grid": {"cols": 40, "rows": 24, "cell_m": 0.5}, "time": {"cfl": 0.5},
    "water": {"gravity_mps2": 9.81, "viscosity_m2s": 0.2},
    "bed": {"type": "bump", "x_m": 14.0, "half_width_m": 3.0, "height_m": 0.3},
    "initial": {"dam": {"x_m": 8.0, "left_depth_m": 2.0, "right_depth_m": 1.0}},
    "boundaries": {"left": "wall", "right": "wall", "bottom": "wall", "top": "wall"}}}
HUYGENS = {"solver": "huygens", "grid": {"n": 64, "length_m": 4.0, "margin": 8},
           "time": {"dt_s": 0.05, "display_per_step": 3}, "stokes": True,
           "initial": [{"type": "gaussian", "x_m": 1.5, "y_m": 2.5, "sigma_m": 0.2, "amplitude_m": 0.01}]}


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        FAILURES.append(what)


def read(reader_class, path):
    r = reader_class()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def differences(vtk_values, npy_values, components):
    """The values that differ (the components past the .npy's, VTK's 3D padding, must be 0) and the
    largest difference; counts the .npy values compared."""
    a = vtk_to_numpy(vtk_values).reshape(-1, vtk_values.GetNumberOfComponents())
    b = npy_values.reshape(a.shape[0], components)
    if a.shape[1] < components:
        return a.size + b.size, float("inf")
    diff = np.abs(a[:, :components].astype(np.float64) - b.astype(np.float64))
    bad = int(np.count_nonzero(diff)) + int(np.count_nonzero(a[:, components:]))
    TOTALS["values"] += b.size
    TOTALS["arrays"] += 1
    NONZERO[vtk_values.GetName()] = NONZERO.get(vtk_values.GetName(), False) or bool(np.any(b))
    worst = float(max(diff.max(initial=0.0), np.abs(a[:, components:]).max(initial=0.0)))
    TOTALS["max_diff"] = max(TOTALS["max_diff"], worst)
    return bad, worst


def compare_point_data(data, npys, label, point_ndim):
    """Every point-data array of `data` equals the .npy of its name; the names are the .npy's. An
    .npy of `point_ndim` + 1 dimensions has shape[-1] values per point."""
    pd = data.GetPointData()
    names = sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays()))
    check(names == sorted(npys), f"{label}: arrays {names} are the .npy fields {sorted(npys)}")
    for name in names:
        if name not in npys:
            continue
        npy = npys[name]
        components = npy.shape[-1] if npy.ndim > point_ndim else 1
        bad, worst = differences(pd.GetArray(name), npy, components)
        check(bad == 0, f"{label}: {name} {npy.shape} equals the .npy ({bad} differ, max |diff| {worst:g})")


def check_vti(path, npys, meta):
    img = read(vtkXMLImageDataReader, path)
    rows, cols = next(iter(npys.values())).shape[:2]
    label = os.path.basename(path)
    check(tuple(img.GetDimensions()) == (cols, rows, 1), f"{label}: {img.GetDimensions()} points = (cols, rows, 1)")
    dx, (x0, y0) = meta["dx"], meta["visible"]["origin_m"]
    check(tuple(img.GetSpacing())[:2] == (dx, dx) and tuple(img.GetOrigin()) == (x0, y0, 0.0),
          f"{label}: spacing {img.GetSpacing()[:2]}, origin {img.GetOrigin()} = meta.json's dx {dx}, origin ({x0}, {y0}, 0)")
    compare_point_data(img, npys, label, 2)


def check_vtu(path, npys):
    grid = read(vtkXMLUnstructuredGridReader, path)
    label = os.path.basename(path)
    n = npys["pos"].shape[0]
    bad, worst = differences(grid.GetPoints().GetData(), npys["pos"], 3)
    check(grid.GetNumberOfPoints() == n and bad == 0,
          f"{label}: {grid.GetNumberOfPoints()} points equal pos {npys['pos'].shape} (max |diff| {worst:g})")
    types = vtk_to_numpy(grid.GetCellTypesArray())
    check(grid.GetNumberOfCells() == n and bool(np.all(types == 1)), f"{label}: one vertex cell per particle")
    compare_point_data(grid, {k: v for k, v in npys.items() if k != "pos"}, label, 1)


def check_dumps(folder):
    """Every dump's VTK files against its .npy files; returns the (time, part, file) run.pvd should list."""
    with open(os.path.join(folder, "meta.json")) as f:
        meta = json.load(f)
    expected = []
    for dump in meta["dumps"]:
        npys = {}
        for name in dump["files"]:
            if name.endswith(".npy"):
                npys[name[:name.index("_")]] = np.load(os.path.join(folder, name))
        particle = {k: v for k, v in npys.items() if k in ("pos", "vel", "density", "pressure")}
        grid = {k: v for k, v in npys.items() if k not in particle}
        vtk_files = [n for n in dump["files"] if n.endswith((".vti", ".vtu"))]
        check(len(vtk_files) == (1 if grid else 0) + (1 if particle else 0),
              f"step {dump['step']} (index {dump['index']}): meta.json lists its VTK files {vtk_files}")
        for name in vtk_files:
            TOTALS["files"] += 1
            path = os.path.join(folder, name)
            check_vti(path, grid, meta) if name.endswith(".vti") else check_vtu(path, particle)
            expected.append((dump["time_s"], 1 if name.endswith(".vtu") else 0, name))
    return meta, expected


def check_pvd(folder, expected):
    root = ET.parse(os.path.join(folder, "run.pvd")).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "Collection", "run.pvd is a VTKFile of type Collection")
    listed = [(float(d.get("timestep")), int(d.get("part")), d.get("file")) for d in root.iter("DataSet")]
    check(listed == expected, f"run.pvd lists the {len(expected)} VTK files of meta.json with their times and parts")
    names = [d.get("name") for d in root.iter("DataSet")]
    check(names == [("particles" if p else "grid") for _, p, _ in listed], "run.pvd names part 0 grid, 1 particles")
    times = sorted({t for t, _, _ in listed})
    check(len(times) > 1 and [t for t, p, _ in listed if p == 0] == sorted(t for t, p, _ in listed if p == 0),
          f"run.pvd's times rise: {', '.join(f'{t:.4g}' for t in times)} s")


def run(cli, scene, folder, steps, every, fmt):
    cmd = [cli, "run", scene, "--steps", str(steps), "--dump", folder, "--dump-every", str(every),
           "--dump-format", fmt, "--fast-plans", "--no-fsync"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    check(p.returncode == 0, " ".join(cmd[1:2] + [os.path.basename(scene)] + cmd[3:]) + f": exit {p.returncode}")
    if p.returncode != 0:
        print(p.stdout + p.stderr)
    return p.returncode == 0


def negative_control(folder, meta):
    """One value changed in a copy of a .vti's first array must be found."""
    dump = meta["dumps"][-1]
    name = next(n for n in dump["files"] if n.endswith(".vti"))
    with open(os.path.join(folder, name), "rb") as f:
        data = bytearray(f.read())
    # past the "_" that starts the raw data and the first array's byte count (UInt64): its sixth float
    at = data.index(b"_", data.index(b'<AppendedData encoding="raw">')) + 1 + 8 + 4 * 5
    data[at:at + 4] = np.float32(np.frombuffer(bytes(data[at:at + 4]), "<f4")[0] + 0.5).tobytes()
    copy = os.path.join(folder, "changed.vti")
    with open(copy, "wb") as f:
        f.write(data)
    img = read(vtkXMLImageDataReader, copy)
    first = img.GetPointData().GetArrayName(0)
    npy = np.load(os.path.join(folder, next(n for n in dump["files"] if n.startswith(first + "_") and n.endswith(".npy"))))
    before = dict(TOTALS)
    bad, worst = differences(img.GetPointData().GetArray(first), npy, npy.shape[-1] if npy.ndim == 3 else 1)
    TOTALS.update(before)
    check(bad == 1 and abs(worst - 0.5) < 1e-3, f"negative control: one changed value of {first} in {name} is found "
          f"({bad} differ, max |diff| {worst:g})")
    os.remove(copy)


def same_vtk_files(a, b):
    names = sorted(n for n in os.listdir(a) if n.endswith((".vti", ".vtu", ".pvd")))
    other = sorted(n for n in os.listdir(b) if n.endswith((".vti", ".vtu", ".pvd")))
    npy = [n for n in os.listdir(b) if n.endswith(".npy")]
    same = names == other and all(open(os.path.join(a, n), "rb").read() == open(os.path.join(b, n), "rb").read()
                                  for n in names)
    check(same and not npy, f"--dump-format vtk: the same {len(names)} VTK files as both, byte for byte, and no .npy")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="huygens_vtk_")
    try:
        for name, scene, steps, every in (("sph", SPH, 20, 10), ("lbm", LBM, 20, 10), ("huygens", HUYGENS, 4, 2)):
            path = os.path.join(work, name + ".json")
            with open(path, "w") as f:
                json.dump(scene, f)
            folder = os.path.join(work, name)
            if not run(args.cli, path, folder, steps, every, "both"):
                continue
            meta, expected = check_dumps(folder)
            check_pvd(folder, expected)
            if name == "lbm":
                negative_control(folder, meta)
                if run(args.cli, path, folder + "_vtk", steps, every, "vtk"):
                    same_vtk_files(folder, folder + "_vtk")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    check(all(NONZERO.values()), f"every field compared holds values other than 0 in some dump: {NONZERO}")
    print(f"compared {TOTALS['values']} values in {TOTALS['arrays']} arrays of {TOTALS['files']} VTK files "
          f"with the .npy dumps: largest difference {TOTALS['max_diff']:g}")
    if FAILURES:
        print(f"{len(FAILURES)} FAILED")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
