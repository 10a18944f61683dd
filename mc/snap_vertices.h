#pragma once
// Vertex snapping (after SnapMC, Raman and Wenger 2008): marching-cubes vertices close to one voxel
// are merged into one, so voxels at (or very near) the isovalue leave no clusters of nearly
// coincident vertices and no sliver triangles. Where SnapMC puts the vertex on the voxel (up to
// the snap distance off the isosurface), a lone group here takes its vertices' centroid, which
// stays near the isosurface they all lie on: curvature from the mesh keeps its accuracy.
//
// Where SnapMC extends the case table to 3^8 configurations, this pass works on the fused mesh the
// mesher already made: the vertices listed as near one voxel are collapsed onto it, a connected
// group at a time, and a collapse is made only where the result stays a 2-manifold with a
// consistent winding and no triangle below a minimum area or flipped against its former normal;
// elsewhere the vertices keep their place. Applied identically after the device mesher and the
// C++ reference (both list the same vertices), so the two still agree.
// Tested in tests/mc/snap_test.cpp.
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "mc/frame.h"

namespace isocurv::mc {

/// Set in SnapCandidate::edge when the vertex lies near the edge's upper end (else its lower end).
constexpr std::uint64_t kSnapUpper = std::uint64_t(1) << 63;

/// Smallest triangle area a collapse may leave, in voxel faces (index units).
constexpr double kSnapMinArea = 1e-6;

/// A vertex the mesher found within the snap distance of one end of its edge.
struct SnapCandidate {
  std::uint64_t edge;    ///< its edge's key (mc/edge_key.h), kSnapUpper set for the upper end
  std::uint32_t vertex;  ///< its index in the mesh
};

/// What a snapping pass did.
struct SnapReport {
  std::size_t candidates = 0;  ///< vertices listed as near a voxel (alone at theirs: left as they are)
  std::size_t moved = 0;       ///< merged vertices placed (one a fan)
  std::size_t merged = 0;      ///< vertices removed by merging into another
  std::size_t vanished = 0;    ///< other vertices removed: every triangle of theirs collapsed
  std::size_t dropped = 0;     ///< triangles removed (collapsed to an edge or a point)
  std::size_t split = 0;       ///< voxels where the surface meets in several fans, one vertex each
  std::size_t kept = 0;        ///< candidates not merged (a collapse there would break the mesh)
  std::size_t pushed = 0;      ///< of those, vertices moved along their edge out to `push`
};

/// Snaps the listed vertices of `mesh` (a marching-cubes mesh from `frame`) onto their voxels,
/// voxel by voxel. The triangles with two or more of a voxel's vertices collapse; the others form
/// fans around the voxel, joined across each spoke as they were joined around its outer vertex.
/// One fan (the usual case) puts its vertex at the centroid of the voxel's vertices (on the voxel
/// where the centroid would leave a bad triangle); several (sheets of the surface touching
/// there, or a tunnel narrower than the snap distance pinched to a point) each get a vertex of
/// their own, 2/1024 voxel from it towards the fan, so no two vertices coincide and no edge or
/// vertex becomes non-manifold. Where a fan would not be a disc, or a triangle would fall below
/// `min_area` (in voxel faces: index units^2) or turn over, that voxel's vertices are not merged: each moves
/// instead along its own cube edge, away from the voxel, to `push` (a fraction of the edge; the
/// snap distance), so the triangles between them grow from about 1e-6 voxel^2 (the mesher's
/// 1/1024-voxel nudge) to about push^2 with the mesh's connectivity unchanged; where that would
/// turn a triangle over they stay where they were.
/// Vertices merged away or left without triangles, and collapsed triangles, are removed (the rest
/// keep their order; `mesh.edge_keys`, when present, follows the vertices). The result depends
/// only on the mesh's geometry and the candidates' edges, not on vertex numbering or candidate
/// order. Every judgement (areas, turning over, the fans' offsets, how far a vertex lies along
/// its edge) is made in index space, through the frame's inverse map: the same volume at another
/// spacing or origin snaps the same vertices.
SnapReport snap_vertices(Mesh& mesh, std::vector<SnapCandidate> candidates, const Frame& frame,
                         double min_area, double push);


}  // namespace isocurv::mc
