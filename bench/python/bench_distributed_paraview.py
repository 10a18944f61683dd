#!/usr/bin/env python3
"""Strong scaling of a distributed extraction: `mpirun -np N isocurv extract` beside ParaView's
`mpirun -np N pvbatch --mpi` (reader, Contour, .pvtp writer) on the same raw volume at the same
isovalue, and the seams each leaves: duplicate points and extra triangles against the single
process. Not a test: prints a table (docs/distributed.md).

Needs ParaView (Debian: paraview, python3-paraview). Installed, on Debian 12 these remove
libvtk9-dev and python3-vtk9; unpacked beside them instead, nothing is replaced:

    apt-get download paraview python3-paraview && for f in *paraview*.deb; do dpkg -x $f /opt/pv; done
    PATH=/opt/pv/usr/bin:$PATH LD_LIBRARY_PATH=/opt/pv/usr/lib/x86_64-linux-gnu \
      PYTHONPATH=/opt/pv/usr/lib/python3/dist-packages \
      /usr/bin/python3 bench/python/bench_distributed_paraview.py --isocurv build/app/isocurv [--runs 3]
"""
import argparse
import datetime
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dgtal_raw import dgtal_to_raw  # noqa: E402
from paraview.simple import *  # noqa: F401,F403  (loads ParaView's VTK modules)
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import vtk_to_numpy

PVBATCH_SCRIPT = r'''
import sys
from paraview.simple import ImageReader, Contour, SaveData
path, iso, dims, out = sys.argv[1], float(sys.argv[2]), [int(d) for d in sys.argv[3].split("x")], sys.argv[4]
r = ImageReader(FileNames=[path])
r.DataScalarType = "unsigned char"
r.DataByteOrder = "LittleEndian"
r.DataExtent = [0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1]
c = Contour(Input=r)
c.ContourBy = ["POINTS", "ImageFile"]
c.Isosurfaces = [iso]
c.ComputeNormals = 0
c.ComputeScalars = 0
SaveData(out, proxy=c)
'''

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")


def wall(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), r.stderr[-2000:]))
    return time.perf_counter() - t0


def pieces_of(pvtp):
    text = open(pvtp).read()
    return [os.path.join(os.path.dirname(pvtp), s) for s in re.findall(r'Source="([^"]+)"', text)]


def count(pvtp):
    """(points, triangles, unique point positions) over the pieces, ghosts left out."""
    pts, tris = [], 0
    for piece in pieces_of(pvtp):
        r = vtk.vtkXMLPolyDataReader()
        r.SetFileName(piece)
        r.Update()
        poly = r.GetOutput()
        p = vtk_to_numpy(poly.GetPoints().GetData()) if poly.GetNumberOfPoints() else np.zeros((0, 3))
        pg = poly.GetPointData().GetArray("vtkGhostType")
        cg = poly.GetCellData().GetArray("vtkGhostType")
        if pg is not None:
            p = p[vtk_to_numpy(pg) == 0]
        tris += poly.GetNumberOfCells() - (int(np.count_nonzero(vtk_to_numpy(cg))) if cg is not None else 0)
        pts.append(p)
    p = np.concatenate(pts) if pts else np.zeros((0, 3))
    return len(p), tris, len(np.unique(p, axis=0))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--isocurv", default="build/app/isocurv")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--ranks", default="1,2")
    a = ap.parse_args()
    iso_exe = os.path.abspath(a.isocurv)
    shared = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared", "datasets")
    tmp = tempfile.mkdtemp(prefix="isocurv-dist-bench-")
    script = os.path.join(tmp, "contour.py")
    open(script, "w").write(PVBATCH_SCRIPT)
    cases = []
    octa = os.path.join(shared, "aa_octaflower", "octa-flower17k-512-aa-l0_1.vol")
    if os.path.exists(octa):
        raw, dims = dgtal_to_raw(octa, tmp)
        cases.append(("octa-flower 512^3 (uint8)", raw, dims, 127.5))
    lidc = os.path.join(shared, "lidc2_ct", "LIDC2_256x256x133_uint8.raw.gz")
    if os.path.exists(lidc):
        import gzip
        raw = os.path.join(tmp, "LIDC2_256x256x133_uint8.raw")
        open(raw, "wb").write(gzip.open(lidc).read())
        cases.append(("LIDC2 CT 256x256x133 (uint8)", raw, [256, 256, 133], 60.0))
    ranks = [int(n) for n in a.ranks.split(",")]
    print("bench_distributed_paraview.py, %s, %d runs each (median wall time, start-up, read and write "
          "included)" % (datetime.date.today(), a.runs))
    for name, raw, dims, iso in cases:
        single = os.path.join(tmp, "single.vtp")
        t_single = statistics.median(wall([iso_exe, "extract", raw, "--iso", str(iso), "-o", single, "--quiet"])
                                     for _ in range(a.runs))
        r = vtk.vtkXMLPolyDataReader()
        r.SetFileName(single)
        r.Update()
        n_pts, n_tris = r.GetOutput().GetNumberOfPoints(), r.GetOutput().GetNumberOfCells()
        print("\n%s at isovalue %g: isocurv's single process makes %d points, %d triangles in %.2f s; "
              "extra triangles are counted against each tool's own single-process surface" % (name, iso, n_pts, n_tris, t_single))
        print("| ranks | isocurv s | pvbatch s | isocurv faster | isocurv dup. points / extra tris | "
              "pvbatch dup. points / extra tris | pvbatch global ids |")
        print("|---|---|---|---|---|---|---|")
        pv_single = None
        for n in ranks:
            ours = os.path.join(tmp, "ours%d.pvtp" % n)
            theirs = os.path.join(tmp, "pv%d.pvtp" % n)
            t_ours = statistics.median(wall(["mpirun", "-q", "-np", str(n), iso_exe, "extract", raw, "--iso", str(iso),
                                             "-o", ours, "--quiet"]) for _ in range(a.runs))
            t_pv = statistics.median(wall(["mpirun", "-q", "-np", str(n), "pvbatch", "--mpi", script, raw, str(iso),
                                           "x".join(map(str, dims)), theirs]) for _ in range(a.runs))
            o_pts, o_tris, o_unique = count(ours)
            p_pts, p_tris, p_unique = count(theirs)
            ids = "yes" if "GlobalIds" in open(theirs).read() else "no"
            if pv_single is None:  # ParaView's own surface without seams: one piece
                one = os.path.join(tmp, "pv_one.pvtp")
                wall(["pvbatch", script, raw, str(iso), "x".join(map(str, dims)), one])
                pv_single = count(one)[1]
            print("| %d | %.2f | %.2f | %.1fx | %d / %d | %d / %d | %s |" %
                  (n, t_ours, t_pv, t_pv / t_ours, o_pts - o_unique, o_tris - n_tris, p_pts - p_unique,
                   p_tris - pv_single, ids))


if __name__ == "__main__":
    main()
