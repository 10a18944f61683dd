// isocurv render VOLUME|MESH -o PNG: a headless picture coloured by curvature.
#include <iostream>

#include "app/commands.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "viz/render.h"

namespace isocurv::app {

void register_render(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a volume's isosurface or a mesh to a PNG, coloured by curvature (no display needed)");
  cmd->footer("Example: isocurv render torus.vdb --color K --ao --dirs -o torus.png\n"
              "A mesh without curvature arrays gets them estimated first.");
  static CommonOptions o;
  static viz::RenderOptions ro;
  static std::string in, out;
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file")->required();
  cmd->add_option("-o,--output", out, "PNG file to write")->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, true);
  add_render_options(*cmd, ro);
  cmd->callback([] {
    StageTimer timer;
    Surface s = load_surface(in, o, timer);
    if (o.flip || !s.field || s.field->H.size() != s.mesh.positions.size()) {
      prepare_mesh_for_curvature(s, in, o);
      s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                                 &s.normals, &s.estimator);
    }
    timer.start("render");
    viz::RenderOptions opts = ro;
    if (opts.title.empty()) opts.title = in;
    viz::render_png(out, s.mesh, *s.field, opts);
    timer.stop();
    if (o.json) {
      nlohmann::json r = surface_report(s);
      r["input"] = in;
      r["output"] = out;
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << "\n";
    }
  });
}

}  // namespace isocurv::app
