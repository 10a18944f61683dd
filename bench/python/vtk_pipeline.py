#!/usr/bin/python3
"""The peer of `isocurv curvature`: a Python + VTK script doing the same job per volume (read the
NRRD, Flying Edges at the isovalue, vtkCurvatures mean and Gaussian, write a VTP with VTK's default
zlib compression). Debian's VTK 9.1 Python vtkNrrdReader is the MPI-parallel vtkPNrrdReader, which
fails without an MPI controller, so the NRRD (raw uint16, little-endian, attached header, as
bench_headless.py writes) is read by vtkImageReader2 from its header's sizes and spacings. Used by bench_headless.py, once per volume (twenty processes) or looping over
them in one process.

    vtk_pipeline.py ISO OUT_DIR VOLUME.nrrd...
"""
import os
import sys

import vtk


def nrrd_reader(path):
    """vtkImageReader2 set up from an attached-header raw uint16 little-endian NRRD."""
    with open(path, "rb") as f:
        head = f.read(4096)
    header = head[: head.index(b"\n\n") + 2].decode()
    fields = dict(line.split(": ", 1) for line in header.splitlines()[1:] if ": " in line)
    if fields.get("type") != "uint16" or fields.get("encoding") != "raw":
        sys.exit("vtk_pipeline: expected a raw uint16 NRRD: " + path)
    nx, ny, nz = (int(x) for x in fields["sizes"].split())
    spacing = [float(x) for x in fields["spacings"].split()]
    r = vtk.vtkImageReader2()
    r.SetFileName(path)
    r.SetFileDimensionality(3)
    r.SetDataScalarTypeToUnsignedShort()
    r.SetDataByteOrderToLittleEndian()
    r.SetDataExtent(0, nx - 1, 0, ny - 1, 0, nz - 1)
    r.SetDataSpacing(*spacing)
    r.SetHeaderSize(len(header))
    return r


def main():
    iso = float(sys.argv[1])
    out_dir = sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    for path in sys.argv[3:]:
        reader = nrrd_reader(path)
        fe = vtk.vtkFlyingEdges3D()
        fe.SetInputConnection(reader.GetOutputPort())
        fe.SetValue(0, iso)
        fe.ComputeNormalsOn()
        mean = vtk.vtkCurvatures()
        mean.SetInputConnection(fe.GetOutputPort())
        mean.SetCurvatureTypeToMean()
        gauss = vtk.vtkCurvatures()
        gauss.SetInputConnection(mean.GetOutputPort())
        gauss.SetCurvatureTypeToGaussian()
        writer = vtk.vtkXMLPolyDataWriter()
        writer.SetInputConnection(gauss.GetOutputPort())
        stem = os.path.basename(path).split(".")[0]
        writer.SetFileName(os.path.join(out_dir, stem + ".vtp"))
        if writer.Write() != 1 or gauss.GetOutput().GetNumberOfPoints() == 0:
            sys.exit("vtk_pipeline: no surface or cannot write " + stem)


if __name__ == "__main__":
    main()
