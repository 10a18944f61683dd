// isocurv measure VOLUME|MESH: the Minkowski functionals of every connected component of the
// isosurface (or mesh), with the curvature integrals and their Gauss-Bonnet check.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/commands.h"
#include "app/label_surfaces.h"
#include "app/picture_title.h"
#include "app/pipeline.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "measure/object_measures.h"

namespace isocurv::app {
namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json measures_json(const measure::ObjectMeasures& m, bool with_genus) {
  nlohmann::json j = {{"vertices", m.vertices},
                      {"triangles", m.triangles},
                      {"closed", m.closed},
                      {"boundary_edges", m.boundary_edges},
                      {"area", m.area},
                      {"mesh_area", m.mesh_area},
                      {"volume", m.closed ? number_or_null(m.volume) : nlohmann::json(nullptr)},
                      {"integral_H", m.integral_H},
                      {"integral_K", m.integral_K},
                      {"euler_characteristic", m.euler},
                      {"gauss_bonnet_gap", number_or_null(m.gauss_bonnet_gap())},
                      {"unmeasured_vertices", m.unmeasured},
                      {"on_vertices", m.on_vertices},
                      {"scale", m.scale},
                      {"resolved", m.resolved},
                      {"curvature_genus", number_or_null(m.curvature_genus())},
                      {"fine_handles", m.has_fine_handles()},
                      {"box", m.box}};
  if (with_genus) j["genus"] = m.closed ? nlohmann::json(m.genus()) : nlohmann::json(nullptr);
  return j;
}

/// One CSV row: the object's number (or "total") and its measures.
std::string csv_row(const std::string& id, const measure::ObjectMeasures& m, long long genus) {
  auto num = [](double v) {
    if (!std::isfinite(v)) return std::string();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return std::string(buf);
  };
  std::ostringstream s;
  s << id << ',' << m.vertices << ',' << m.triangles << ',' << (m.closed ? 1 : 0) << ','
    << num(m.area) << ',' << (m.closed ? num(m.volume) : "") << ',' << num(m.integral_H) << ','
    << num(m.integral_K) << ',' << m.euler << ',' << (genus >= 0 ? std::to_string(genus) : "")
    << ',' << num(m.gauss_bonnet_gap()) << ',' << m.unmeasured;
  for (double b : m.box) s << ',' << num(b);
  s << ',' << num(m.mesh_area) << ',' << num(m.scale) << ',' << (m.resolved ? 1 : 0) << '\n';
  return s.str();
}

/// One label's measures: the sum of its components, and how many there are.
struct LabelRow {
  std::int64_t label = 0;
  std::size_t components = 0;
  measure::ObjectMeasures m;
  long long genus = 0;  ///< the sum of its closed components' genera; -1 when one is cut
};

/// The objects grouped by the label part holding their first vertex, in the parts' order.
std::vector<LabelRow> label_rows(const std::vector<measure::ObjectMeasures>& objects,
                                 const std::vector<labels::LabelPart>& parts) {
  std::vector<LabelRow> rows;
  for (const labels::LabelPart& p : parts) {
    std::vector<measure::ObjectMeasures> mine;
    for (const auto& m : objects)
      if (p.holds_vertex(m.first_vertex)) mine.push_back(m);
    LabelRow r;
    r.label = p.value;
    r.components = mine.size();
    r.m = measure::total(mine);
    r.genus = measure::genus_sum(mine);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

void register_measure(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "measure", "Per connected component of the isosurface (or mesh): enclosed volume, area, "
                 "integrals of H and K, Euler characteristic and genus, with the Gauss-Bonnet check");
  cmd->footer("Example: isocurv measure build/datasets/torus.vdb\n"
              "         isocurv measure ../shared/datasets/lobster/lobster.vol --iso 40 --csv lobster.csv\n"
              "World units (the volume's spacing); the curvature comes from the volume estimator for\n"
              "volumes (the default), so the integrals are those of the smooth object the scan samples.");
  static CommonOptions o;
  static std::string in, csv;
  static int rows = 20;
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file")->required();
  cmd->add_option("--csv", csv, "Also write one row per component and a total row to this .csv");
  cmd->add_option("--rows", rows, "Components listed in the text report, largest first (default 20)")
      ->check(CLI::Range(0, 1000000));
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, true);
  add_label_options(*cmd, o, false);
  cmd->callback([] {
    if (!csv.empty()) require_writable_file(csv);  // before any work
    StageTimer timer;
    Surface s;
    bool from_file = false;
    if (o.labelled()) {
      s = load_label_surfaces(in, o, timer, true);
    } else {
      s = load_surface(in, o, timer);
      prepare_mesh_for_curvature(s, in, o);
      const std::size_t nv = s.mesh.positions.size();
      from_file = !s.volume && s.field && s.field->H.size() == nv && s.field->K.size() == nv;
      if (!from_file)
        s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                                     &s.normals, &s.estimator);
    }
    timer.start("measure");
    const std::vector<measure::ObjectMeasures> objects = measure::object_measures(s.mesh, *s.field);
    const measure::ObjectMeasures all = measure::total(objects);
    const std::vector<LabelRow> by_label = label_rows(objects, s.label_parts);
    timer.stop();
    const long long genus_total = measure::genus_sum(objects);  // -1 when one is cut
    const std::string estimator = from_file ? "from the file" : s.estimator.estimator;
    // What the text states: the estimator with the scale the measure belongs to.
    const std::string described = from_file ? estimator : estimator_title(s.estimator);
    const bool labelled = !s.label_parts.empty();
    if (!csv.empty()) {
      std::string text = std::string(labelled ? "label,components," : "object,") +
          "vertices,triangles,closed,area,volume,integral_H,integral_K,euler,genus,"
          "gauss_bonnet_gap,unmeasured_vertices,xmin,xmax,ymin,ymax,zmin,zmax,mesh_area,scale,"
          "resolved\n";
      if (labelled)
        for (const LabelRow& r : by_label)
          text += csv_row(std::to_string(r.label) + "," + std::to_string(r.components), r.m, r.genus);
      else
        for (std::size_t i = 0; i < objects.size(); ++i)
          text += csv_row(std::to_string(i + 1), objects[i], objects[i].closed ? objects[i].genus() : -1);
      text += csv_row(labelled ? "total," + std::to_string(objects.size()) : "total", all,
                      genus_total);
      write_text_file(csv, text);
    }
    if (o.json) {
      nlohmann::json r;
      r["input"] = in;
      if (s.volume) r["isovalue"] = s.isovalue;
      r["estimator"] = estimator;
      r["curvature"] = described;  // e.g. "volume, scale 0.8-1.5 per vertex" (world units)
      r["objects"] = nlohmann::json::array();
      for (const auto& m : objects) r["objects"].push_back(measures_json(m, true));
      if (labelled) {
        r["labels"] = nlohmann::json::array();
        for (const LabelRow& l : by_label) {
          nlohmann::json j = measures_json(l.m, false);
          j["label"] = l.label;
          j["components"] = l.components;
          j["genus"] = l.genus >= 0 ? nlohmann::json(l.genus) : nlohmann::json(nullptr);
          r["labels"].push_back(j);
        }
        std::size_t k = 0;  // each component's label
        for (const auto& m : objects) {
          for (const labels::LabelPart& p : s.label_parts)
            if (p.holds_vertex(m.first_vertex)) r["objects"][k]["label"] = p.value;
          ++k;
        }
      }
      r["total"] = measures_json(all, false);
      r["total"]["components"] = objects.size();
      r["total"]["genus"] = genus_total >= 0 ? nlohmann::json(genus_total) : nlohmann::json(nullptr);
      if (!csv.empty()) r["csv"] = csv;
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
      return;
    }
    if (o.quiet) return;
    if (labelled)
      std::printf("%zu label%s, %zu component%s; curvature: %s (each label's own indicator)\n",
                  by_label.size(), by_label.size() == 1 ? "" : "s", objects.size(),
                  objects.size() == 1 ? "" : "s", described.c_str());
    else
      std::printf("%zu component%s%s; curvature: %s\n", objects.size(), objects.size() == 1 ? "" : "s",
                  s.volume ? (" at isovalue " + format_number(s.isovalue)).c_str() : "",
                  described.c_str());
    std::printf("%6s %12s %12s %12s %12s %12s %6s %6s %9s %s\n", labelled ? "label" : "object",
                "area", "mesh area", "volume", "int H dA", "int K dA", "euler", "genus", "GB gap", "");
    auto line = [](const std::string& id, const measure::ObjectMeasures& m, long long genus,
                   bool one = true) {
      char vol[32] = "", gap[32] = "", g[24] = "", why[96] = "";
      if (m.closed) std::snprintf(vol, sizeof vol, "%.6g", m.volume);
      if (std::isfinite(m.gauss_bonnet_gap())) std::snprintf(gap, sizeof gap, "%+.2f%%", 100 * m.gauss_bonnet_gap());
      if (genus >= 0) std::snprintf(g, sizeof g, "%lld", genus);
      if (!m.closed)
        std::snprintf(why, sizeof why, "cut by the box (open: no volume, no genus)");
      else if (one && !m.resolved)
        std::snprintf(why, sizeof why, "below its curvature scale (%.3g): H, K integrals unreliable", m.scale);
      std::printf("%6s %12.6g %12.6g %12s %12.6g %12.6g %6lld %6s %9s %s\n", id.c_str(), m.area,
                  m.mesh_area, vol, m.integral_H, m.integral_K, m.euler, g, gap, why);
    };
    const std::size_t listed = labelled ? by_label.size() : objects.size();
    for (std::size_t i = 0; i < listed && i < std::size_t(rows); ++i) {
      if (labelled) line(std::to_string(by_label[i].label), by_label[i].m, by_label[i].genus);
      else line(std::to_string(i + 1), objects[i], objects[i].closed ? objects[i].genus() : -1);
    }
    if (listed > std::size_t(rows))
      std::printf("%6s (%zu more %s not listed; --rows, --csv or --json list them)\n", "...",
                  listed - std::size_t(rows), labelled ? "labels" : "smaller components");
    line("total", all, genus_total, false);
    std::printf("area: the smooth surface the curvature describes (its normals and surface points); "
                "mesh area: the triangles' own, as check and stats.json report it\n");
    std::size_t below = 0;
    for (const auto& m : objects) below += !m.resolved;
    if (below > 0)
      std::printf("%zu component%s smaller than %.3g times %s largest smoothing scale (%s integrals "
                  "of H and K and Gauss-Bonnet gap%s measure the smoothing more than the object)\n",
                  below, below == 1 ? "" : "s", measure::kResolvedExtent, below == 1 ? "its" : "their",
                  below == 1 ? "its" : "their", below == 1 ? "" : "s");
    std::size_t specks = 0;
    for (const auto& m : objects) specks += m.on_vertices;
    if (specks > 0)
      std::printf("%zu component%s below the curvature scale measured over the mesh's own vertices "
                  "(the estimator's surface points would move %s by more than half)\n",
                  specks, specks == 1 ? "" : "s", specks == 1 ? "it" : "them");
    if (!labelled) {
      std::size_t fine = 0, first = 0;
      for (std::size_t i = 0; i < objects.size(); ++i)
        if (objects[i].has_fine_handles() && fine++ == 0) first = i;
      if (fine > 0)
        std::printf("%zu component%s with handles finer than the curvature scale (object %zu: its "
                    "integral of K counts %.0f of its %lld handles; the rest, noise tunnels in a scan, "
                    "are not on the smooth surface the curvature describes, so the Gauss-Bonnet gap "
                    "counts them: docs/measure.md)\n",
                    fine, fine == 1 ? "" : "s", first + 1,
                    std::max(0.0, objects[first].curvature_genus()), objects[first].genus());
    }
    if (all.unmeasured > 0)
      std::printf("%zu unmeasured vertices (flagged Unreliable) count as H = K = 0 in the integrals\n",
                  all.unmeasured);
    if (!csv.empty()) std::printf("wrote %s\n", csv.c_str());
  });
}

}  // namespace isocurv::app
