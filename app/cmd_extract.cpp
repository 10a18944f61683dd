// isocurv extract VOLUME -o MESH: the fused isosurface mesh.
#include <iostream>

#include "app/commands.h"
#include "app/pipeline.h"
#include "io/mesh_file.h"

namespace isocurv::app {

void register_extract(CLI::App& app) {
  auto* cmd = app.add_subcommand("extract", "Extract the isosurface of a volume as a fused, indexed triangle mesh");
  cmd->footer(
      "Example: isocurv extract lobster.vol --iso 40 -o lobster.ply --json\n"
      "The object is where values are above the isovalue (below for level sets, or with\n"
      "--inside below); triangles are wound so their normals point out of it. An isovalue that\n"
      "gives no surface writes an empty mesh after a warning (the other commands refuse it).");
  static CommonOptions o;
  static std::string in, out;
  cmd->add_option("VOLUME", in, "Volume file")->required();
  cmd->add_option("-o,--output", out, std::string("Mesh file to write (") + io::mesh_extensions() + ")")->required();
  add_common_options(*cmd, o);
  cmd->callback([] {
    StageTimer timer;
    Surface s = load_surface(in, o, timer, EmptySurface::warn);
    timer.start("write");
    io::write_mesh(out, s.mesh);
    timer.stop();
    nlohmann::json r = surface_report(s);
    if (o.json) {
      r["input"] = in;
      r["output"] = out;
      r["device"] = device_name(o);
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << ": " << r["vertices"] << " vertices, " << r["triangles"] << " triangles at isovalue "
                << s.isovalue << " (extract " << timer.json().value("extract", 0.0) << " ms)\n";
    }
  });
}

}  // namespace isocurv::app
