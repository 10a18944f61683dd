// isocurv check MESH_OR_VOLUME: fusion and topology report for our meshes or anyone's.
#include <cstdio>
#include <iostream>

#include "app/commands.h"
#include "app/pipeline.h"
#include "mc/mesh_check.h"

namespace isocurv::app {

void register_check(CLI::App& app) {
  auto* cmd = app.add_subcommand("check", "Check a mesh (or a volume's isosurface) for duplicate and unreferenced "
                                          "vertices, boundary and non-manifold edges, orientation, Euler characteristic and genus");
  cmd->footer("Example: isocurv check other_mesher_output.ply\n         isocurv check head.nrrd --iso 500 --json\n"
              "Exit status 0 when the check ran (whatever it found), 1 on bad input.");
  static CommonOptions o;
  static std::string in;
  cmd->add_option("MESH_OR_VOLUME", in, "Mesh (.vtp .ply .obj .stl) or volume file")->required();
  add_common_options(*cmd, o);
  cmd->callback([] {
    StageTimer timer;
    Surface s = load_surface(in, o, timer);
    timer.start("check");
    const mc::MeshCheck c = mc::check_mesh(s.mesh);
    timer.stop();
    if (o.json) {
      nlohmann::json r = {{"input", in}, {"vertices", c.vertices}, {"triangles", c.triangles},
                          {"duplicate_vertices", c.duplicate_vertices}, {"unreferenced_vertices", c.unreferenced_vertices},
                          {"degenerate_triangles", c.degenerate_triangles}, {"edges", c.edges},
                          {"boundary_edges", c.boundary_edges}, {"non_manifold_edges", c.non_manifold_edges},
                          {"misoriented_edges", c.misoriented_edges}, {"consistently_oriented", c.oriented()},
                          {"watertight", c.watertight()}, {"components", c.components},
                          {"euler_characteristic", c.euler}, {"area", c.area}, {"timings_ms", timer.json()}};
      r["genus"] = c.genus() >= 0 ? nlohmann::json(c.genus()) : nlohmann::json(nullptr);
      if (s.volume) r["isovalue"] = s.isovalue;
      std::cout << r.dump(2) << "\n";
      return;
    }
    std::printf("%s\n", in.c_str());
    if (s.volume) std::printf("  isovalue              %g\n", s.isovalue);
    std::printf("  vertices              %zu\n  triangles             %zu\n", c.vertices, c.triangles);
    std::printf("  duplicate vertices    %zu\n  unreferenced vertices %zu\n  degenerate triangles  %zu\n",
                c.duplicate_vertices, c.unreferenced_vertices, c.degenerate_triangles);
    std::printf("  edges                 %zu (boundary %zu, non-manifold %zu)\n", c.edges, c.boundary_edges, c.non_manifold_edges);
    std::printf("  orientation           %s (%zu edges traversed the same way twice)\n",
                c.oriented() ? "consistent" : "INCONSISTENT", c.misoriented_edges);
    std::printf("  components            %zu\n  Euler characteristic  %lld\n", c.components, c.euler);
    if (c.genus() >= 0) std::printf("  genus                 %lld\n", c.genus());
    else std::printf("  genus                 n/a (not closed and oriented)\n");
    std::printf("  area                  %.6g\n", c.area);
    const bool clean = c.duplicate_vertices == 0 && c.unreferenced_vertices == 0 && c.degenerate_triangles == 0 &&
                       c.non_manifold_edges == 0 && c.oriented();
    std::printf("  verdict               %s%s\n", clean ? "fused and manifold" : "PROBLEMS FOUND",
                c.watertight() ? ", watertight" : ", open");
  });
}

}  // namespace isocurv::app
