// isocurv extract VOLUME -o MESH: the fused isosurface mesh.
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

/// One input -> the mesh file `out`; the report --json prints.
nlohmann::json extract_one(const std::string& in, const std::string& out, const CommonOptions& o) {
  if (o.labelled()) return label_surfaces_to_files(in, out, o, false);
  if (o.split) throw Error("--split needs --labels or --label");
  // A mesh has no isosurface to extract: writing it out again looked like an extraction at
  // isovalue 0 and dropped its arrays.
  if (is_mesh_path(in))
    throw Error(in, "a mesh file: extract takes a volume (isocurv curvature MESH -o OUT writes a "
                    "mesh with its curvature, isocurv check reads one)");
  require_writable_file(out);  // before any work
  StageTimer timer;
  Surface s = load_surface(in, o, timer, EmptySurface::warn);
  timer.start("write");
  const io::Metadata context = context_metadata(s, in);
  io::write_mesh(out, s.mesh, nullptr, o.compress, &context);
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

void register_extract(CLI::App& app) {
  auto* cmd = app.add_subcommand("extract", "Extract the isosurface of a volume as a fused, indexed triangle mesh");
  cmd->footer(
      "Example: isocurv extract lobster.vol --iso 40 -o lobster.ply --json\n"
      "The object is where values are above the isovalue (below for level sets, or with\n"
      "--inside below); triangles are wound so their normals point out of it. An isovalue that\n"
      "gives no surface writes an empty mesh after a warning (the other commands refuse it).");
  static CommonOptions o;
  static BatchCli b;
  static SeriesCli series;
  static std::string out;
  static bool gather = false;
  add_batch_options(*cmd, b, "VOLUME", "Volume file", {"vtp", "ply", "obj", "stl"});
  cmd->add_option("-o,--output", out, std::string("Mesh file to write (") + io::mesh_extensions() +
                                          "), or the folder of a batch; under mpirun a .pvtp, one piece per rank (docs/distributed.md)")->required();
  add_common_options(*cmd, o, false);
  add_compress_option(*cmd, o);
  add_label_options(*cmd, o, true);
  add_series_options(*cmd, series);
  add_distributed_options(*cmd, gather);
  cmd->callback([] {
    if (series.enabled) {
      require_series_cli(b, o);
      run_series(b.inputs, series, {"extract", out}, o,
                 [](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                   return extract_one(f.path, path, fo);
                 });
      return;
    }
    if (run_as_batch(b, o, BatchKind::extract, out)) return;
    if (runs_distributed(out, gather)) {
      print_distributed(run_distributed(b.inputs.front(), out, gather, o, DistributedWork::extract), o);
      return;
    }
    const std::string& in = b.inputs.front();
    const nlohmann::json r = extract_one(in, out, o);
    if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet && o.labelled()) {
      print_label_summary(r, "");
    } else if (!o.quiet) {
      std::cout << "wrote " << out << " (" << format_bytes(r["output_bytes"]) << "): " << r["vertices"] << " vertices, " << r["triangles"] << " triangles at isovalue "
                << r.value("isovalue", 0.0f) << " (extract " << r["timings_ms"].value("extract", 0.0) << " ms)\n";
    }
  });
}

}  // namespace isocurv::app
