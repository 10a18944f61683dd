// isocurv check MESH_OR_VOLUME: fusion, topology and triangle quality of our meshes or anyone's.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/distributed.h"
#include "app/pipeline.h"
#include "core/mesh_measures.h"
#include "mc/mesh_check.h"
#include "mc/triangle_quality.h"

namespace isocurv::app {
namespace {

constexpr std::size_t kListedInText = 5;  // offenders listed per kind in the text report

// " (e.g. 4=0, 9=2, ...)": the first few pairs joined by `sep`.
std::string first_few(const std::vector<mc::VertexPair>& pairs, const char* sep) {
  if (pairs.empty()) return "";
  std::string s = " (";
  for (std::size_t i = 0; i < pairs.size() && i < kListedInText; ++i)
    s += (i ? ", " : "") + std::to_string(pairs[i][0]) + sep + std::to_string(pairs[i][1]);
  return s + (pairs.size() > kListedInText ? ", ...)" : ")");
}

nlohmann::json pairs_json(const std::vector<mc::VertexPair>& pairs) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& p : pairs) j.push_back({p[0], p[1]});
  return j;
}

}  // namespace

void register_check(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "check",
      "Check a mesh (or a volume's isosurface) for duplicate and unreferenced vertices, boundary "
      "and non-manifold edges, orientation, Euler characteristic, genus and triangle quality");
  cmd->footer(
      "Example: isocurv check other_mesher_output.ply\n"
      "         isocurv check head.nrrd --iso 500 --json\n"
      "Small triangles: area under 1e-4 voxel face areas (volume input) or 1e-4 squared mean\n"
      "edge lengths (mesh files). Exit status 0 for a clean mesh (fused, manifold, consistently\n"
      "oriented outward; open or small triangles are reported, not problems), 1 when the check\n"
      "reports problems (the report and --json are printed all the same) or on bad input, 2 on\n"
      "a usage error.");
  static CommonOptions o;
  static std::string in;
  cmd->add_option("MESH_OR_VOLUME", in, "Mesh (.vtp .ply .obj .stl) or volume file")->required();
  add_common_options(*cmd, o);
  cmd->callback([] {
    StageTimer timer;
    // Under mpirun: the ranks extract the surface together, rank 0 checks it (app/distributed.h).
    std::optional<Surface> on_zero = surface_for_rank_zero(in, o, timer, DistributedWork::extract);
    if (!on_zero) return;
    Surface& s = *on_zero;
    timer.start("check");
    // A mesh of isocurv's --labels: duplicates within a label; touching labels' walls expected.
    const std::vector<float>* labels = s.field ? s.field->find_extra("Label") : nullptr;
    const mc::MeshCheck c = mc::check_mesh(s.mesh, labels);
    const double edge = mean_edge_length(s.mesh);
    const std::string unit = s.volume ? "voxel^2" : "mean-edge-length^2";
    const mc::TriangleQuality q =
        mc::triangle_quality(s.mesh, s.volume ? mc::voxel_face_area(*s.volume) : edge * edge);
    timer.stop();
    const std::size_t closed = c.closed_components(), inward = c.inward_components();
    const double volume = c.closed_signed_volume();
    // Judged only when every component is closed: where a surface is cut open (by the box of a
    // CT, say), the closed components inside it are its cavities, inward by right.
    const bool judged = closed > 0 && closed == c.components;
    const bool inward_overall = judged && volume < 0;
    const bool clean = c.duplicate_vertices == 0 && c.unreferenced_vertices == 0 &&
                       c.degenerate_triangles == 0 && c.non_manifold_edges == 0 && c.oriented() &&
                       !inward_overall;
    if (!clean) command_exit_status() = 1;
    if (o.json) {
      nlohmann::json r = {{"input", in},
                          {"vertices", c.vertices},
                          {"triangles", c.triangles},
                          {"duplicate_vertices", c.duplicate_vertices},
                          {"labelled", labels != nullptr},
                          {"label_wall_vertices", c.label_wall_vertices},
                          {"unreferenced_vertices", c.unreferenced_vertices},
                          {"degenerate_triangles", c.degenerate_triangles},
                          {"edges", c.edges},
                          {"boundary_edges", c.boundary_edges},
                          {"non_manifold_edges", c.non_manifold_edges},
                          {"misoriented_edges", c.misoriented_edges},
                          {"consistently_oriented", c.oriented()},
                          {"watertight", c.watertight()},
                          {"components", c.components},
                          {"euler_characteristic", c.euler},
                          {"area", c.area},
                          {"timings_ms", timer.json()}};
      r["genus"] = c.genus() >= 0 ? nlohmann::json(c.genus()) : nlohmann::json(nullptr);
      r["duplicate_vertex_ids"] = pairs_json(c.duplicates);
      r["non_manifold_edge_ids"] = pairs_json(c.non_manifold);
      r["misoriented_edge_ids"] = pairs_json(c.misoriented);
      nlohmann::json comps = nlohmann::json::array();
      for (const mc::ComponentCheck& k : c.component_list)
        comps.push_back({{"first_vertex", k.first_vertex},
                         {"triangles", k.triangles},
                         {"closed", k.closed},
                         {"signed_volume",
                          k.closed ? nlohmann::json(k.signed_volume) : nlohmann::json(nullptr)},
                         {"orientation", !k.closed             ? "open"
                                         : k.signed_volume < 0 ? "inward"
                                                               : "outward"}});
      r["component_orientation"] = comps;
      r["closed_components"] = closed;
      r["inward_components"] = inward;
      r["closed_signed_volume"] = volume;
      r["orientation"] = !judged ? "n/a" : inward_overall ? "inward" : "outward";
      r["problems_found"] = !clean;
      r["triangle_quality"] = {{"min_area", q.min_area},
                               {"min_angle_degrees", q.min_angle},
                               {"small_area_triangles", q.small},
                               {"thin_triangles", q.thin},
                               {"area_unit", unit},
                               {"area_unit_value", q.unit_area},
                               {"small_area_below", mc::kSmallAreaFraction * q.unit_area},
                               {"thin_below_degrees", mc::kThinAngleDegrees}};
      if (s.volume) r["isovalue"] = s.isovalue;
      std::cout << r.dump(2) << "\n";
      return;
    }
    std::printf("%s\n", in.c_str());
    if (s.volume) std::printf("  isovalue              %g\n", s.isovalue);
    std::printf("  vertices              %zu\n  triangles             %zu\n", c.vertices,
                c.triangles);
    std::printf("  duplicate vertices    %zu%s%s\n", c.duplicate_vertices,
                labels ? " within a label" : "", first_few(c.duplicates, "=").c_str());
    if (labels)
      std::printf("  label walls           %zu vertices shared by touching labels (each label's "
                  "surface is closed on its own; not a problem)\n",
                  c.label_wall_vertices);
    std::printf("  unreferenced vertices %zu\n  degenerate triangles  %zu\n",
                c.unreferenced_vertices, c.degenerate_triangles);
    std::printf("  edges                 %zu (boundary %zu, non-manifold %zu)%s\n", c.edges,
                c.boundary_edges, c.non_manifold_edges, first_few(c.non_manifold, "-").c_str());
    std::printf("  orientation           %s (%zu edges misoriented)%s\n",
                c.oriented() ? "consistent" : "INCONSISTENT", c.misoriented_edges,
                first_few(c.misoriented, "-").c_str());
    if (closed == 0)
      std::printf("  closed components     0 (no outward/inward judgement)\n");
    else if (!judged)
      std::printf(
          "  closed components     %zu: %zu outward, %zu inward by signed volume; overall n/a (open "
          "components: the inward ones may be their cavities)\n",
          closed, closed - inward, inward);
    else
      std::printf(
          "  closed components     %zu: %zu outward, %zu inward by signed volume; overall %s "
          "(volume %.6g)%s\n",
          closed, closed - inward, inward, inward_overall ? "INWARD" : "outward", volume,
          inward_overall ? "; isocurv curvature --flip reverses the triangles" : "");
    std::printf("  components            %zu\n  Euler characteristic  %lld\n", c.components,
                c.euler);
    if (c.genus() >= 0)
      std::printf("  genus                 %lld\n", c.genus());
    else
      std::printf("  genus                 n/a (not closed and oriented)\n");
    std::printf("  area                  %.6g\n", c.area);
    std::printf("  smallest triangle     %.6g (%zu under %g %s = %.6g)\n", q.min_area, q.small,
                mc::kSmallAreaFraction, unit.c_str(), mc::kSmallAreaFraction * q.unit_area);
    std::printf("  smallest angle        %.6g degrees (%zu triangles under %g degree)\n",
                q.min_angle, q.thin, mc::kThinAngleDegrees);
    std::printf("  verdict               %s%s\n", clean ? "fused and manifold" : "PROBLEMS FOUND",
                c.watertight() ? ", watertight" : ", open");
  });
}

}  // namespace isocurv::app
