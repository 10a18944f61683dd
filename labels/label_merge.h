#pragma once
// The surfaces of several labels as one mesh: positions and triangles concatenated, their
// curvature arrays too, and a "Label" array on the vertices (CurvatureField::extra) and on the
// triangles, as one mesh file holding every label.
// Tested in tests/labels/test_label_map.cpp.
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::labels {

/// Where one label's surface lies in a LabelledMesh.
struct LabelPart {
  std::int64_t value = 0;
  std::uint32_t first_vertex = 0, vertices = 0;
  std::size_t first_triangle = 0, triangles = 0;
  /// True when vertex `v` of the merged mesh belongs to this label.
  bool holds_vertex(std::uint32_t v) const { return v >= first_vertex && v - first_vertex < vertices; }
};

/// Several labels' surfaces in one mesh. Labels never share a vertex, so each label's surface
/// keeps its own components (touching labels each stay closed).
struct LabelledMesh {
  Mesh mesh;
  /// The parts' fields concatenated (surface_points too): an array is kept when every part with
  /// vertices had it (else it is left empty); the metadata is the first part's. Its extra "Label" array holds each
  /// vertex's label (as a float: exact, labels are below 2^24).
  curvature::CurvatureField field;
  std::vector<std::int32_t> triangle_labels;  ///< each triangle's label ("Label" cell array)
  std::vector<LabelPart> parts;               ///< in the order appended
};

/// Appends label `value`'s surface `mesh` (with its curvature `field`, or none) to `into`.
/// @throw Error when the merged mesh would pass 2^32 - 1 vertices, or `field`'s arrays do not
///        have one entry per vertex of `mesh`.
void append_label(LabelledMesh& into, std::int64_t value, const Mesh& mesh,
                  const curvature::CurvatureField* field);

/// The part of `m` holding label `value`, as a mesh of its own (vertex ids from 0) with its field;
/// empty when `m` has no such label.
void extract_label(const LabelledMesh& m, std::int64_t value, Mesh& mesh,
                   curvature::CurvatureField& field);

/// The same for one part of a merged mesh and field (as LabelledMesh holds them), without a
/// LabelledMesh: `part` must be one of the merged mesh's parts.
void extract_label(const Mesh& merged, const curvature::CurvatureField& merged_field,
                   const LabelPart& part, Mesh& mesh, curvature::CurvatureField& field);

}  // namespace isocurv::labels
