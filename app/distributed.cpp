#include "app/distributed.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "core/atomic_file.h"
#include "core/error.h"
#include "dist/gather.h"
#include "dist/piece.h"
#include "dist/piece_file.h"
#include "dist/slabs.h"
#include "dist/totals.h"
#include "dist/world.h"
#include "io/field_arrays.h"
#include "mc/bricks.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/frame.h"

namespace isocurv::app {
namespace {

// Cells past the slab a rank extracts: snapping's and the ghost ring's (dist::kExtractGhostCells),
// plus, for curvature, the mesh estimator's neighbourhood: the scale's 3 sigma when given, else 8
// cells (the estimators' k-rings and automatic scales reach a few edges).
int margin_cells(const volume::Volume& v, const CommonOptions& o, DistributedWork work) {
  int margin = dist::kExtractGhostCells;
  if (work == DistributedWork::curvature) {
    double sigma = 0;
    for (const std::string& s : parse_scales(o.scale))
      if (s != "auto") sigma = std::max(sigma, std::stod(s));
    const openvdb::Vec3d h = v.spacing();
    const double step = std::min({h[0], h[1], h[2]});
    margin += sigma > 0 ? int(std::ceil(3 * sigma / step)) + 2 : 8;
  }
  return margin;
}

}  // namespace

void add_distributed_options(CLI::App& cmd, bool& gather) {
  cmd.add_flag("--gather", gather,
               "Under mpirun: rank 0 writes one mesh file (-o .vtp .ply ...) instead of a .pvtp and one piece "
               "per rank (docs/distributed.md)");
}

bool runs_distributed(const std::string& out, bool gather) {
  const bool pvtp = dist::is_pvtp(out);
  if (gather && pvtp) throw Error(out + ": --gather writes one mesh file (.vtp, .ply, ...), not a .pvtp");
  const dist::World& w = dist::World::get();
  if (!pvtp && !gather && w.size() > 1)
    throw Error("under mpirun with " + std::to_string(w.size()) + " ranks, -o must name a .pvtp (one piece per "
                "rank), or add --gather for one mesh file; " + out + " is neither");
  return pvtp || gather;
}

namespace {

// One rank's share of a distributed surface.
struct RankSurface {
  Surface s;  ///< the volume and isovalue (the local extraction is not kept)
  dist::Slabs slabs;
  dist::Piece piece;
  std::optional<curvature::CurvatureField> field;  ///< per piece vertex (curvature)
  dist::SurfaceTotals totals;
  StageTimer timer;
};

// Checks that every rank would refuse alike, before any work.
void refuse_undistributed(const std::string& in, const CommonOptions& o, DistributedWork work) {
  if (is_mesh_path(in))
    throw Error(in, "a distributed run takes a volume (each rank extracts its part); run a mesh file without mpirun");
  if (o.labelled()) throw Error("--labels and --label do not run distributed (run them without mpirun)");
  if (o.split) throw Error("--split needs --labels or --label");
  if (work != DistributedWork::curvature) return;
  if (!o.ao.empty() && o.ao != "griffin")
    throw Error("--ao-method " + o.ao + " does not run distributed (it casts rays across the whole surface)");
  // The volume estimator picks its automatic scale from the whole surface's noise and edges, and
  // treats a mesh's open edge as the volume's box: per piece it would differ from the single
  // process near the seams. The mesh estimators see their whole neighbourhood in the margin.
  if (curvature::estimator_name(default_estimator(o, true)) == std::string("volume"))
    throw Error("the volume estimator does not run distributed yet (its automatic scale is chosen over the "
                "whole surface); choose a mesh estimator, e.g. --estimator rusinkiewicz, or run without mpirun");
}

// Loads, divides, extracts this rank's slab and cuts its piece; estimates its curvature for
// `work` curvature; reduces the totals. Collective; throws on every rank when one failed.
void make_rank_surface(RankSurface& r, const std::string& in, const CommonOptions& o, DistributedWork work,
                       EmptySurface empty) {
  const dist::World& world = dist::World::get();
  StageTimer& timer = r.timer;
  volume::Volume v;
  float iso = 0;
  dist::together(world, [&] { v = load_volume(in, o, timer, &iso); });

  // Slabs balanced by the bricks that carry surface (every rank computes the same).
  mc::Options mo;
  mo.cap = o.cap;
  mo.snap = o.snap;
  const bool reference = reference_device(o);
  std::unique_ptr<mc::Mesher> mesher;
  timer.start("extract");
  dist::together(world, [&] {
    const mc::Frame whole = mc::make_frame(v, iso, mo);
    std::vector<openvdb::Coord> bricks;
    if (reference) {
      bricks = mc::BrickIndex(v).candidates(whole);
    } else {
      mesher = std::make_unique<mc::Mesher>(v, device_for(o));
      bricks = mesher->surface_bricks(iso, mo);
    }
    const int first = whole.cells.empty() ? 0 : (whole.cells.min().z() & ~7);
    const int layers = whole.cells.empty() ? 0 : (whole.cells.max().z() - first) / 8 + 1;
    std::vector<std::uint64_t> per_layer(std::size_t(std::max(layers, 0)), 0);
    for (const openvdb::Coord& b : bricks) ++per_layer[std::size_t((b.z() - first) / 8)];
    r.slabs = dist::balance_slabs(per_layer, first, world.size(), whole.key_origin.z());
  });

  // This rank's cells with their margin, and its piece.
  const auto [z0, z1] = r.slabs.extract_range(world.rank(), margin_cells(v, o, work));
  mo.cells_min[2] = z0;
  mo.cells_max[2] = z1;
  mo.keep_edge_keys = true;
  Mesh local;
  dist::together(world, [&] {
    local = reference ? mc::extract_reference(v, iso, mo) : mesher->extract(iso, mo);
    r.piece = dist::cut_piece(local, r.slabs, world.rank());
  });
  timer.stop();
  // The whole surface's counts; the empty surface is refused (curvature) or warned about (extract).
  const Vec3f origin = [&] {
    const openvdb::Vec3d c = v.grid->transform().indexToWorld(v.domain.getCenter());
    return Vec3f{float(c[0]), float(c[1]), float(c[2])};
  }();
  r.totals = dist::reduce_totals(world, r.piece, origin);
  r.s.volume = std::move(v);
  r.s.isovalue = iso;
  if (r.totals.triangles == 0)
    dist::together(world, [&] {
      handle_empty_surface(r.s, in, o, empty);
    });
  if (work == DistributedWork::curvature)
    dist::together(world, [&] {
      const curvature::CurvatureField f =
          estimate_curvature(local, &*r.s.volume, iso, o, timer, &r.s.normals, &r.s.estimator);
      r.field = io::select_vertices(f, r.piece.local_vertex);
    });
}

// Quiet on every rank but 0: one set of progress bars and warnings.
CommonOptions rank_options(const CommonOptions& options) {
  CommonOptions o = options;
  if (dist::World::get().rank() != 0) o.quiet = true;
  return o;
}

}  // namespace

nlohmann::json run_distributed(const std::string& in, const std::string& out, bool gather,
                               const CommonOptions& options, DistributedWork work) {
  const dist::World& world = dist::World::get();
  const CommonOptions o = rank_options(options);
  refuse_undistributed(in, o, work);
  if (work == DistributedWork::curvature) require_curvature_format(gather ? out : out + ".vtp");
  if (gather)
    dist::together(world, [&] {
      if (world.rank() == 0) require_writable_file(out);
    });
  else
    dist::require_writable_pieces(world, out);

  RankSurface rs;
  make_rank_surface(rs, in, o, work, work == DistributedWork::curvature ? EmptySurface::error : EmptySurface::warn);
  const dist::Piece& piece = rs.piece;
  const dist::SurfaceTotals& totals = rs.totals;
  StageTimer& timer = rs.timer;
  const curvature::CurvatureField* field = rs.field ? &*rs.field : nullptr;
  timer.start("write");
  const io::Metadata context = context_metadata(rs.s, in);
  if (gather)
    dist::write_gathered(world, out, piece, field, o.compress, &context);
  else
    dist::write_pieces(world, out, piece, field, o.compress, &context);
  timer.stop();

  nlohmann::json r = {{"vertices", totals.vertices},
                      {"triangles", totals.triangles},
                      {"area", totals.area},
                      {"enclosed_volume", totals.signed_volume},
                      {"euler_characteristic", totals.euler()},
                      {"components", totals.components},
                      {"boundary_edges", totals.boundary_edges},
                      {"watertight", totals.watertight()},
                      {"isovalue", rs.s.isovalue}};
  if (totals.genus() >= 0) r["genus"] = totals.genus();
  if (work == DistributedWork::curvature) {
    const nlohmann::json single = surface_report(rs.s);
    if (single.contains("estimator")) r["estimator"] = single["estimator"];
    if (single.contains("normals")) r["normals"] = single["normals"];
  }
  const std::vector<std::int64_t> piece_counts = [&] {
    std::vector<std::int64_t> mine(std::size_t(world.size()) * 3, 0);
    mine[std::size_t(world.rank()) * 3] = std::int64_t(piece.owned_triangles);
    mine[std::size_t(world.rank()) * 3 + 1] = std::int64_t(piece.mesh.triangles.size() - piece.owned_triangles);
    mine[std::size_t(world.rank()) * 3 + 2] = std::int64_t(std::count(piece.point_ghost.begin(), piece.point_ghost.end(), 0));
    return world.sum(mine);
  }();
  nlohmann::json ranks = nlohmann::json::array();
  for (int k = 0; k < world.size(); ++k) {
    const auto& c = rs.slabs.cuts;
    nlohmann::json slab = {{"rank", k}, {"triangles", piece_counts[std::size_t(k) * 3]},
                           {"ghost_triangles", piece_counts[std::size_t(k) * 3 + 1]},
                           {"vertices", piece_counts[std::size_t(k) * 3 + 2]}};
    if (k > 0) slab["z_from"] = c[std::size_t(k)];
    if (k + 1 < world.size()) slab["z_to"] = c[std::size_t(k) + 1] - 1;
    ranks.push_back(slab);
  }
  r["ranks"] = ranks;
  r["input"] = in;
  r["output"] = out;
  if (!gather) {
    nlohmann::json pieces = nlohmann::json::array();
    for (int k = 0; k < world.size(); ++k) pieces.push_back(dist::piece_path(out, k));
    r["pieces"] = pieces;
  }
  if (world.rank() == 0) r["output_bytes"] = file_bytes(out);
  r["compression"] = io::to_string(o.compress);
  r["device"] = device_name(o);
  r["timings_ms"] = timer.json();  // rank 0's
  return r;
}

bool finishes_on_rank_zero() { return dist::World::get().size() > 1; }

Surface gathered_surface(const std::string& in, const CommonOptions& options, StageTimer& timer,
                         DistributedWork work) {
  const dist::World& world = dist::World::get();
  const CommonOptions o = rank_options(options);
  refuse_undistributed(in, o, work);
  RankSurface rs;
  make_rank_surface(rs, in, o, work, EmptySurface::error);
  Surface s = std::move(rs.s);
  curvature::CurvatureField whole;
  rs.timer.start("gather");
  dist::together(world, [&] { dist::gather_mesh(world, rs.piece, rs.field ? &*rs.field : nullptr, s.mesh, whole); });
  rs.timer.stop();
  if (rs.field && world.rank() == 0) {
    whole.metadata = rs.field->metadata;
    s.field = std::move(whole);
  }
  timer = std::move(rs.timer);
  return s;
}

void print_distributed(const nlohmann::json& r, const CommonOptions& o) {
  if (dist::World::get().rank() != 0) return;
  if (o.json) {
    std::cout << r.dump(2) << "\n";
    return;
  }
  if (o.quiet) return;
  const std::size_t ranks = r["ranks"].size();
  std::cout << "wrote " << r["output"].get<std::string>();
  if (r.contains("pieces")) std::cout << " and " << ranks << " piece" << (ranks == 1 ? "" : "s");
  std::cout << " (" << ranks << " rank" << (ranks == 1 ? "" : "s") << "): " << r["vertices"] << " vertices, "
            << r["triangles"] << " triangles at isovalue " << r["isovalue"].get<float>() << "; "
            << r["components"] << " component" << (r["components"] == 1 ? "" : "s") << ", "
            << (r["watertight"].get<bool>() ? "watertight" : "open") << "\n";
}

}  // namespace isocurv::app
