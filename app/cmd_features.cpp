// isocurv features VOLUME|MESH --radius R[,R...] -o MESH: neighbourhood
// features at a radius (several inputs or isovalues: a batch, app/batch.h).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "core/atomic_file.h"
#include "app/batch.h"
#include "app/commands.h"
#include "app/distributed.h"
#include "app/label_surfaces.h"
#include "app/pipeline.h"
#include "app/series.h"
#include "core/error.h"
#include "core/mesh_measures.h"
#include "features/features.h"
#include "io/mesh_file.h"
#include "labels/label_surfaces.h"

namespace isocurv::app {
namespace {

/// --radius "4,0.5,2%" -> radii in world units (features::parse_radii).
void radius_option(const std::string &list, double diagonal,
                 features::Options &o) {
  try {
    features::parse_radii(list, diagonal, o);
  } catch (const Error &e) {
    throw Error(std::string("--radius: ") + e.what());
  }
  if (o.radii.empty())
    throw Error("--radius: no radius given");
}

/// The command line's feature options.
struct FeaturesCli {
  std::string radius, list = "all";
  int samples = -1;
  bool adaptive = false;
};

/// The features --features asks for (fo.features). @throw Error for a bad list.
features::Options feature_selection(const FeaturesCli &c) {
  features::Options fo;
  if (c.list != "all")
    fo.features = features::parse_features(c.list);
  return fo;
}

/// The world length of the diagonal of `v`'s data domain (corner voxel to corner voxel).
double volume_box_diagonal(const volume::Volume &v) {
  const openvdb::Vec3d a = v.grid->transform().indexToWorld(v.domain.min().asVec3d()),
                       b = v.grid->transform().indexToWorld(v.domain.max().asVec3d());
  return (b - a).length();
}

/// What the features of one surface (or of every label's) add up to, for the report.
struct FeatureTally {
  std::vector<std::string> arrays;   ///< the feature arrays' names
  std::size_t boundary = 0;          ///< vertices flagged FeatureBoundary
  std::uint64_t samples_taken = 0;
  double traced_weighted = 0;        ///< traced_fraction times the vertices, summed
  std::size_t vertices = 0;
};

/// The features of `mesh` (with its readied curvature `field`, and the volume `vol` it was
/// extracted from at fo.isovalue, or none) added to field.extra (replacing arrays of the same
/// names a mesh file carried, and FeatureBoundary), counted into `tally`.
void add_features(const Mesh &mesh, curvature::CurvatureField &field, const volume::Volume *vol,
                  const features::Options &fo, const CommonOptions &o, StageTimer &timer,
                  FeatureTally &tally) {
  timer.start("features");
  features::FeatureField f = reference_device(o)
                                 ? features::compute(mesh, field, vol, fo)
                                 : features::compute(mesh, field, vol, fo, device_for(o));
  timer.stop();
  for (std::uint8_t b : f.boundary)
    tally.boundary += b;
  tally.samples_taken += f.samples_taken;
  tally.traced_weighted += f.traced_fraction * double(mesh.vertex_count());
  tally.vertices += mesh.vertex_count();
  auto &extra = field.extra; // a mesh file may carry features from an earlier run: replace them
  for (const auto &a : f.arrays)
    extra.erase(
        std::remove_if(extra.begin(), extra.end(),
                       [&](const auto &e) { return e.name == a.name; }),
        extra.end());
  extra.erase(std::remove_if(
                  extra.begin(), extra.end(),
                  [](const auto &e) { return e.name == "FeatureBoundary"; }),
              extra.end());
  const bool first = tally.arrays.empty();
  for (auto &a : f.arrays) {
    if (first) tally.arrays.push_back(a.name);
    extra.push_back({a.name, std::move(a.values)});
  }
  extra.push_back(
      {"FeatureBoundary",
       std::vector<float>(f.boundary.begin(), f.boundary.end())});
}

/// The sampling options of `c` for a surface of a volume (or none) at `isovalue`.
features::Options sampled_options(const FeaturesCli &c, features::Options fo, bool volume,
                                  float isovalue) {
  fo.isovalue = isovalue;
  fo.samples = c.samples >= 0 ? c.samples : (volume ? 256 : 0);
  fo.adaptive = c.adaptive;
  if (c.adaptive && fo.samples == 0)
    throw Error("--adaptive applies to sampled neighbourhoods (--samples N with a volume)");
  return fo;
}

/// The --json report of the features of `s`: surface_report and what `tally` counted.
nlohmann::json features_report(const Surface &s, const features::Options &fo,
                               const FeatureTally &tally, const CommonOptions &o) {
  nlohmann::json r = surface_report(s);
  nlohmann::json radii = nlohmann::json::array();
  for (std::size_t i = 0; i < fo.radii.size(); ++i)
    radii.push_back(
        {{"as_given", fo.radius_names[i]}, {"world", fo.radii[i]}});
  r["features"] = {
      {"radii", radii},
      {"arrays", tally.arrays},
      {"mean_curvature_from", s.volume ? "volume integral invariant" : "surface samples"},
      {"boundary_vertices", tally.boundary},
      {"neighbourhoods", fo.samples > 0 ? "sampled" : "exact"},
      {"samples", fo.samples},
      {"adaptive", fo.adaptive},
      {"samples_taken", tally.samples_taken},
      {"traced_fraction",
       tally.vertices ? tally.traced_weighted / double(tally.vertices) : 1.0},
      {"device", device_name(o)}};
  return r;
}

/// Computes the features of `s` (as loaded: a volume's isosurface or a mesh file) into its
/// field's extra arrays, readying the curvature first; returns the --json report without
/// input, output and timings.
nlohmann::json compute_features(Surface &s, const std::string &in, const CommonOptions &o,
                                const FeaturesCli &c, features::Options fo, StageTimer &timer) {
  const std::size_t nv = s.mesh.vertex_count();
  if (s.field && s.field->normals.size() == nv && s.field->area.size() == nv && !o.flip) {
    prepare_mesh_for_curvature(s, in, o);
    if (!s.field)  // welded: the file's curvature and arrays no longer apply
      s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o,
                                   timer, &s.normals);
  } else {
    reestimate_keeping_extras(s, in, o, timer);  // --flip or no field: the file's arrays stay
  }
  radius_option(c.radius, bounding_box_diagonal(s.mesh), fo);
  fo = sampled_options(c, fo, s.volume.has_value(), s.isovalue);
  FeatureTally tally;
  add_features(s.mesh, *s.field, s.volume ? &*s.volume : nullptr, fo, o, timer, tally);
  return features_report(s, fo, tally, o);
}

/// --labels: each label's features on its own surface and indicator (neighbourhoods never cross
/// into another label), its curvature first; a radius in % is of the label map's box diagonal
/// (one radius for every label). Returns the --json report; `s` gets the labels' surfaces.
nlohmann::json compute_label_features(Surface &s, const std::string &in, const CommonOptions &o,
                                      const FeaturesCli &c, features::Options fo,
                                      StageTimer &timer) {
  FeatureTally tally;
  LabelHooks hooks;
  hooks.margin = [&](const volume::Volume &map) {
    radius_option(c.radius, volume_box_diagonal(map), fo);
    fo = sampled_options(c, fo, true, labels::kIndicatorIsovalue);
    const openvdb::Vec3d sp = map.spacing();
    const double largest = *std::max_element(fo.radii.begin(), fo.radii.end());
    // the neighbourhoods reach the radius from the surface: keep them inside the indicator
    return int(std::ceil(largest / std::min({sp[0], sp[1], sp[2]}))) + 2;
  };
  hooks.field = [&](const Mesh &mesh, const volume::Volume &indicator,
                    curvature::CurvatureField &field) {
    add_features(mesh, field, &indicator, fo, o, timer, tally);
  };
  s = load_label_surfaces(in, o, timer, true, hooks);
  return features_report(s, fo, tally, o);
}

/// The features mesh: the surface with its curvature and feature arrays (uncompressed).
/// `report` is compute_features's: with one radius the arrays carry no _r suffix, so the file
/// says it as field data "feature_radius" (picture titles quote it).
void write_features(const std::string &path, const Surface &s, const std::string &in,
                    const nlohmann::json &report) {
  io::Metadata context = context_metadata(s, in);
  const nlohmann::json &radii = report["features"]["radii"];
  if (radii.size() == 1) context.emplace_back("feature_radius", radii[0]["as_given"].get<std::string>());
  io::write_mesh(path, s.mesh, &*s.field, {}, &context);
}

} // namespace

void register_features(CLI::App &app) {
  auto *cmd = app.add_subcommand(
      "features", "Neighbourhood features at a radius of support (Andreadis et "
                  "al.): LBE NSV Vr H_ii K_ii SI_ii");
  cmd->footer(
      "Example: isocurv features lobster.vol --radius 2%,4% -o "
      "lobster_features.vtp\n"
      "Radii in world units, or N% of the surface's bounding-box diagonal. "
      "With several radii each\n"
      "array is suffixed _r<radius as written> (H_ii_r2%). Vr needs a volume.");
  static CommonOptions o;
  static std::string out;
  static FeaturesCli c;
  static BatchCli b;
  static SeriesCli series;
  add_batch_options(*cmd, b, "VOLUME_OR_MESH", "Volume or mesh file", {"vtp", "ply"});
  cmd->add_option("-o,--output", out,
                  "Mesh file to write (.vtp or .ply), with the curvature and "
                  "feature arrays, or the folder of a batch")
      ->required();
  cmd->add_option("--radius", c.radius,
                  "Radius of support R[,R...] (world units, or N% of the "
                  "bounding-box diagonal)")
      ->required();
  cmd->add_option("--features", c.list,
                  "Comma-separated: LBE, NSV, Vr, H_ii, K_ii, SI_ii, or all "
                  "(those the input allows)")
      ->capture_default_str();
  cmd->add_option("--samples", c.samples,
                  "Samples per vertex for LBE, NSV and K_ii: N >= 32 traces N/16 curves "
                  "on the volume's isosurface (cost independent of the radius); 0 = the "
                  "exact neighbourhoods (the mesh's vertices within R, cost grows with R^2). "
                  "Default: 256 for a volume, 0 for a mesh file");
  cmd->add_flag("--adaptive", c.adaptive,
                "Sampled path: trace the second half of the curves only where the first "
                "half's mean curvatures disagree (two-stage adaptive sampling)");
  add_common_options(*cmd, o, false);
  add_curvature_options(*cmd, o, true);
  add_label_options(*cmd, o, false);
  add_series_options(*cmd, series);
  // One input -> `out`; prints its summary unless `quiet_summary` (a series frame). Returns the
  // --json report.
  static auto one = [](const std::string& in, const std::string& out, CommonOptions& o,
                       bool quiet_summary) -> nlohmann::json {
    require_curvature_format(out);
    require_writable_file(out);  // before any work
    const features::Options fo = feature_selection(c);
    StageTimer timer;
    std::optional<Surface> on_zero;
    nlohmann::json r;
    if (o.labelled()) {
      on_zero.emplace();
      r = compute_label_features(*on_zero, in, o, c, fo, timer);
    } else {
      // Under mpirun: the ranks extract the surface together, rank 0 computes the features.
      on_zero = surface_for_rank_zero(in, o, timer, DistributedWork::extract,
                                      WholeVolume::on_rank_zero);
      if (!on_zero) return nlohmann::json::object();
      r = compute_features(*on_zero, in, o, c, fo, timer);
    }
    Surface& s = *on_zero;
    timer.start("write");
    write_features(out, s, in, r);
    timer.stop();
    r["input"] = in;
    r["output"] = out;
    r["timings_ms"] = timer.json();
    if (quiet_summary) {
    } else if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << ": " << s.mesh.vertex_count()
                << " vertices, " << r["features"]["arrays"].size()
                << " feature arrays (features "
                << format_number(timer.json().value("features", 0.0)) << " ms; "
                << r["features"]["boundary_vertices"].get<std::size_t>()
                << " vertices whose neighbourhood left the data flagged "
                   "FeatureBoundary)\n";
    }
    return r;
  };
  // A batch entry: the same computation and file; stats.json holds the --json report.
  static const BatchStep step{
      "features", true, [](Surface& s, const std::string& in, StageTimer& timer) {
        BatchStep::Output out;
        out.report = compute_features(s, in, o, c, feature_selection(c), timer);
        out.write = [&s, in, report = out.report](const std::string& path) {
          write_features(path, s, in, report);
        };
        out.summary_keys = {"vertices", "triangles", "features"};
        return out;
      }};
  cmd->callback([] {
    if (series.enabled) {
      require_series_cli(b, o);
      run_series(b.inputs, series, {"features", out}, o,
                 [](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                   return one(f.path, path, fo, true);
                 });
      return;
    }
    // A batch checks first what every entry would fail on: --features, the radii as written.
    if (run_as_batch(b, o, step, out, [] {
          feature_selection(c);
          features::Options probe;
          radius_option(c.radius, 1.0, probe);
        }))
      return;
    one(b.inputs.front(), out, o, false);
  });
}

} // namespace isocurv::app
