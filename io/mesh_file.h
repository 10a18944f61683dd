#pragma once
// Reading and writing meshes with their curvature arrays, the format chosen by the extension.
//
//   .vtp  VTK XML PolyData, binary appended, LZ4 compressed by default (io/compression.h); every array of DESIGN.md by name,
//         "Normals" also set as the point normals. Opens in ParaView.
//   .ply  binary little-endian PLY: vertex properties x y z, nx ny nz (Normals), then one float
//         property per scalar array (Area k1 k2 H K ShapeIndex Curvedness AO), vectors as
//         <name>_0 <name>_1 <name>_2 (dir1, dir2) and dcurv_0..dcurv_3, Boundary as uchar; faces
//         as "list uchar int vertex_indices". Opens in MeshLab. Reading also accepts ascii and
//         big-endian PLY, any property types, and polygons (fan-triangulated).
//   .obj  Wavefront OBJ: v, vn (Normals), f; geometry and normals only.
//   .stl  binary STL via VTK: geometry only (read merges coincident points).
//
// Float arrays read back from .vtp and .ply are bit-for-bit what was written; .obj writes floats
// with 9 significant digits, which also round-trips exactly. Mesh::edge_keys are not stored.
// Tested in tests/io/test_mesh_file.cpp, tests/io/test_fuzz_regressions.cpp.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "io/compression.h"
#include "curvature/curvature_field.h"

namespace isocurv::io {

/// Text (name, value) pairs of a .vtp's field data: how the curvature was made
/// (CurvatureField::metadata) and where the surface came from ("isovalue", "length_unit",
/// "world_space", "source": app/pipeline.h's context_metadata).
using Metadata = std::vector<std::pair<std::string, std::string>>;

/// An integer array with one value per triangle (the "Label" of label maps), written as cell data.
struct CellArray {
  std::string name;
  std::vector<std::int32_t> values;
};
using CellArrays = std::vector<CellArray>;

/// A mesh read from a file, with whatever curvature arrays the file carried.
struct MeshFile {
  Mesh mesh;
  /// Present when the file carried at least one of the named arrays. Each array then holds one
  /// value per vertex, or is empty when the file did not carry it (e.g. .obj gives Normals only).
  /// Its metadata is the file's field data (as `metadata`).
  std::optional<curvature::CurvatureField> field;
  /// The field data's one-value string arrays (.vtp only; at most 64, values up to 1,024 bytes:
  /// longer ones are left out).
  Metadata metadata;
  /// The one-component integer cell arrays of a .vtp (one value per triangle; polygons that were
  /// fan-triangulated repeat their value). Empty for the other formats.
  CellArrays cells;
};

/// Writes `mesh` (and the non-empty arrays of `field`, when given) to `path`, the format chosen by
/// the extension (.vtp, .ply, .obj, .stl; case-insensitive). Written atomically: on failure no
/// file is left and an existing one is untouched. Throws Error for an unknown extension, a field
/// whose arrays do not match the vertex count, or any write failure. `compression` applies to
/// .vtp only (the other formats are uncompressed). `context`, when given, joins the field's
/// metadata in the .vtp's field data (keys the field's metadata already has are not repeated);
/// the other formats have no place for either. `cells`, when given, are per-triangle arrays: cell
/// data of a .vtp, face properties of a .ply (int), left out of .obj and .stl; each must have one
/// value per triangle (else Error).
void write_mesh(const std::string& path, const Mesh& mesh,
                const curvature::CurvatureField* field = nullptr,
                const Compression& compression = {}, const Metadata* context = nullptr,
                const CellArrays* cells = nullptr);

/// Reads a mesh file written by write_mesh (or any reasonable .vtp/.ply/.obj/.stl). Throws Error
/// naming the file for a missing, unreadable, truncated or malformed file, an unknown extension or
/// out-of-range indices.
MeshFile read_mesh(const std::string& path);

/// The extensions write_mesh and read_mesh accept, for help texts: ".vtp, .ply, .obj, .stl".
const char* mesh_extensions();

}  // namespace isocurv::io
