#!/usr/bin/python3
"""Shape measures against scikit-image and OpenVDB's LevelSetMeasure, from one run (issue 43).

On the same volumes (generated here with numpy, fixed seeds), each solid with exactly known
volume V, area A, integral of the mean curvature int H dA (H = (k1 + k2) / 2) and Euler
characteristic chi of its surface (so int K dA = 2 pi chi):

  - isocurv: the Python module in-process (from_array + extract + measure) and the command line
    (`isocurv measure FILE.nrrd --iso V --json`, the whole process's wall time);
  - scikit-image: marching_cubes (Lewiner), mesh_surface_area, the mesh's volume by the
    divergence theorem (numpy), and euler_number(mask, connectivity=3) of the solid voxel mask
    (26-connected object, 6-connected background; the solid's chi, so the surface's is twice it);
  - OpenVDB: build/bench/bench_measure, which rebuilds a narrow-band level set from the volume at
    the isovalue (tools::levelSetRebuild, each voxel's sign then taken from the volume so that
    cavities stay empty) and runs tools::LevelSetMeasure on it; its time is the negation of a
    density, the level set and the measure (not the file's load).

Each quantity's error against the exact value, and the times: medians of --runs after a warm-up.

    /usr/bin/python3 bench/python/bench_measure.py [--build build] [--runs 3] [--quick]
        [--update-doc docs/measure-benchmark.md]

--update-doc replaces the part of that page between its `bench_measure:begin` and
`bench_measure:end` markers with this run's tables, command and date. Needs numpy, scipy and
python3-skimage (Debian's /usr/bin/python3), the module in BUILD/python, BUILD/app/isocurv and
BUILD/bench/bench_measure. Writes its volumes under a temporary folder.
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.special import erfc

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
PI = math.pi

# CT-like volumes: lo outside, hi inside, an erfc edge of width B voxels, Gaussian noise.
CT_LO, CT_HI, CT_B, CT_SIGMA = 40.0, 200.0, 1.0, 4.0


def rotation(ax, ay, az):
    """Rotation matrix from angles (radians) about x, then y, then z."""
    cx, sx, cy, sy, cz, sz = math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay), math.cos(az), math.sin(az)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return rz @ ry @ rx


def local_coords(n, centre, rot=None):
    """Coordinates (x, y, z) of every voxel of an n^3 grid ([z, y, x] arrays), relative to
    `centre` (voxel units) and expressed in the shape's frame (rot: shape frame -> grid)."""
    z, y, x = np.meshgrid(*(np.arange(n, dtype=np.float64),) * 3, indexing="ij")
    p = [x - centre[0], y - centre[1], z - centre[2]]
    if rot is None:
        return p
    r = rot.T  # grid -> shape frame
    return [r[i, 0] * p[0] + r[i, 1] * p[1] + r[i, 2] * p[2] for i in range(3)]


# Each shape: a signed distance (negative inside, voxel units) on an n^3 grid, and its exact measures.

def sphere(n, radius):
    c = (n / 2 - 0.5 + 0.31, n / 2 - 0.5 - 0.17, n / 2 - 0.5 + 0.23)
    x, y, z = local_coords(n, c)
    d = np.sqrt(x * x + y * y + z * z) - radius
    r = radius
    return d, dict(V=4 / 3 * PI * r ** 3, A=4 * PI * r * r, H=4 * PI * r, chi=2)


def torus(n, big, small):
    c = (n / 2 - 0.5 + 0.27, n / 2 - 0.5 - 0.19, n / 2 - 0.5 + 0.11)
    x, y, z = local_coords(n, c, rotation(0.35, -0.2, 0.5))
    q = np.sqrt(x * x + y * y) - big
    d = np.sqrt(q * q + z * z) - small
    return d, dict(V=2 * PI * PI * big * small ** 2, A=4 * PI * PI * big * small, H=2 * PI * PI * big, chi=0)


def two_handles(n, hx=32.0, hy=16.0, hole=12.0, hole_x=16.0, rho=7.0):
    """The points within rho of a flat plate (a 2hx x 2hy rectangle in the shape's z = 0 plane with
    two round holes of radius `hole`): a smooth solid of genus 2. Its measures follow from Steiner's
    formula for a parallel body (rho below the plate's reach, the hole radius): with the plate's
    area a, perimeter p and Euler characteristic chi_P = -1,
    V = 2 rho a + (pi/2) rho^2 p + (4/3) pi rho^3 chi_P, A = 2 a + pi rho p + 4 pi rho^2 chi_P,
    int H dA = (pi/2) p + 4 pi rho chi_P, chi = 2 chi_P."""
    c = (n / 2 - 0.5 + 0.21, n / 2 - 0.5 + 0.13, n / 2 - 0.5 - 0.29)
    x, y, z = local_coords(n, c, rotation(0.25, 0.3, -0.4))
    # 2-D distance from (x, y) to the plate.
    ox, oy = np.maximum(np.abs(x) - hx, 0), np.maximum(np.abs(y) - hy, 0)
    d2 = np.sqrt(ox * ox + oy * oy)
    for sx in (-hole_x, hole_x):
        r = np.sqrt((x - sx) ** 2 + y * y)
        d2 = np.where(r < hole, hole - r, d2)
    d = np.sqrt(d2 * d2 + z * z) - rho
    area = 4 * hx * hy - 2 * PI * hole ** 2
    perim = 4 * (hx + hy) + 2 * 2 * PI * hole
    chi_p = -1
    return d, dict(V=2 * rho * area + PI / 2 * rho ** 2 * perim + 4 / 3 * PI * rho ** 3 * chi_p,
                   A=2 * area + PI * rho * perim + 4 * PI * rho ** 2 * chi_p,
                   H=PI / 2 * perim + 4 * PI * rho * chi_p, chi=2 * chi_p)


def box_with_cavity(n, half=(28.0, 24.0, 20.0), rho=6.0, cavity=12.0):
    """A box of sides 2 half, rounded by rho (the box's parallel body), with a spherical cavity of
    radius `cavity` inside: chi = 2 + 2. Steiner's formula for the box's measures; the cavity adds
    its area, takes its volume, and adds -4 pi R to int H dA (its surface faces into the cavity)."""
    c = (n / 2 - 0.5 - 0.23, n / 2 - 0.5 + 0.37, n / 2 - 0.5 + 0.16)
    x, y, z = local_coords(n, c, rotation(-0.3, 0.45, 0.2))
    q = [np.abs(x) - half[0], np.abs(y) - half[1], np.abs(z) - half[2]]
    outside = np.sqrt(sum(np.maximum(qi, 0) ** 2 for qi in q))
    inside = np.minimum(np.maximum(np.maximum(q[0], q[1]), q[2]), 0)
    d_box = outside + inside - rho
    cc = (1.7, -1.1, 0.9)  # the cavity's centre, off the box's
    d_cav = cavity - np.sqrt((x - cc[0]) ** 2 + (y - cc[1]) ** 2 + (z - cc[2]) ** 2)
    d = np.maximum(d_box, d_cav)
    a, b, cz = (2 * h for h in half)
    return d, dict(
        V=a * b * cz + 2 * rho * (a * b + b * cz + cz * a) + PI * rho ** 2 * (a + b + cz) + 4 / 3 * PI * rho ** 3
        - 4 / 3 * PI * cavity ** 3,
        A=2 * (a * b + b * cz + cz * a) + 2 * PI * rho * (a + b + cz) + 4 * PI * rho ** 2 + 4 * PI * cavity ** 2,
        H=PI * (a + b + cz) + 4 * PI * rho - 4 * PI * cavity, chi=4)


SHAPES = [
    ("sphere R20", 96, lambda n: sphere(n, 20.0)),
    ("torus R24 r8", 96, lambda n: torus(n, 24.0, 8.0)),
    ("two handles", 96, two_handles),
    ("box + cavity", 96, box_with_cavity),
    ("sphere R40", 128, lambda n: sphere(n, 40.0)),
]
KINDS = ["float SDF", "CT uint8", "mask 0/255"]


def make_volume(d, kind, seed):
    """(array [z, y, x], isovalue, inside) of one kind from the signed distance d."""
    if kind == "float SDF":
        return np.ascontiguousarray(d, dtype=np.float32), 0.0, "below"
    if kind == "CT uint8":
        rng = np.random.default_rng(seed)
        v = CT_LO + (CT_HI - CT_LO) * 0.5 * erfc(d / (math.sqrt(2) * CT_B)) + rng.normal(0, CT_SIGMA, d.shape)
        return np.ascontiguousarray(np.clip(np.rint(v), 0, 255).astype(np.uint8)), (CT_LO + CT_HI) / 2, "above"
    return np.ascontiguousarray(np.where(d < 0, 255, 0).astype(np.uint8)), 127.5, "above"


def write_nrrd(path, a):
    nz, ny, nx = a.shape
    t = {np.dtype(np.float32): "float", np.dtype(np.uint8): "uint8"}[a.dtype]
    with open(path, "wb") as f:
        f.write(("NRRD0004\ntype: %s\ndimension: 3\nsizes: %d %d %d\nspacings: 1 1 1\n"
                 "encoding: raw\nendian: little\n\n" % (t, nx, ny, nz)).encode())
        f.write(a.astype(a.dtype.newbyteorder("<")).tobytes())


def median_time(f, runs):
    """(median ms over `runs` timed calls after one untimed warm-up, last result)."""
    out = f()
    t = []
    for _ in range(runs):
        t0 = time.perf_counter()
        out = f()
        t.append(1e3 * (time.perf_counter() - t0))
    return statistics.median(t), out


def mesh_volume(verts, faces):
    v0, v1, v2 = verts[faces[:, 0]], verts[faces[:, 1]], verts[faces[:, 2]]
    return abs(float(np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum()) / 6.0)


def run_skimage(a, iso, inside):
    from skimage import measure as skm
    vol = a.astype(np.float32) if a.dtype != np.float32 else a
    verts, faces, _, _ = skm.marching_cubes(vol, level=iso)
    area = float(skm.mesh_surface_area(verts, faces))
    volume = mesh_volume(verts, faces)
    mask = a > iso if inside == "above" else a < iso
    chi_solid = int(skm.euler_number(mask, connectivity=3))
    return dict(A=area, V=volume, chi=2 * chi_solid, H=None, K=None)


def run_isocurv_py(isocurv, a, iso, inside):
    v = isocurv.from_array(a, spacing=(1.0, 1.0, 1.0), inside=inside)
    m = isocurv.extract(v, iso=iso)
    r = isocurv.measure(m, v)
    return dict(A=float(r["area"].sum()), V=float(r["volume"].sum()), H=float(r["integral_H"].sum()),
                K=float(r["integral_K"].sum()), chi=int(r["euler_characteristic"].sum()),
                components=len(r["area"]))


def run_cli(cli, path, iso, inside, runs):
    cmd = [cli, "measure", path, "--iso", repr(iso), "--json", "--quiet"] + (["--inside", "below"] if inside == "below" else [])

    def once():
        p = subprocess.run(cmd, capture_output=True, text=True)
        if p.returncode != 0:
            raise RuntimeError("%s: %s" % (" ".join(cmd), p.stderr.strip()))
        return json.loads(p.stdout)

    ms, j = median_time(once, runs)
    t = j["total"]
    return ms, dict(A=t["area"], V=t["volume"], H=t["integral_H"], K=t["integral_K"], chi=t["euler_characteristic"],
                    stages=j.get("timings_ms", {}))


def run_openvdb(exe, path, iso, inside, runs):
    cmd = [exe, path, "--iso", repr(iso), "--inside", inside, "--repeat", str(runs)]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = 1e3 * (time.perf_counter() - t0)
    if p.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), p.stderr.strip()))
    j = json.loads(p.stdout)
    t = j["timings_ms"]
    return t["negate"] + t["level_set_measure"], dict(A=j["area"], V=j["volume"], H=j["integral_H"], K=j["integral_K"],
                                                    chi=j["euler_characteristic"], wall=wall)


def rel(x, exact):
    return None if x is None else 100.0 * (x - exact) / abs(exact)


def gb_gap(k, chi):
    """int K dA against 2 pi chi, in % of 2 pi max(1, |chi|) (the exact int K dA is 2 pi chi)."""
    return None if k is None else 100.0 * (k - 2 * PI * chi) / (2 * PI * max(1, abs(chi)))


def fmt(x, digits=2):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    return ("%+." + str(digits) + "f") % x


def best_marks(vals):
    """Indexes of the smallest |value| among the non-None ones (ties too)."""
    ok = [abs(v) for v in vals if v is not None and not math.isnan(v)]
    if not ok:
        return set()
    m = min(ok)
    return {i for i, v in enumerate(vals) if v is not None and not math.isnan(v) and abs(v) <= m * 1.0000001 + 1e-12}


def tables(results):
    out = []
    peers = ["isocurv", "skimage", "openvdb"]
    for q, title, exact_fmt in [("V", "Enclosed volume V (voxel units^3): error %", "%.1f"),
                                ("A", "Area A (voxel units^2): error %", "%.1f"),
                                ("H", "Integral of the mean curvature, int H dA (H = (k1 + k2) / 2): error %", "%.2f")]:
        out.append("#### " + title + "\n")
        out.append("| volume | kind | exact | isocurv | scikit-image | OpenVDB |")
        out.append("|---|---|---:|---:|---:|---:|")
        for r in results:
            errs = [rel(r[p][q], r["exact"][q]) for p in peers]
            best = best_marks(errs)
            cells = [("**%s**" % fmt(e) if i in best and len(best) < 3 else fmt(e)) for i, e in enumerate(errs)]
            out.append("| %s | %s | %s | %s |" % (r["shape"], r["kind"], exact_fmt % r["exact"][q], " | ".join(cells)))
        out.append("")
    out.append("#### Euler characteristic chi of the surface (found; exact in the third column)\n")
    out.append("| volume | kind | exact | isocurv (V - E + F) | scikit-image (2 x euler_number) | OpenVDB (round(int K dA / 2 pi)) |")
    out.append("|---|---|---:|---:|---:|---:|")
    for r in results:
        e = r["exact"]["chi"]
        cells = ["%d%s" % (r[p]["chi"], "" if r[p]["chi"] == e else " ✗") for p in peers]
        out.append("| %s | %s | %d | %s |" % (r["shape"], r["kind"], e, " | ".join(cells)))
    out.append("")
    out.append("#### Gauss-Bonnet: int K dA against 2 pi chi, in % of 2 pi max(1, |chi|)\n")
    out.append("| volume | kind | exact int K dA | isocurv | scikit-image | OpenVDB |")
    out.append("|---|---|---:|---:|---:|---:|")
    for r in results:
        e = r["exact"]["chi"]
        errs = [gb_gap(r[p]["K"], e) for p in peers]
        best = best_marks(errs)
        cells = [("**%s**" % fmt(x) if i in best and len(best) < 3 else fmt(x)) for i, x in enumerate(errs)]
        out.append("| %s | %s | %.4f | %s |" % (r["shape"], r["kind"], 2 * PI * e, " | ".join(cells)))
    out.append("")
    out.append("#### Times (ms, medians) and the speed ratio\n")
    out.append("| volume | grid | kind | isocurv Python | isocurv CLI (process) | scikit-image | OpenVDB | skimage / isocurv Python | skimage / isocurv CLI |")
    out.append("|---|---|---|---:|---:|---:|---:|---:|---:|")
    for r in results:
        t = r["times"]
        out.append("| %s | %d^3 | %s | %.0f | %.0f | %.0f | %.0f | %.1fx | %.2fx |" % (
            r["shape"], r["n"], r["kind"], t["isocurv"], t["cli"], t["skimage"], t["openvdb"],
            t["skimage"] / t["isocurv"], t["skimage"] / t["cli"]))
    out.append("")
    return "\n".join(out)


def summary(results):
    """Per quantity and peer: how often it is the most accurate, and the worst |error|."""
    lines = []
    peers = [("isocurv", "isocurv"), ("skimage", "scikit-image"), ("openvdb", "OpenVDB")]
    for q, name in [("V", "volume"), ("A", "area"), ("H", "int H dA")]:
        parts = []
        for p, label in peers:
            errs = [rel(r[p][q], r["exact"][q]) for r in results]
            errs = [abs(e) for e in errs if e is not None and not math.isnan(e)]
            if errs:
                parts.append("%s max %.2f%% / median %.2f%%" % (label, max(errs), statistics.median(errs)))
            else:
                parts.append("%s n/a" % label)
        lines.append("- %s |error|: %s" % (name, "; ".join(parts)))
    chi_ok = {p: sum(r[p]["chi"] == r["exact"]["chi"] for r in results) for p, _ in peers}
    lines.append("- chi right: %s (of %d)" % (", ".join("%s %d" % (l, chi_ok[p]) for p, l in peers), len(results)))
    ratios = [r["times"]["skimage"] / r["times"]["isocurv"] for r in results]
    cli = [r["times"]["skimage"] / r["times"]["cli"] for r in results]
    lines.append("- speed, scikit-image / isocurv: Python %.1fx to %.1fx (median %.1fx); whole CLI process %.2fx to %.2fx (median %.2fx)" % (
        min(ratios), max(ratios), statistics.median(ratios), min(cli), max(cli), statistics.median(cli)))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="the 96^3 sphere and torus only")
    ap.add_argument("--update-doc", metavar="MD", help="write the tables into this page between its markers")
    args = ap.parse_args()

    sys.path.insert(0, os.path.join(args.build, "python"))
    import isocurv
    import skimage
    cli = os.path.join(args.build, "app", "isocurv")
    vdb = os.path.join(args.build, "bench", "bench_measure")
    for exe in (cli, vdb):
        if not os.access(exe, os.X_OK):
            sys.exit("missing %s (build it: make -C %s %s)" % (exe, args.build, os.path.basename(exe)))

    shapes = SHAPES[:2] if args.quick else SHAPES
    tmp = tempfile.mkdtemp(prefix="bench_measure_")
    results = []
    try:
        for si, (shape, n, make) in enumerate(shapes):
            d, exact = make(n)
            for ki, kind in enumerate(KINDS):
                a, iso, inside = make_volume(d, kind, seed=1000 + 10 * si + ki)
                path = os.path.join(tmp, "v%d_%d.nrrd" % (si, ki))
                write_nrrd(path, a)
                r = dict(shape=shape, kind=kind, n=n, exact=exact, times={})
                r["times"]["isocurv"], r["isocurv"] = median_time(lambda: run_isocurv_py(isocurv, a, iso, inside), args.runs)
                r["times"]["skimage"], r["skimage"] = median_time(lambda: run_skimage(a, iso, inside), args.runs)
                r["times"]["cli"], r["cli"] = run_cli(cli, path, iso, inside, args.runs)
                r["times"]["openvdb"], r["openvdb"] = run_openvdb(vdb, path, iso, inside, args.runs)
                for q in ("A", "V", "H", "K", "chi"):  # the module and the CLI are one code path
                    x, y = r["isocurv"][q], r["cli"][q]
                    if abs(x - y) > 1e-6 * max(1.0, abs(x)):
                        print("note: %s %s: module %s %.6g, CLI %.6g" % (shape, kind, q, x, y), file=sys.stderr)
                results.append(r)
                print("%-13s %-10s iso %-6g  isocurv %6.0f ms (CLI %5.0f)  skimage %6.0f ms  OpenVDB %6.0f ms" % (
                    shape, kind, iso, r["times"]["isocurv"], r["times"]["cli"], r["times"]["skimage"], r["times"]["openvdb"]),
                    file=sys.stderr)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            m = re.search(r"model name\s*:\s*(.*)", f.read())
            cpu = m.group(1).strip() if m else ""
    except OSError:
        pass
    head = ("Run %s on %s (%d cores), Python %s, numpy %s, scikit-image %s, OpenVDB %s; isocurv's "
            "OpenCL device: its default. Medians of %d timed runs after a warm-up.\n" % (
                datetime.date.today().isoformat(), cpu or platform.machine(), os.cpu_count(), platform.python_version(),
                np.__version__, skimage.__version__, vdb_version(), args.runs))
    text = head + "\n" + tables(results) + "\nSummary:\n\n" + summary(results) + "\n"
    print(text)
    if args.update_doc:
        update_doc(args.update_doc, text, args)


def vdb_version():
    try:
        with open("/usr/include/openvdb/version.h") as f:
            s = f.read()
        v = [re.search(r"#define OPENVDB_LIBRARY_%s_VERSION_NUMBER (\d+)" % k, s).group(1) for k in ("MAJOR", "MINOR", "PATCH")]
        return ".".join(v)
    except (OSError, AttributeError):
        return "?"


def update_doc(path, text, args):
    begin, end = "<!-- bench_measure:begin -->", "<!-- bench_measure:end -->"
    with open(path) as f:
        doc = f.read()
    if begin not in doc or end not in doc:
        sys.exit("%s: no %s ... %s markers" % (path, begin, end))
    cmd = "/usr/bin/python3 bench/python/bench_measure.py" + (" --quick" if args.quick else "") + (
        " --runs %d" % args.runs if args.runs != 3 else "") + " --update-doc " + os.path.relpath(path, ROOT)
    block = "%s\n<!-- written by `%s`; do not edit by hand -->\n\n%s%s" % (begin, cmd, text, end)
    doc = doc[:doc.index(begin)] + block + doc[doc.index(end) + len(end):]
    with open(path, "w") as f:
        f.write(doc)
    print("wrote %s" % path, file=sys.stderr)


if __name__ == "__main__":
    main()
