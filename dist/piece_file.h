#pragma once
// A distributed surface on disk, as ParaView and VTK's vtkXMLPPolyDataReader read it: `out.pvtp`
// naming one `.vtp` per rank in the folder `out/` (out/out_0.vtp, ...), each piece carrying
// vtkGlobalPointIds (the edge keys) and vtkGhostType on points and cells; or, with --gather, one
// `.vtp` (or .ply .obj .stl) written by rank 0 with each vertex and triangle once.
//
// All or nothing: every rank writes its piece under a temporary name; only when all succeeded are
// they renamed into place, and rank 0 writes the .pvtp last. Any failure leaves no new piece and
// no .pvtp (an existing .pvtp stays as it was).
// Tested in tests/dist/test_distributed.cpp (.pvtp pieces and gathered .vtp).
#include <memory>
#include <string>

#include "curvature/curvature_field.h"
#include "dist/piece.h"
#include "dist/world.h"
#include "io/compression.h"
#include "io/mesh_file.h"

namespace isocurv {
class NewFolder;
}

namespace isocurv::dist {

/// The piece file of rank `rank` for `pvtp` ("dir/out.pvtp" -> "dir/out/out_<rank>.vtp"), and
/// its name relative to the .pvtp's folder ("out/out_<rank>.vtp").
std::string piece_path(const std::string& pvtp, int rank);
std::string piece_source(const std::string& pvtp, int rank);

/// True for a path ending in .pvtp (case-insensitive).
bool is_pvtp(const std::string& path);

/// Collective, before any work: every rank checks that it can write its piece (the pieces' folder
/// is created by rank 0 first) and rank 0 that it can write `pvtp`. @throw Error (every rank,
/// naming the first rank that cannot) otherwise. Rank 0 gets the folder's guard: keep it until
/// the pieces are written, so that a failure (or a signal) before then takes a new, still empty
/// folder away again (NewFolder); the other ranks get nullptr.
std::unique_ptr<NewFolder> require_writable_pieces(const World& world, const std::string& pvtp);

/// Collective: writes every rank's `piece` (with `field`, per piece vertex, when given, and the
/// `context` field data) and then `pvtp`, as above. @throw Error on every rank when any failed.
void write_pieces(const World& world, const std::string& pvtp, const Piece& piece,
                  const curvature::CurvatureField* field, const io::Compression& compression,
                  const io::Metadata* context);

/// Collective: rank 0 assembles the owned vertices (in increasing global id) and triangles of every
/// piece into one mesh (and field, when every rank passes one) and writes it to `path` with
/// io::write_mesh; the other ranks write nothing. @throw Error on every rank when it failed.
void write_gathered(const World& world, const std::string& path, const Piece& piece,
                    const curvature::CurvatureField* field, const io::Compression& compression,
                    const io::Metadata* context);

}  // namespace isocurv::dist
