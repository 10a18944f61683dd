#include "app/distributed.h"

#include <malloc.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/series.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "curvature/auto_scale.h"
#include "curvature/detail/volume_setup.h"
#include "curvature/volume_estimate.h"
#include "dist/gather.h"
#include "dist/piece.h"
#include "dist/piece_file.h"
#include "dist/slabs.h"
#include "dist/surface_piece.h"
#include "dist/totals.h"
#include "dist/volume_stats.h"
#include "dist/world.h"
#include "io/field_arrays.h"
#include "mc/bricks.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/frame.h"
#include "volume/load.h"
#include "volume/prefilter.h"
#include "volume/pyramid.h"

namespace isocurv::app {
namespace {

// Cells past the slab a rank extracts: snapping's and the ghost ring's (dist::kExtractGhostCells),
// plus, for curvature, the estimator's reach around the piece's vertices:
//  - the volume estimator's smoothing at its largest scale (the one given, else the per-vertex
//    choice's cap, curvature::kAdaptiveMaxVoxels): the samples its pyramid level reads
//    (volume::pyramid_support: the prefilter's taps, the B-spline's and the decimations'), and
//    for binary volumes the move to the smoothed surface
//    (kMaxShiftVoxels voxels plus kShrinkScales sigma); the box test's kSupportDeviations and
//    the choice's regions (2 kRegionScales sigma) lie inside that;
//  - a mesh estimator's neighbourhood: the scale's 3 sigma when given, else 8 cells (the
//    estimators' k-rings and automatic scales reach a few edges).
int margin_cells(const volume::Volume& v, const CommonOptions& o, DistributedWork work) {
  int margin = dist::kExtractGhostCells;
  if (work != DistributedWork::curvature) return margin;
  double sigma = 0;
  for (const std::string& s : parse_scales(o.scale))
    if (s != "auto") sigma = std::max(sigma, std::stod(s));
  const openvdb::Vec3d h = v.spacing();
  const double step = h[2];  // the slabs are cut along index z
  if (curvature::needs_volume(default_estimator(o, true))) {
    if (sigma == 0 || o.scale.find("auto") != std::string::npos)
      sigma = std::max(sigma, curvature::kAdaptiveMaxVoxels * std::cbrt(h[0] * h[1] * h[2]));
    const double largest = std::max({h[0], h[1], h[2]});
    sigma = std::max(sigma, 1.01 * volume::kMinScaleVoxels * largest);  // auto_scale's floor
    const double reach = volume::pyramid_support(volume::Pyramid(v), sigma, 2,
                                                 0.5 * step + curvature::kMaxShiftVoxels * largest +
                                                     curvature::detail::kShrinkScales * sigma);
    return margin + int(std::ceil(reach / step)) + 1;
  }
  return margin + (sigma > 0 ? int(std::ceil(3 * sigma / std::min({h[0], h[1], h[2]}))) + 2 : 8);
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
}

// Voxels a rank reads past the cells it extracts: the upper sample of its last cells, and the
// gradient normals' stencil (central differences, interpolated) around its vertices.
constexpr int kReadApron = 4;

// What a rank needs before extracting: its part of the volume, the isovalue, the slabs.
struct RankVolume {
  volume::Volume v;
  float iso = 0;
  dist::Slabs slabs;
  std::unique_ptr<mc::Mesher> mesher;  // on v (device runs)
};

// The surface bricks `bricks` (origins) per brick layer of the whole frame `whole`, those with
// index z in [from, to] only.
dist::LayerBricks count_layers(const mc::Frame& whole, const std::vector<openvdb::Coord>& bricks, int from = INT_MIN,
                               int to = INT_MAX) {
  std::vector<int> z;
  z.reserve(bricks.size());
  for (const openvdb::Coord& b : bricks) z.push_back(b.z());
  return whole.cells.empty() ? dist::LayerBricks{}
                             : dist::count_layer_bricks(whole.cells.min().z(), whole.cells.max().z(), z, from, to);
}

// The whole volume on every rank (formats that cannot be read in part, and features, which
// integrate over the whole volume on rank 0): slabs from the mesher's own surface bricks.
void load_whole(RankVolume& rv, const std::string& in, const CommonOptions& o, const mc::Options& mo,
                StageTimer& timer) {
  const dist::World& world = dist::World::get();
  dist::together(world, [&] { rv.v = load_volume(in, o, timer, &rv.iso); });
  timer.start("extract");
  dist::together(world, [&] {
    const mc::Frame whole = mc::make_frame(rv.v, rv.iso, mo);
    std::vector<openvdb::Coord> bricks;
    if (reference_device(o)) {
      bricks = mc::BrickIndex(rv.v).candidates(whole);
    } else {
      rv.mesher = std::make_unique<mc::Mesher>(rv.v, device_for(o));
      bricks = rv.mesher->surface_bricks(rv.iso, mo);
    }
    const dist::LayerBricks layers = count_layers(whole, bricks);
    rv.slabs = dist::balance_slabs(layers.counts, layers.first_layer_z, world.size(), whole.key_origin.z());
  });
}

// Raw, NRRD (raw encoding), MetaImage (binary) and .nii files, read in part (volume::LoadOptions::z_slab): first an even
// share of the slices, from which the whole volume's statistics (so the single process's default
// isovalue) and its surface bricks per layer are reduced over the ranks; then only the slab this
// rank extracts, with its margin, its non-finite voxels given the whole volume's outside value.
// `probe` (the file's first block of slices) gives the depth and which side is inside.
void load_in_part(RankVolume& rv, const std::string& in, const CommonOptions& o, const mc::Options& mo, int margin,
                  volume::Volume probe, StageTimer& timer) {
  const dist::World& world = dist::World::get();
  const volume::LoadOptions lo = to_load_options(o.volume);
  const int depth = probe.domain.max().z() + 1, blocks = (depth + 7) / 8;
  const int b0 = int((long long)blocks * world.rank() / world.size());
  const int b1 = int((long long)blocks * (world.rank() + 1) / world.size());
  timer.start("load");
  std::optional<volume::Volume> share;  // none when there are more ranks than 8-slice blocks
  dist::together(world, [&] {
    if (b1 == b0) return;
    volume::LoadOptions so = lo;
    so.z_slab = {{8 * b0, 8 * b1 - 1}};
    share = volume::load(in, so);
  });
  probe.stats = dist::reduce_stats(world, share ? &*share : nullptr, in);
  dist::together(world, [&] { rv.iso = checked_isovalue(in, probe, o.iso); });
  timer.start("extract");
  // The surface bricks of this rank's share, per brick layer of the whole frame.
  const mc::Frame whole = mc::make_frame(probe, rv.iso, mo);
  dist::LayerBricks layers = count_layers(whole, {}), leaves = layers;
  dist::together(world, [&] {
    if (!share) return;
    share->stats = probe.stats;
    layers = count_layers(whole, mc::BrickIndex(*share).candidates(mc::make_frame(*share, rv.iso, mo)), 8 * b0,
                          8 * b1 - 1);
    std::vector<openvdb::Coord> leaf_origins;  // the share's blocks that are not constant
    for (auto leaf = share->grid->tree().cbeginLeaf(); leaf; ++leaf) leaf_origins.push_back(leaf->origin());
    leaves = count_layers(whole, leaf_origins, 8 * b0, 8 * b1 - 1);
  });
  share.reset();
#ifdef __GLIBC__
  malloc_trim(0);  // the share's pages back to the system before the slab is read (retain_freed_memory keeps them)
#endif
  // Surface bricks and leaves per layer, summed over the shares (one reduction).
  std::vector<std::int64_t> mine(layers.counts.begin(), layers.counts.end());
  mine.insert(mine.end(), leaves.counts.begin(), leaves.counts.end());
  const std::vector<std::int64_t> counts = world.sum(mine);
  const std::size_t n = layers.counts.size();
  // Each rank reads its slab: the layers' blocks weigh in beside their surface (dist/slabs.h).
  const openvdb::Coord dim = probe.domain.dim();
  const std::uint64_t blocks_per_layer = std::uint64_t((dim.x() + 7) / 8) * std::uint64_t((dim.y() + 7) / 8);
  rv.slabs = dist::balance_slabs(
      dist::read_in_part_costs(std::vector<std::uint64_t>(counts.begin(), counts.begin() + std::ptrdiff_t(n)),
                               std::vector<std::uint64_t>(counts.begin() + std::ptrdiff_t(n), counts.end()),
                               blocks_per_layer),
      layers.first_layer_z, world.size(), whole.key_origin.z());
  // This rank's slab, its margin and the apron.
  timer.start("load");
  const auto [z0, z1] = rv.slabs.extract_range(world.rank(), margin);
  dist::together(world, [&] {
    volume::LoadOptions so = lo;
    so.z_slab = {{int(std::max<long long>((long long)z0 - kReadApron, 0)),
                  int(std::min<long long>((long long)z1 + 1 + kReadApron, depth - 1))}};
    so.outside = float(probe.inside == volume::Inside::Above ? probe.stats.min : probe.stats.max);
    rv.v = volume::load(in, so);
    rv.v.stats = probe.stats;
  });
  timer.start("extract");
  dist::together(world, [&] {
    if (!reference_device(o)) rv.mesher = std::make_unique<mc::Mesher>(rv.v, device_for(o));
  });
}

// The estimator's counts over the whole surface (each rank's own vertices), in place of this
// rank's, which count its extraction's margin too. A volume estimate flags every vertex whose
// smoothing reaches the box's cut Boundary (the cut's own vertices among them), so on a dense
// volume those are its Boundary vertices. Collective.
void reduce_estimator_counts(RankSurface& r, const dist::World& world) {
  const curvature::CurvatureField& f = *r.field;
  curvature::EstimatorReport& e = r.s.estimator;
  const std::vector<float>* scale = nullptr;
  for (const auto& [name, values] : f.extra)
    if (name == "Scale") scale = &values;
  double asked = 0;
  for (const auto& [name, value] : e.parameters)
    if (name == "scale") asked = value;
  const bool box = e.estimator == "volume" && r.s.volume->dense && !r.s.volume->domain.empty();
  std::vector<std::int64_t> counts(3, 0);
  for (std::size_t i = 0; i < r.piece.point_ghost.size(); ++i) {
    if (r.piece.point_ghost[i]) continue;
    counts[0] += !f.unreliable.empty() && f.unreliable[i];
    counts[1] += scale && (*scale)[i] < float(asked);
    counts[2] += box && !f.boundary.empty() && f.boundary[i];
  }
  counts = world.sum(counts);
  e.unreliable = std::size_t(counts[0]);
  e.finer_scale = std::size_t(counts[1]);
  e.outside = std::size_t(counts[2]);
}

// Loads, divides, extracts this rank's slab and cuts its piece; estimates its curvature for
// `work` curvature; reduces the totals. Collective; throws on every rank when one failed.
// `in_part`: uncompressed files (volume::LoadOptions::z_slab) may be read in part (not for features, which need the whole
// volume on rank 0).
void make_rank_surface(RankSurface& r, const std::string& in, const CommonOptions& o, DistributedWork work,
                       EmptySurface empty, bool in_part = true) {
  const dist::World& world = dist::World::get();
  StageTimer& timer = r.timer;
  mc::Options mo;
  mo.cap = o.cap;
  mo.snap = o.snap;
  RankVolume rv;
  // Can this file be read in part? Its first block of slices says (and gives its depth).
  std::optional<volume::Volume> probe;
  if (in_part && world.size() > 1)
    dist::together(world, [&] {
      volume::LoadOptions po = to_load_options(o.volume);
      po.z_slab = {{0, 0}};
      timer.start("load");
      volume::Volume p = volume::load(in, po);
      if (p.slab) probe = std::move(p);
    });
  // The probe's reading: the same file on every rank, so every rank takes the same branch.
  if (probe) {
    const int margin = margin_cells(*probe, o, work);
    load_in_part(rv, in, o, mo, margin, std::move(*probe), timer);
  } else {
    load_whole(rv, in, o, mo, timer);
  }
  volume::Volume& v = rv.v;
  const float iso = rv.iso;
  r.slabs = rv.slabs;
  std::unique_ptr<mc::Mesher>& mesher = rv.mesher;
  const bool reference = reference_device(o);

  // This rank's cells with their margin, and its piece.
  const auto [z0, z1] = r.slabs.extract_range(world.rank(), margin_cells(v, o, work));
  mo.cells_min[2] = z0;
  mo.cells_max[2] = z1;
  mo.keep_edge_keys = true;
  Mesh local;
  dist::together(world, [&] {
    local = reference ? mc::extract_reference(v, iso, mo) : mesher->extract(iso, mo);
    timer.start("piece");
    r.piece = dist::cut_piece(local, r.slabs, world.rank());
  });
  timer.start("totals");
  // The whole surface's counts; the empty surface is refused (curvature) or warned about (extract).
  const Vec3f origin = [&] {
    const openvdb::Vec3d c = v.grid->transform().indexToWorld(v.domain.getCenter());
    return Vec3f{float(c[0]), float(c[1]), float(c[2])};
  }();
  r.totals = dist::reduce_totals(world, r.piece, origin);
  timer.stop();
  r.s.volume = std::move(v);
  r.s.isovalue = iso;
  if (r.totals.triangles == 0)
    dist::together(world, [&] {
      handle_empty_surface(r.s, in, o, empty);
    });
  if (work == DistributedWork::curvature)
    dist::together(world, [&] {
      // The whole-surface quantities (the volume estimator's scale, the AO scale) reduced over
      // the ranks' own vertices and triangles.
      const dist::RankPiece own(world, local, r.slabs, r.piece);
      const curvature::CurvatureField f =
          estimate_curvature(local, &*r.s.volume, iso, o, timer, &r.s.normals, &r.s.estimator, &own);
      r.field = io::select_vertices(f, r.piece.local_vertex);
    });
  if (work == DistributedWork::curvature) reduce_estimator_counts(r, world);
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
  std::unique_ptr<NewFolder> pieces_folder;  // rank 0's: gone again if nothing lands in it
  if (gather)
    dist::together(world, [&] {
      if (world.rank() == 0) require_writable_file(out);
    });
  else
    pieces_folder = dist::require_writable_pieces(world, out);

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
  constexpr std::size_t kPer = 4;  // per rank: triangles, ghost triangles, vertices, peak memory
  const std::vector<std::int64_t> piece_counts = [&] {
    std::vector<std::int64_t> mine(std::size_t(world.size()) * kPer, 0);
    std::int64_t* at = &mine[std::size_t(world.rank()) * kPer];
    at[0] = std::int64_t(piece.owned_triangles);
    at[1] = std::int64_t(piece.mesh.triangles.size() - piece.owned_triangles);
    at[2] = std::int64_t(std::count(piece.point_ghost.begin(), piece.point_ghost.end(), 0));
    at[3] = std::int64_t(std::max(peak_rss_kb(), 0L)) * 1024;  // VmHWM (app/series.h); 0 if unknown
    return world.sum(mine);
  }();
  nlohmann::json ranks = nlohmann::json::array();
  for (int k = 0; k < world.size(); ++k) {
    const auto& c = rs.slabs.cuts;
    const std::int64_t* at = &piece_counts[std::size_t(k) * kPer];
    nlohmann::json slab = {{"rank", k}, {"triangles", at[0]}, {"ghost_triangles", at[1]}, {"vertices", at[2]},
                           {"peak_memory_bytes", at[3]}};
    if (k > 0) slab["z_from"] = c[std::size_t(k)];
    if (k + 1 < world.size()) slab["z_to"] = c[std::size_t(k) + 1] - 1;
    ranks.push_back(slab);
  }
  r["ranks"] = ranks;
  if (rs.s.volume && rs.s.volume->slab)  // read in part (volume::LoadOptions::z_slab): this rank's slices
    r["read"] = "in part: each rank its slab, margin and apron";
  else
    r["read"] = world.size() > 1 ? "whole, by every rank" : "whole";
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
                         DistributedWork work, WholeVolume whole_volume) {
  const dist::World& world = dist::World::get();
  const CommonOptions o = rank_options(options);
  refuse_undistributed(in, o, work);
  RankSurface rs;
  // features integrates over the whole volume on rank 0: every rank reads it whole.
  make_rank_surface(rs, in, o, work, EmptySurface::error, whole_volume == WholeVolume::not_needed);
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

std::optional<Surface> surface_for_rank_zero(const std::string& in, const CommonOptions& o, StageTimer& timer,
                                             DistributedWork work, WholeVolume whole_volume) {
  if (!finishes_on_rank_zero()) return load_surface(in, o, timer);
  Surface s = gathered_surface(in, o, timer, work, whole_volume);
  if (dist::World::get().rank() != 0) return std::nullopt;
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
