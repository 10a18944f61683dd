#!/usr/bin/python3
"""The peer of `isocurv curvature`: a Python + VTK script doing the same job per volume (read the
NRRD, Flying Edges at the isovalue, vtkCurvatures mean and Gaussian, write a VTP with VTK's default
zlib compression). Used by bench_headless.py, once per volume (twenty processes) or looping over
them in one process.

    vtk_pipeline.py ISO OUT_DIR VOLUME.nrrd...
"""
import os
import sys

import vtk


def main():
    iso = float(sys.argv[1])
    out_dir = sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    for path in sys.argv[3:]:
        reader = vtk.vtkNrrdReader()
        reader.SetFileName(path)
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
        if writer.Write() != 1:
            sys.exit("vtk_pipeline: cannot write " + stem)


if __name__ == "__main__":
    main()
