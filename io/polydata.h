#pragma once
// Converting a Mesh (with its curvature arrays) to vtkPolyData and back; used by the .vtp/.stl
// formats and by viz/.
// Tested in tests/io/test_polydata.cpp.
#include <string>

#include <vtkSmartPointer.h>

#include "io/mesh_file.h"

class vtkPolyData;

namespace isocurv::io {

/// A vtkPolyData with float points, triangle polys and, when `field` is given, one point-data
/// array per non-empty field array, named as in DESIGN.md (float, Boundary as unsigned char);
/// "Normals" is also the active point normals. Copies the data. `field` sizes must match (see
/// check_field_sizes; unchecked here). The field's metadata, then the `context` pairs whose keys
/// it lacks, become one-value string arrays of the field data. `cells` become Int32 cell data.
vtkSmartPointer<vtkPolyData> to_polydata(const Mesh& mesh,
                                         const curvature::CurvatureField* field = nullptr,
                                         const Metadata* context = nullptr,
                                         const CellArrays* cells = nullptr);

/// Writes `poly` as a .vtp at `path` (binary appended, `compression`, 64-bit headers), not
/// atomically: write_mesh's .vtp writer, for callers that add arrays of their own (dist/ pieces).
/// @throw std::runtime_error with VTK's message on failure.
void write_polydata(const std::string& path, vtkPolyData* poly, const Compression& compression);

/// The mesh and named arrays of `poly` (the inverse of to_polydata). Polygons are fan-triangulated,
/// triangle strips split, vertices and lines ignored; float data is copied bit-for-bit, other types
/// converted. "Normals" falls back to the active point normals. `source` names the file in errors:
/// an array with the wrong component count or length, or too many points, throws Error(source, ...).
/// The field data's one-value string arrays come back as MeshFile::metadata (and the field's);
/// one-component integer cell arrays as MeshFile::cells.
MeshFile from_polydata(vtkPolyData* poly, const std::string& source);

}  // namespace isocurv::io
