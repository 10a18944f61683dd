// isocurv curvature VOLUME|MESH -o MESH: a mesh carrying every curvature array.
#include <iostream>

#include "app/commands.h"
#include "app/pipeline.h"
#include "io/mesh_file.h"

namespace isocurv::app {

void register_curvature(CLI::App& app) {
  auto* cmd = app.add_subcommand("curvature", "Estimate per-vertex curvature (k1 k2 dir1 dir2 H K dcurv ShapeIndex Curvedness AO) "
                                              "on a volume's isosurface or on a mesh");
  cmd->footer("Example: isocurv curvature torus.vdb -o torus.vtp --normals volume --json\n"
              "Normals point out of the object, so a solid sphere of radius R has k1 = k2 = H = +1/R.");
  static CommonOptions o;
  static std::string in, out;
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file")->required();
  cmd->add_option("-o,--output", out,
                  "Mesh file to write (.vtp or .ply: the formats that carry the curvature arrays)")
      ->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, true);
  cmd->callback([] {
    require_curvature_format(out);  // before any work: .obj and .stl would drop the arrays
    StageTimer timer;
    Surface s = load_surface(in, o, timer);
    prepare_mesh_for_curvature(s, in, o);
    s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                                 &s.normals, &s.estimator);
    timer.start("write");
    io::write_mesh(out, s.mesh, &*s.field);
    timer.stop();
    nlohmann::json r = surface_report(s);
    if (o.json) {
      r["input"] = in;
      r["output"] = out;
      r["device"] = device_name(o);
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << ": " << r["vertices"] << " vertices with curvature (curvature "
                << timer.json().value("curvature", 0.0) << " ms)\n";
    }
  });
}

}  // namespace isocurv::app
