// isocurv compare VOLUME|MESH: every mesh curvature estimator on the same surface, side by side.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/label_surfaces.h"
#include "app/pipeline.h"
#include "core/error.h"
#include "core/mesh_measures.h"
#include "curvature/ao_scale.h"
#include "curvature/estimator.h"
#include "curvature/field_stats.h"
#include "curvature/mesh_estimators.h"
#include "curvature/request.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "volume/gradient_normals.h"

namespace isocurv::app {
namespace {

using curvature::CurvatureField;

constexpr double kPercentiles[3] = {1, 50, 99};

// Vertices every statistic counts for one estimator: those the other commands' statistics count
// (curvature::counted_vertices: measured, finite, max(|k1|, |k2|) at most 1 / (half the mean
// edge length)), less those on an open boundary.
std::vector<bool> counted(const CurvatureField& f, double mean_edge) {
  const std::vector<std::uint8_t> stats = curvature::counted_vertices(f, mean_edge);
  std::vector<bool> keep(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    keep[i] = stats[i] && !(!f.boundary.empty() && f.boundary[i]);
  return keep;
}

// p1, p50, p99 of x over the kept vertices (nearest rank); NaN when none is kept.
std::array<double, 3> percentiles(const std::vector<float>& x, const std::vector<bool>& keep) {
  std::vector<float> v;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (keep[i]) v.push_back(x[i]);
  std::array<double, 3> p;
  p.fill(std::nan(""));
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  for (int k = 0; k < 3; ++k)
    p[k] = v[std::min(v.size() - 1, std::size_t(kPercentiles[k] / 100 * double(v.size())))];
  return p;
}

// sqrt(sum (a - b)^2 / sum b^2) over the kept vertices.
double relative_rms(const std::vector<float>& a, const std::vector<double>& b,
                    const std::vector<bool>& keep) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (keep[i]) num += (a[i] - b[i]) * (a[i] - b[i]), den += b[i] * b[i];
  return den > 0 ? std::sqrt(num / den) : std::nan("");
}

// Agreement of two estimators: RMS(a - b) / RMS of both, over vertices counted for both.
double disagreement(const std::vector<float>& a, const std::vector<float>& b,
                    const std::vector<bool>& ka, const std::vector<bool>& kb) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (ka[i] && kb[i])
      diff += double(a[i] - b[i]) * (a[i] - b[i]), scale += 0.5 * (double(a[i]) * a[i] + double(b[i]) * b[i]);
  return scale > 0 ? std::sqrt(diff / scale) : std::nan("");
}

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

// The analytic field a bundled dataset was sampled from (its "field" metadata), when the volume's
// placement is the file's own (no --spacing or --origin).
std::unique_ptr<datasets::Field> analytic_source(const Surface& s, const CommonOptions& o) {
  if (!s.volume || s.volume->format != "vdb" || !o.volume.spacing.empty() ||
      !o.volume.origin.empty())
    return nullptr;
  const auto meta = s.volume->grid->getMetadata<openvdb::StringMetadata>("field");
  if (!meta) return nullptr;
  const std::vector<std::string> names = datasets::field_names();
  if (std::find(names.begin(), names.end(), meta->value()) == names.end()) return nullptr;
  return datasets::make_field(meta->value());
}

/// One estimator's results over the surface (or every label's surface, one after another).
struct CompareRow {
  std::string name, path;
  std::vector<float> H, K;
  std::vector<bool> keep;  ///< counted (counted()), per vertex
  double ms = 0;
  std::size_t flagged = 0;
};

/// What the surfaces compared add up to (one surface, or every label's).
struct CompareTotals {
  std::string normals;  ///< the mesh estimators' normals' name
  std::size_t surfaces = 0, vertices = 0, triangles = 0;
  std::array<double, 2> edges{0, 0};  ///< edge_length_sum's terms over every surface
  double mean_edge() const { return edges[1] > 0 ? edges[0] / edges[1] : 0; }
};

/// Every mesh estimator on `mesh` (normals as `curvature` takes them: --normals, else the
/// gradient of `volume`, else the faces), and with a volume the volume estimator on `volume` at
/// `isovalue`, appended to `rows` (one row per estimator, made on the first call); the mesh is
/// counted into `totals`.
void compare_estimators(const Mesh& mesh, const volume::Volume* volume, float isovalue,
                        const CommonOptions& o, StageTimer& timer, std::vector<CompareRow>& rows,
                        CompareTotals& totals) {
  curvature::Options co;
  const curvature::NormalsSource asked = mesh_estimators_normals(o, volume != nullptr);
  const volume::MeshNormals normals = curvature::host_normals(asked, mesh, volume, o.cap);
  if (curvature::host_computed(asked)) co.vertex_normals = &normals.normals;
  co.ao_scale = curvature::default_ao_scale(mesh);
  apply_estimator_parameters(o, co);  // --scale reaches the volume row, the weights batagelo's
  Device* device = reference_device(o) ? nullptr : &device_for(o);
  const std::array<double, 2> edges = edge_length_sum(mesh);
  const double mean_edge = mesh.triangles.empty() ? 0 : edges[0] / edges[1];  // mean_edge_length
  totals.normals = curvature::normals_name(asked);
  ++totals.surfaces;
  totals.vertices += mesh.vertex_count();
  totals.triangles += mesh.triangle_count();
  totals.edges[0] += edges[0], totals.edges[1] += edges[1];
  std::size_t row = 0;
  // Runs one estimator (once before timing when `warm`: the device's program build, buffers).
  auto add = [&](const std::string& name, const std::string& path, bool warm,
                 const std::function<CurvatureField()>& run) {
    if (rows.size() <= row) rows.push_back(CompareRow{name, path, {}, {}, {}, 0, 0});
    CompareRow& r = rows[row++];
    if (warm) run();
    timer.start(name);
    const auto t0 = std::chrono::steady_clock::now();
    const CurvatureField f = run();
    r.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    timer.stop();
    const std::vector<bool> keep = counted(f, mean_edge);
    r.keep.insert(r.keep.end(), keep.begin(), keep.end());
    r.H.insert(r.H.end(), f.H.begin(), f.H.end());
    r.K.insert(r.K.end(), f.K.begin(), f.K.end());
    for (std::uint8_t u : f.unreliable) r.flagged += u;
  };
  for (const curvature::MeshEstimatorInfo& e : curvature::mesh_estimators()) {
    Device* d = e.kernels ? device : nullptr;
    add(e.name, d ? "opencl" : "reference", d != nullptr,
        [&] { return curvature::estimate_mesh(e.id, mesh, d, co); });
  }
  if (volume) {  // the volume estimator at its auto scale (the default for volume input)
    curvature::Options vo = co;
    vo.estimator = curvature::Estimator::volume;
    vo.vertex_normals = nullptr;
    add("volume", device ? "opencl" : "reference", device != nullptr,
        [&] { return curvature::estimate_field(mesh, {volume, isovalue}, device, vo); });
  }
}

}  // namespace

void register_compare(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "compare",
      "Run every curvature estimator on one surface (the volume estimator on volume input): "
      "time, H and K percentiles, pairwise "
      "agreement, and the error against the exact values on the bundled analytic datasets");
  cmd->footer(
      "Example: isocurv compare build/datasets/torus.vdb\n"
      "         isocurv compare mesh.ply --json\n"
      "Estimators: rusinkiewicz, batagelo, prantl3, prantl2 (OpenCL, or their references with\n"
      "--device reference), quadric, cubic, sampling, meyer (double references, single-threaded),\n"
      "and for volume input volume (at --scale, auto by default; --normals and --batagelo-weights\n"
      "apply to the mesh estimators; --estimator and --ao-scale are refused: compare runs them all\n"
      "and reports no AO).\n"
      "Statistics leave out boundary vertices, vertices an estimator flags Unreliable and those\n"
      "with max(|k1|,|k2|) above 1 / (half the mean edge length). Agreement: RMS(a - b) over the\n"
      "RMS of both, for H and K, over vertices counted for both.");
  static CommonOptions o;
  static std::string in;
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file (.vtp .ply .obj .stl)")->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, /*mesh_input=*/true);
  add_label_options(*cmd, o, false);
  cmd->callback([] {
    // Options compare would otherwise ignore are refused, before any work.
    if (!o.estimator.empty())
      throw CLI::ValidationError("--estimator", "compare runs every estimator; for one, use isocurv curvature");
    if (o.ao_scale > 0) throw CLI::ValidationError("--ao-scale", "compare reports no AO; use isocurv curvature");
    if (o.scale != "auto" && parse_scales(o.scale).size() > 1)
      throw CLI::ValidationError("--scale", "compare measures the volume estimator at one scale");
    StageTimer timer;
    std::vector<CompareRow> rows;
    CompareTotals totals;
    std::unique_ptr<datasets::Field> field;
    std::vector<double> exact_h, exact_k;
    if (o.labelled()) {
      // Each label's surface on its own indicator, its rows after the previous labels'.
      const PickedLabels p = pick_labels(in, o, timer);
      const std::vector<std::int64_t> empty = labels::for_each_label_surface(
          p.map, p.picked, label_steps(p.map, o, timer), [&](labels::LabelSurface& l) {
            compare_estimators(l.mesh, &l.indicator, l.isovalue, o, timer, rows, totals);
          });
      report_label_visits(in, empty, totals.surfaces > 0, o);
    } else {
      Surface s = load_surface(in, o, timer);
      if (o.scale != "auto" && !s.volume)
        throw CLI::ValidationError("--scale", "applies to the volume estimator, which needs a volume input");
      prepare_mesh_for_curvature(s, in, o);
      const Mesh& mesh = s.mesh;
      field = analytic_source(s, o);
      if (field) {
        timer.start("exact");
        for (const Vec3f& p : mesh.positions) {
          const datasets::SurfaceCurvature c = datasets::exact_curvature(
              *field, datasets::project_to_surface(*field, Eigen::Vector3d(p[0], p[1], p[2])));
          exact_h.push_back(c.H), exact_k.push_back(c.K);
        }
        timer.stop();
      }
      compare_estimators(mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer, rows, totals);
    }
    const double limit = 2 / totals.mean_edge();

    nlohmann::json j;
    j["input"] = in;
    j["vertices"] = totals.vertices;
    j["triangles"] = totals.triangles;
    if (o.labelled()) j["labels"] = totals.surfaces;
    j["normals"] = totals.normals;
    j["device"] = device_name(o);
    j["analytic_field"] = field ? nlohmann::json(field->name()) : nlohmann::json();
    j["unreliable_above"] = limit;
    nlohmann::json list = nlohmann::json::array();
    for (const CompareRow& r : rows) {
      nlohmann::json e;
      e["estimator"] = r.name;
      e["path"] = r.path;
      e["time_ms"] = r.ms;
      e["unreliable"] = r.flagged;
      e["counted"] = std::count(r.keep.begin(), r.keep.end(), true);
      const auto ph = percentiles(r.H, r.keep), pk = percentiles(r.K, r.keep);
      e["H"] = {{"p1", number(ph[0])}, {"p50", number(ph[1])}, {"p99", number(ph[2])}};
      e["K"] = {{"p1", number(pk[0])}, {"p50", number(pk[1])}, {"p99", number(pk[2])}};
      if (field) {
        e["exact_error"] = {{"H_relative_rms", number(relative_rms(r.H, exact_h, r.keep))},
                            {"K_relative_rms", number(relative_rms(r.K, exact_k, r.keep))}};
      }
      list.push_back(e);
    }
    j["estimators"] = list;
    nlohmann::json agree;
    for (const CompareRow& a : rows)
      for (const CompareRow& b : rows)
        agree[a.name][b.name] = {
            number(disagreement(a.H, b.H, a.keep, b.keep)),
            number(disagreement(a.K, b.K, a.keep, b.keep))};
    j["agreement_H_K"] = agree;
    j["timings_ms"] = timer.json();

    if (o.json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::printf("%s: %s%zu vertices, %zu triangles, %s normals, %s%s\n", in.c_str(),
                o.labelled() ? (std::to_string(totals.surfaces) + " labels, ").c_str() : "",
                totals.vertices, totals.triangles, totals.normals.c_str(),
                device_name(o).c_str(),
                field ? (", exact values of the analytic field " + field->name()).c_str() : "");
    std::printf("%-13s %-9s %9s %6s %10s %10s %10s  %10s %10s %10s%s\n", "estimator", "path",
                "ms", "flags", "H p1", "H p50", "H p99", "K p1", "K p50", "K p99",
                field ? "   rel. RMS error H     K" : "");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const nlohmann::json& e = list[i];
      auto g = [](const nlohmann::json& x) { return x.is_null() ? std::nan("") : x.get<double>(); };
      std::printf("%-13s %-9s %9.1f %6zu %10.4g %10.4g %10.4g  %10.4g %10.4g %10.4g",
                  rows[i].name.c_str(), e["path"].get<std::string>().c_str(), rows[i].ms,
                  rows[i].flagged, g(e["H"]["p1"]), g(e["H"]["p50"]), g(e["H"]["p99"]),
                  g(e["K"]["p1"]), g(e["K"]["p50"]), g(e["K"]["p99"]));
      if (field)
        std::printf("   %10.4g %10.4g", g(e["exact_error"]["H_relative_rms"]),
                    g(e["exact_error"]["K_relative_rms"]));
      std::printf("\n");
    }
    std::printf("\nagreement: RMS difference over RMS, H (upper right) and K (lower left)\n%-13s",
                "");
    for (const CompareRow& r : rows) std::printf(" %12s", r.name.c_str());
    std::printf("\n");
    for (std::size_t a = 0; a < rows.size(); ++a) {
      std::printf("%-13s", rows[a].name.c_str());
      for (std::size_t b = 0; b < rows.size(); ++b) {
        if (a == b) {
          std::printf(" %12s", "-");
          continue;
        }
        const nlohmann::json& v = agree[rows[a].name][rows[b].name][a < b ? 0 : 1];
        std::printf(" %12.4g", v.is_null() ? std::nan("") : v.get<double>());
      }
      std::printf("\n");
    }
  });
}

}  // namespace isocurv::app
