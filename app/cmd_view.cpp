// isocurv view VOLUME: the interactive explorer (isovalue slider, curvature colours).
#include <chrono>
#include <iostream>
#include <memory>

#include "app/commands.h"
#include "app/line_options_cli.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "core/error.h"
#include "curvature/estimate.h"
#include "lines/extract.h"
#include "lines/reference.h"
#include "mc/extract.h"
#include "viz/explorer.h"

namespace isocurv::app {

void register_view(CLI::App& app) {
  auto* cmd = app.add_subcommand("view", "Explore a volume interactively: isovalue slider, surface coloured by curvature");
  cmd->footer("Example: isocurv view headsq.raw --dims 64 64 93 --type int16 --iso 500\n"
              "Keys: c cycles the colour quantity, a toggles AO, d toggles direction glyphs, l toggles the feature\n"
              "lines (--lines; they follow the camera and the isovalue), s saves a screenshot,\n"
              "r resets the camera, q quits. Needs an X display.");
  static CommonOptions o;
  static viz::RenderOptions ro;
  static std::string in;
  cmd->add_option("VOLUME", in, "Volume file")->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o);
  add_render_options(*cmd, ro);
  static LineCli lc;
  add_line_options(*cmd, lc, "contours,suggestive");
  static bool show_lines = false;
  cmd->add_flag("--show-lines", show_lines, "Start with the lines on (else press l)")->group("Lines");
  cmd->callback([] {
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error& e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    StageTimer timer;
    float iso = 0;
    auto vol = std::make_shared<volume::Volume>(load_volume(in, o, timer, &iso));
    // The OpenCL mesher keeps its per-block ranges between slider moves; the reference re-reads
    // the whole volume each time (slow, but it needs no OpenCL).
    std::shared_ptr<mc::Mesher> mesher;
    if (!reference_device(o)) mesher = std::make_shared<mc::Mesher>(*vol, device_for(o));
    viz::ExplorerSetup setup;
    setup.isovalue = iso;
    setup.min_value = static_cast<float>(vol->stats.min);
    setup.max_value = static_cast<float>(vol->stats.max);
    setup.view = ro;
    if (setup.view.title.empty()) setup.view.title = in;
    setup.surface = [vol, mesher](float value) {
      const auto t0 = std::chrono::steady_clock::now();
      mc::Options mo;
      mo.cap = o.cap;
      mo.snap = o.snap;
      mc::ExtractTimings et;
      viz::Surface out;
      out.mesh = mesher ? mesher->extract(value, mo, &et) : extract_surface(*vol, value, o);
      const auto t1 = std::chrono::steady_clock::now();
      StageTimer ignored;  // the explorer shows its own timings
      out.field = estimate_curvature(out.mesh, vol.get(), o, ignored);
      const auto t2 = std::chrono::steady_clock::now();
      auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
      out.update_ms = ms(t0, t2);
      out.detail = "extract " + std::to_string(int(ms(t0, t1))) + " ms (" + std::to_string(et.bricks) +
                   " bricks), curvature " + std::to_string(int(ms(t1, t2))) + " ms";
      return out;
    };
    if (lo.lines.any()) {
      setup.show_lines = show_lines;
      setup.lines = [lo](const viz::Surface& s, const Camera& cam, bool surface_changed) {
        const lines::Segments segs =
            reference_device(o) ? lines::extract_reference(s.mesh, s.field, cam, lo)
                                : lines::extract(s.mesh, s.field, cam, lo, device_for(o), nullptr, surface_changed);
        return lines::join_segments(segs);
      };
    }
    viz::run_explorer(setup);
  });
}

}  // namespace isocurv::app
