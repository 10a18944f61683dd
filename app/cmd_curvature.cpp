// isocurv curvature VOLUME|MESH -o MESH: a mesh carrying every curvature array.
#include <iostream>

#include "core/atomic_file.h"
#include "app/batch.h"
#include "app/commands.h"
#include "app/distributed.h"
#include "app/label_surfaces.h"
#include "core/error.h"
#include "app/pipeline.h"
#include "app/series.h"
#include "io/mesh_file.h"

namespace isocurv::app {
namespace {

/// One input -> the mesh file `out` with every curvature array; the report --json prints.
nlohmann::json curvature_one(const std::string& in, const std::string& out,
                             const CommonOptions& o) {
  if (o.labelled()) {
    if (!o.split) require_curvature_format(out);  // .obj and .stl would drop the arrays
    return label_surfaces_to_files(in, out, o, true);
  }
  if (o.split) throw Error("--split needs --labels or --label");
  require_curvature_format(out);  // before any work: .obj and .stl would drop the arrays
  require_writable_file(out);
  StageTimer timer;
  Surface s = load_surface(in, o, timer);
  prepare_mesh_for_curvature(s, in, o);
  s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                               &s.normals, &s.estimator);
  timer.start("write");
  const io::Metadata context = context_metadata(s, in);
  io::write_mesh(out, s.mesh, &*s.field, o.compress, &context);
  timer.stop();
  nlohmann::json r = surface_report(s);
  r["input"] = in;
  r["output"] = out;
  r["output_bytes"] = file_bytes(out);
  r["compression"] = io::to_string(o.compress);
  r["programs"] = program_report();
  r["device"] = device_name(o);
  r["timings_ms"] = timer.json();
  return r;
}

}  // namespace

void register_curvature(CLI::App& app) {
  auto* cmd = app.add_subcommand("curvature", "Estimate per-vertex curvature (k1 k2 dir1 dir2 H K dcurv ShapeIndex Curvedness AO) "
                                              "on a volume's isosurface or on a mesh");
  cmd->footer("Example: isocurv curvature torus.vdb -o torus.vtp --normals volume --json\n"
              "Series: isocurv curvature --time-series 'frames/*.ply' -o out/  (out/<frame>.vtp, out/series.pvd)\n"
              "Normals point out of the object, so a solid sphere of radius R has k1 = k2 = H = +1/R.");
  static CommonOptions o;
  static BatchCli b;
  static SeriesCli series;
  static std::string out;
  static bool gather = false;
  add_batch_options(*cmd, b, "VOLUME_OR_MESH", "Volume or mesh file", {"vtp", "ply"});
  cmd->add_option("-o,--output", out,
                  "Mesh file to write (.vtp or .ply: the formats that carry the curvature arrays), "
                  "or the folder of a batch; under mpirun a .pvtp, one piece per rank (docs/distributed.md)")
      ->required();
  add_common_options(*cmd, o, false);
  add_curvature_options(*cmd, o, true);
  add_ao_options(*cmd, o);
  add_compress_option(*cmd, o);
  add_label_options(*cmd, o, true);
  add_series_options(*cmd, series);
  add_distributed_options(*cmd, gather);
  cmd->callback([] {
    if (series.enabled) {
      require_series_cli(b, o);
      run_series(b.inputs, series, {"curvature", out}, o,
                 [](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                   return curvature_one(f.path, path, fo);
                 });
      return;
    }
    if (run_as_batch(b, o, BatchKind::curvature, out)) return;
    if (runs_distributed(out, gather)) {
      print_distributed(run_distributed(b.inputs.front(), out, gather, o, DistributedWork::curvature), o);
      return;
    }
    const nlohmann::json r = curvature_one(b.inputs.front(), out, o);
    if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet && o.labelled()) {
      print_label_summary(r, " with curvature");
    } else if (!o.quiet) {
      std::cout << "wrote " << out << " (" << format_bytes(r["output_bytes"]) << "): " << r["vertices"]
                << " vertices with curvature (curvature " << r["timings_ms"].value("curvature", 0.0)
                << " ms)\n";
    }
  });
}

}  // namespace isocurv::app
