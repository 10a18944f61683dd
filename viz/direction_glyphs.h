#pragma once
// Principal directions drawn as short line segments on an even subsample of the vertices.
#include <vtkSmartPointer.h>

#include "core/mesh.h"
#include "core/mesh_measures.h"
#include "curvature/curvature_field.h"

class vtkPolyData;

namespace isocurv::viz {

/// Colours of the glyphs: dir1 (direction of k1, the larger curvature) and dir2.
constexpr unsigned char kDir1Color[3] = {255, 255, 255};  // white
constexpr unsigned char kDir2Color[3] = {20, 20, 20};     // near-black

/// Line segments centred on a spatially even subsample of the vertices (one per grid cell of
/// `spacing`: at least 2.5 mean edge lengths, and at most ~120 glyphs across the bounding box so
/// they stay visible on fine meshes), two per vertex: along dir1 and along dir2, each 0.7 *
/// spacing long (so about 1.75 mean edges on coarse meshes), lifted off the surface by a tenth of a
/// mean edge along the normal. Cell data "Colors" (RGB) holds kDir1Color / kDir2Color. Vertices
/// without finite non-zero directions are skipped; empty when the field has no dir1/dir2.
/// Deterministic: the first vertex (by index) in each cell is chosen.
vtkSmartPointer<vtkPolyData> direction_glyphs(const Mesh& mesh, const curvature::CurvatureField& field);

}  // namespace isocurv::viz
