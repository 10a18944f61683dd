#pragma once
// Options of the marching-cubes mesher.
// Tested in tests/mc/extract_test.cpp, tests/mc/snap_test.cpp (through its users).
#include <array>
#include <climits>

namespace isocurv::mc {

/// Default snap distance (Options::snap), a fraction of a voxel edge.
constexpr float kDefaultSnap = 0.01f;

struct Options {
  /// Width of the per-vertex edge hash used for fusion, 1..32 bits. Narrow hashes collide often
  /// (tests use that); the output is the same for every width, only slower when narrow.
  int hash_bits = 32;
  /// Close surfaces cut by the bounding box of a dense volume (outside the box counts as outside
  /// the object, as OpenVDB does). Default: leave them open there, as VTK does.
  bool cap = false;
  /// Fill Mesh::edge_keys (the cube edge of each vertex), for tests and fusion checks.
  bool keep_edge_keys = false;
  /// Vertices closer than this fraction of a voxel edge to a voxel are merged with the others
  /// near it into one vertex at their centroid (on the voxel where the centroid would leave a bad
  /// triangle), wherever the mesh stays a consistently wound 2-manifold (mc/snap_vertices.h, after
  /// SnapMC). Removes the clusters of nearly coincident vertices and the slivers that voxels equal
  /// to the isovalue (integer CT and MR data) otherwise leave. A merged vertex moves by at most
  /// twice this distance and stays within it of the voxel. Where no merge is possible the
  /// vertices move out along their edges to this distance from the voxel instead. 0 turns
  /// snapping off; at most 0.5.
  float snap = kDefaultSnap;
  /// Visit only the cells whose lower corner (index space) lies in [cells_min, cells_max] on every
  /// axis, inclusive; the default visits every cell. For a piece of a distributed extraction
  /// (dist/): edge keys still count from the whole volume's key origin, and vertices are placed
  /// exactly as in the whole extraction, so pieces agree on the vertices they share. The cut
  /// leaves the piece open there, and snapping near the cut sees only the piece's side: callers
  /// keep a few cells of margin (dist::kExtractGhostCells) and drop what lies in it.
  std::array<int, 3> cells_min{{INT_MIN, INT_MIN, INT_MIN}};
  std::array<int, 3> cells_max{{INT_MAX, INT_MAX, INT_MAX}};
};

/// Vertices never sit closer than this fraction of a voxel edge to a voxel, so voxels exactly at
/// the isovalue cannot create coincident vertices or zero-area triangles.
constexpr float kMinEdgeFraction = 1.0f / 1024.0f;

}  // namespace isocurv::mc
