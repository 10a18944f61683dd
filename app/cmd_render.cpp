// isocurv render VOLUME|MESH -o PNG: a headless picture coloured by curvature.
#include <iostream>
#include <optional>

#include "app/commands.h"
#include "app/label_surfaces.h"
#include "app/line_options_cli.h"
#include "app/picture_title.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "viz/color_map.h"
#include "viz/direction_glyphs.h"
#include "viz/render.h"

namespace isocurv::app {

void register_render(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a volume's isosurface or a mesh to a PNG, coloured by curvature (no display needed)");
  cmd->footer("Example: isocurv render build/datasets/torus.vdb --color K --shading ambient-ao --dirs -o torus.png\n"
              "         isocurv render ../shared/datasets/vg_bunny/bunny-128.vol --lines contours,suggestive -o bunny.png\n"
              "(the bundled datasets, from the checkout: build/datasets and ../shared/datasets)\n"
              "A mesh without curvature arrays gets them estimated first.");
  static CommonOptions o;
  static RenderCli ro;
  static std::string in, out;
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file")->required();
  cmd->add_option("-o,--output", out, "PNG file to write")->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, true);
  add_ao_options(*cmd, o);
  add_label_options(*cmd, o, false);
  add_render_options(*cmd, ro);
  static LineCli lc;
  add_line_options(*cmd, lc, "");
  cmd->callback([] {
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error& e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    require_lines_supported(lo.lines, o);
    StageTimer timer;
    if (!ro.dirs_out.empty() && !ro.opts.dirs) throw Error(ro.dirs_out, "--dirs-out needs --dirs");
    if (!ro.dirs_out.empty()) viz::check_glyphs_path(ro.dirs_out);
    require_writable_file(out);  // before any work
    Surface s = o.labelled() ? load_label_surfaces(in, o, timer, true) : load_surface(in, o, timer);
    bool estimated = o.labelled();
    const std::size_t nv = s.mesh.positions.size();
    if (o.labelled()) {
      // each label's curvature came from its own indicator
    } else if (o.flip || !s.field || s.field->H.size() != nv ||
        (lo.lines.any() && (s.field->dir1.size() != nv || s.field->dcurv.size() != nv))) {
      reestimate_keeping_extras(s, in, o, timer);  // --flip or no H: the file's extras stay
      estimated = true;
    } else if (!o.ao.empty()) {
      apply_ao(s.mesh, *s.field, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer);  // --ao-method on the file's curvature
    }
    const SurfaceContext context = surface_context(s);
    const std::string from_file = context.file_estimator.empty()
                                      ? "curvature from the file"
                                      : "from the file: " + context.file_estimator;
    const viz::RenderOptions opts = render_options_for(
        ro, in, context, with_ao(estimated ? estimator_title(s.estimator) : from_file, o),
        &*s.field);
    viz::LinesForCamera lines_for;
    if (lo.lines.any())
      lines_for = [&](const Camera& cam) {
        return lines::join_segments(extract_lines(s.mesh, *s.field, cam, lo, o, timer));
      };
    timer.start("render");
    AtomicFileSet outputs;  // the PNG and the glyphs together or not at all
    viz::PictureLayout layout;
    outputs.write(out, [&](const std::string& tmp) {
      layout = viz::render_png(tmp, s.mesh, *s.field, opts, lines_for);
    });
    if (!ro.dirs_out.empty())
      outputs.write(ro.dirs_out, [&](const std::string& tmp) {
        viz::write_glyphs(tmp, viz::direction_glyphs(s.mesh, *s.field, viz::glyph_options(opts)));
      });
    outputs.commit();
    timer.stop();
    if (o.json) {
      nlohmann::json r = surface_report(s);
      r["input"] = in;
      r["output"] = out;
      if (!layout.ticks.empty())  // the legend's ends are the colour range
        r["color"] = {{"array", opts.color},
                      {"cmap", viz::resolve_color_map(opts.cmap, opts.color)},
                      {"range", {layout.ticks.front(), layout.ticks.back()}}};
      r["title"] = layout.title.text;          // as drawn (shortened to fit)
      r["legend_title"] = layout.legend_title.text;  // the quantity and its unit
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << "\n";
    }
  });
}

}  // namespace isocurv::app
