#pragma once
// `mpirun -np N isocurv extract|curvature VOLUME -o out.pvtp [--gather]`: one surface made by
// several ranks (dist/). Each rank extracts its slab of the volume (dist/slabs.h) with a margin,
// cuts its piece out (dist/piece.h), estimates curvature there when asked, and writes its piece;
// rank 0 writes the .pvtp, the one report and the totals (dist/totals.h). docs/distributed.md.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "app/pipeline.h"

namespace isocurv::app {

/// What each rank computes on its piece.
enum class DistributedWork { extract, curvature };

/// Adds --gather (one mesh file from rank 0 instead of a .pvtp and its pieces).
void add_distributed_options(CLI::App& cmd, bool& gather);

/// True when the command is to run distributed: -o names a .pvtp, or --gather was given (these
/// work at any rank count, one included, with or without mpirun). Several ranks with neither is
/// an Error (each would write the same file); so is --gather with a .pvtp.
bool runs_distributed(const std::string& out, bool gather);

/// Runs `work` distributed on the volume `in`, writing `out` (.pvtp and pieces, or with `gather`
/// one mesh file). Returns the report --json prints (on every rank; counts are the whole
/// surface's). @throw Error on every rank, with the first failing rank's message, when any failed.
nlohmann::json run_distributed(const std::string& in, const std::string& out, bool gather,
                               const CommonOptions& o, DistributedWork work);

/// True under mpirun with several ranks: the commands that finish on one process (run, check,
/// features) take their surface from gathered_surface, and only rank 0 goes on from there.
bool finishes_on_rank_zero();

/// Collective: the volume `in`'s isosurface made by every rank as run_distributed makes it (with
/// `work` curvature, each piece's curvature by a mesh estimator), gathered on rank 0: there, the
/// whole mesh (vertices in increasing global id), its field, the volume and isovalue, as
/// load_surface (and estimate_curvature) would give on one process; on the other ranks the same
/// without a mesh. Uncompressed raw, NRRD, MetaImage and NIfTI files are read in part, so rank 0's volume holds only its slab
/// (Volume::slab) unless `whole_volume` asks for all of it (features integrates over it).
/// `timer` receives the stages. @throw Error on every rank when one failed.
enum class WholeVolume { not_needed, on_rank_zero };
Surface gathered_surface(const std::string& in, const CommonOptions& o, StageTimer& timer,
                         DistributedWork work, WholeVolume whole_volume = WholeVolume::not_needed);

/// The surface of a command that finishes on one process (run, check, features): under mpirun
/// with several ranks, gathered_surface's on rank 0 and nothing on the others (which are done);
/// otherwise load_surface's. Collective under mpirun.
std::optional<Surface> surface_for_rank_zero(const std::string& in, const CommonOptions& o, StageTimer& timer,
                                             DistributedWork work,
                                             WholeVolume whole_volume = WholeVolume::not_needed);

/// Prints `r` as extract and curvature print a single run's result (rank 0 only).
void print_distributed(const nlohmann::json& r, const CommonOptions& o);

}  // namespace isocurv::app
