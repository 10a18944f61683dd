#pragma once
// The whole surface on one rank: every piece's owned vertices (with their curvature arrays) and
// owned triangles sent to rank 0 and joined by global id, each vertex and triangle once. For
// --gather, and for the commands that finish on one process (run's picture, check's report).
// Tested in tests/dist/test_distributed.cpp (mpirun runs bit-identical to one process).
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "dist/piece.h"
#include "dist/world.h"

namespace isocurv::dist {

/// Collective. On rank 0, `mesh` becomes the whole surface, its vertices in increasing global id,
/// and (when `field` is given on every rank: the arrays of the piece's vertices) `whole` the
/// whole field; the other ranks' outputs are left empty. @throw Error on rank 0 when the pieces
/// do not fit (a vertex owned twice, a triangle using a vertex no piece owns); wrap the call in
/// together() so every rank hears of it.
void gather_mesh(const World& world, const Piece& piece, const curvature::CurvatureField* field, Mesh& mesh,
                 curvature::CurvatureField& whole);

}  // namespace isocurv::dist
