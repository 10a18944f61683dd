#pragma once
// Thresholds shared by the double reference and the float kernels (passed to the OpenCL build as
// macros), so both skip the same degenerate triangles.
// Tested through the kernels beside their references:
// tests/curvature/mesh_estimator_kernels_test.cpp.

namespace isocurv::curvature {

/// A triangle's least-squares system is singular (its edges do not span a plane: zero area or a
/// needle) when an LDL^T pivot is not above this fraction of the largest diagonal entry. The
/// system's diagonal scales with squared edge lengths, so this is about aspect ratio^2.
inline constexpr double kPivotTolerance = 1e-5;

/// Frames whose normals n, m have 1 + n.m below this are treated as opposite (a flipped
/// triangle): the rotation between them is then a half turn about the first tangent.
inline constexpr double kOppositeNormals = 1e-6;

}  // namespace isocurv::curvature
