#pragma once
// Validation of the curvature stage's input, shared by the kernels' host code and the reference.
// Tested in tests/curvature/estimator_bad_input_test.cpp (every estimator's refusals).
#include "core/mesh.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Throws isocurv::Error (one line naming the problem) when the mesh or options cannot be used:
/// a triangle index out of range, a non-finite vertex coordinate, more than 2^32 - 1 corners,
/// options.vertex_normals of the wrong size, or a non-finite options.ao_scale. Degenerate but
/// valid input (zero-area or repeated-index triangles, isolated or duplicate vertices) passes.
void check_input(const Mesh& mesh, const Options& options);

/// The triangle part of check_input: at most 2^32 - 1 vertices and corners, every index below
/// vertex_count. Throws isocurv::Error naming the first bad triangle.
void check_triangles(const Triangles& triangles, std::size_t vertex_count);

/// The position part of check_input: every coordinate finite. Throws isocurv::Error naming the
/// first bad vertex.
void check_positions(const Positions& positions);

/// The option part of check_input for a mesh of vertex_count vertices: vertex_normals of that
/// size (when given), a finite ao_scale.
void check_options(const Options& options, std::size_t vertex_count);

}  // namespace isocurv::curvature
