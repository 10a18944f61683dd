#!/usr/bin/python3
"""Headless pipelines at scale, against Python + VTK, from one run (ratios; wall times of whole
processes, medians of --runs).

  1. one CT-like volume (128x96x114 uint16 NRRD, blurred solids with noise): `isocurv curvature
     CT.nrrd -o out.vtp` against the Python + VTK script (vtk_pipeline.py);
  2. twenty such volumes: one `isocurv curvature IN... -o DIR` call (and with --jobs 2) against
     twenty Python + VTK processes and against one Python process looping over them;
  3. program builds of a second and later process start (timings_ms.compile, with the cache);
  4. the Python module's extract + curvature against the C++ library's same calls
     (bench_library), same volume, both warm.

    /usr/bin/python3 bench/python/bench_headless.py [--build build] [--runs 3]

Needs numpy, python3-vtk9 and the module in BUILD/python. Writes under a temporary folder.
"""
import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DIMS = (128, 96, 114)  # x, y, z
SPACING = (0.8, 0.8, 1.25)
ISO = 1300.0


def ct_volume(seed):
    """A CT-like uint16 volume: an ellipsoid of 'soft tissue' (1100) holding a torus and a ball of
    'bone' (1900) over 'air' (~100), edges blurred over ~1.5 voxels, Gaussian noise (sigma 25),
    quantised. [z, y, x] order."""
    rng = np.random.default_rng(seed)
    nx, ny, nz = DIMS
    z, y, x = np.mgrid[0:nz, 0:ny, 0:nx].astype(np.float32)
    shift = rng.uniform(-3, 3, size=3)
    cx, cy, cz = nx / 2 + shift[0], ny / 2 + shift[1], nz / 2 + shift[2]

    def edge(d):  # 1 inside (d < 0) to 0 outside, blurred
        return 0.5 * (1 - np.tanh(d / 1.5))

    ell = np.sqrt(((x - cx) / 55) ** 2 + ((y - cy) / 40) ** 2 + ((z - cz) / 50) ** 2)
    v = 100 + 1000 * edge((ell - 1) * 45)
    q = np.sqrt((x - cx) ** 2 + (y - cy) ** 2) - 25
    torus = np.sqrt(q ** 2 + (z - cz + 12) ** 2) - 8
    ball = np.sqrt((x - cx - 10) ** 2 + (y - cy) ** 2 + (z - cz - 25) ** 2) - 10
    v = v + 800 * edge(np.minimum(torus, ball))
    v = v + rng.normal(0, 25, size=v.shape)
    return np.clip(np.rint(v), 0, 65535).astype(np.uint16)


def write_nrrd(path, a):
    header = (
        "NRRD0004\ntype: uint16\ndimension: 3\nsizes: %d %d %d\nspacings: %g %g %g\n"
        "encoding: raw\nendian: little\n\n" % (DIMS + SPACING)
    )
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(a.astype("<u2").tobytes())


CPU = []  # CPU time (user + sys, ms) of each wall() call's process, in call order


def wall(cmd, env=None):
    """Runs cmd; returns its wall time in ms and its stdout, and appends its CPU time to CPU (on a
    shared, overloaded machine the CPU time is the steadier figure)."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    dt = (time.perf_counter() - t0) * 1000
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU.append(1000 * (r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime))
    if r.returncode != 0:
        sys.exit("bench_headless: failed: %s\n%s" % (" ".join(cmd), r.stderr.decode()))
    return dt, r.stdout


def median_of(runs, f):
    """Median wall ms of f() over runs calls, and the median CPU ms of the processes they ran."""
    walls, cpus = [], []
    for _ in range(runs):
        n = len(CPU)
        walls.append(f())
        cpus.append(sum(CPU[n:]))
    return statistics.median(walls), statistics.median(cpus)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(HERE, "..", "..", "build"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--volumes", type=int, default=20)
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    exe = os.path.join(build, "app", "isocurv")
    sys.path.insert(0, os.path.join(build, "python"))
    import isocurv  # noqa: E402

    work = tempfile.mkdtemp(prefix="isocurv_bench_headless_")
    env = dict(os.environ, ISOCURV_CACHE_DIR=os.path.join(work, "cache"))
    try:
        vols = []
        for i in range(args.volumes):
            p = os.path.join(work, "ct_%02d.nrrd" % i)
            write_nrrd(p, ct_volume(i))
            vols.append(p)
        vtk_script = [sys.executable, os.path.join(HERE, "vtk_pipeline.py"), str(ISO)]
        # Warm both (file cache, program cache, PoCL's kernel cache) before timing.
        wall([exe, "curvature", vols[0], "--iso", str(ISO), "-o", os.path.join(work, "warm.vtp"), "--quiet"], env)
        wall(vtk_script + [os.path.join(work, "warm_vtk"), vols[0]])

        print("isocurv headless benchmark: %d CT-like volumes %dx%dx%d uint16, iso %g, medians of %d"
              % (args.volumes, *DIMS, ISO, args.runs))
        out1 = os.path.join(work, "one.vtp")
        one_ours = median_of(args.runs, lambda: wall([exe, "curvature", vols[0], "--iso", str(ISO), "-o", out1, "--quiet"], env)[0])
        one_vtk = median_of(args.runs, lambda: wall(vtk_script + [os.path.join(work, "one_vtk"), vols[0]])[0])
        row = "   %-32s %8.0f %8.0f"
        print("\n1. one volume, whole process       wall ms   CPU ms")
        print(row % ("isocurv curvature", *one_ours))
        print(row % ("Python + VTK script", *one_vtk) + "   VTK / isocurv: wall %.2f, CPU %.2f"
              % (one_vtk[0] / one_ours[0], one_vtk[1] / one_ours[1]))

        def batch(jobs):
            d = os.path.join(work, "batch_j%d" % jobs)
            shutil.rmtree(d, ignore_errors=True)
            return wall([exe, "curvature", *vols, "--iso", str(ISO), "-o", d, "--quiet", "--jobs", str(jobs)], env)[0]

        b1 = median_of(args.runs, lambda: batch(1))
        b2 = median_of(args.runs, lambda: batch(2))
        loop = median_of(args.runs, lambda: wall(vtk_script + [os.path.join(work, "loop_vtk"), *vols])[0])
        each = median_of(1, lambda: sum(wall(vtk_script + [os.path.join(work, "each_vtk"), v])[0] for v in vols))
        print("\n2. %d volumes                      wall ms   CPU ms" % args.volumes)
        print(row % ("isocurv curvature IN... -o DIR", *b1))
        print(row % ("the same with --jobs 2", *b2))
        print(row % ("Python + VTK, one loop process", *loop) + "   loop / isocurv: wall %.2f (--jobs 2: %.2f), CPU %.2f"
              % (loop[0] / b1[0], loop[0] / b2[0], loop[1] / b1[1]))
        print(row % ("Python + VTK, %d processes" % args.volumes, *each) + "   processes / isocurv: wall %.2f, CPU %.2f"
              % (each[0] / b1[0], each[1] / b1[1]))

        compiles = []
        for _ in range(max(3, args.runs)):
            _, out = wall([exe, "curvature", vols[0], "--iso", str(ISO), "-o", out1, "--json"], env)
            compiles.append(json.loads(out)["timings_ms"].get("compile", 0.0))
        cold_env = dict(env, ISOCURV_CACHE_DIR="")
        _, out = wall([exe, "curvature", vols[0], "--iso", str(ISO), "-o", out1, "--json"], cold_env)
        cold = json.loads(out)["timings_ms"].get("compile", 0.0)
        print("\n3. program builds per process start   ms")
        print("   without the cache               %8.1f" % cold)
        print("   with it (later starts, median)  %8.1f   (runs: %s)" % (statistics.median(compiles), ", ".join("%.1f" % c for c in compiles)))

        # 4. Python module vs the C++ library on the same volume, both warm, alternating.
        v = isocurv.load(vols[0])

        def py_once():
            t0 = time.perf_counter()
            m = isocurv.extract(v, ISO)
            isocurv.curvature(m, v)
            return (time.perf_counter() - t0) * 1000

        lib_exe = os.path.join(build, "bench", "bench_library")
        libs, pys = [], []
        for _ in range(max(3, args.runs)):
            _, out = wall([lib_exe, "--volume", vols[0], "--iso", str(ISO), "--runs", "9"], env)
            libs.append(float(out.split()[1]))
            for _ in range(2):
                py_once()  # warm-up, as bench_library's
            pys.append(statistics.median(py_once() for _ in range(9)))
        lib, py = statistics.median(libs), statistics.median(pys)
        print("\n4. extract + curvature in process     ms (medians of 9, warm; rounds alternate)")
        print("   C++ library (bench_library)     %8.1f   (rounds: %s)" % (lib, ", ".join("%.1f" % x for x in libs)))
        print("   Python module                   %8.1f   (rounds: %s)   Python / C++ = %.2f"
              % (py, ", ".join("%.1f" % x for x in pys), py / lib))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
