#pragma once
// What the isocurv subcommands share: options, reading a volume or mesh, the stages, timings.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <optional>
#include <string>

#include "app/volume_options.h"
#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"
#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::app {

/// Options common to the commands that run stages.
struct CommonOptions {
  VolumeOptions volume;
  std::optional<float> iso;       ///< --iso; default: the volume's suggested isovalue
  int device = -1;                ///< --device; -1: default device
  bool cap = false;               ///< --cap
  float snap = mc::kDefaultSnap;  ///< --snap (mc::Options::snap)
  bool json = false;              ///< --json
  bool quiet = false;             ///< --quiet
  std::string normals = "mesh";   ///< --normals mesh|volume
  float ao_scale = 0;             ///< --ao-scale; 0: 4 x the mean edge length
};

/// Adds --iso --device --cap --snap --json --quiet and the volume options.
void add_common_options(CLI::App& cmd, CommonOptions& o, bool with_iso = true);
/// Adds --normals and --ao-scale.
void add_curvature_options(CLI::App& cmd, CommonOptions& o);

/// Wall-clock timings of the stages of one command, reported as "timings_ms".
class StageTimer {
 public:
  /// Starts timing `stage`; the previous stage (if any) ends here.
  void start(const std::string& stage);
  void stop();
  const nlohmann::json& json() const { return timings_; }

 private:
  std::string current_;
  std::chrono::steady_clock::time_point t0_;
  nlohmann::json timings_ = nlohmann::json::object();
};

/// True for a mesh file extension (.vtp .ply .obj .stl), false for anything else (a volume).
bool is_mesh_path(const std::string& path);

/// A loaded input: a volume (then `mesh` is extracted from it) or a mesh file.
struct Surface {
  std::optional<volume::Volume> volume;
  float isovalue = 0;
  Mesh mesh;
  std::optional<curvature::CurvatureField> field;  ///< carried by a mesh file, or estimated
};

/// The device chosen by --device (opened once per process).
Device& device_for(const CommonOptions& o);

/// Loads a volume (stage "load") and checks --iso against its value range (an isovalue outside
/// [min, max] is an Error naming the file).
volume::Volume load_volume(const std::string& path, const CommonOptions& o, StageTimer& timer, float* iso);

/// Volume path -> load + extract; mesh path -> read (stage "load").
Surface load_surface(const std::string& path, const CommonOptions& o, StageTimer& timer);

/// Estimates the curvature of `mesh` (stage "curvature"), with normals from the gradient of
/// `volume` when --normals volume (an Error when volume is null, i.e. the input was a mesh).
curvature::CurvatureField estimate_curvature(const Mesh& mesh, const volume::Volume* volume,
                                             const CommonOptions& o, StageTimer& timer);

/// Mesh and curvature statistics for --json and stats.json: counts, area, Euler characteristic,
/// genus, and min/max/mean/percentiles of H, K, k1, k2 when a field is present.
nlohmann::json surface_report(const Surface& s);

/// A number as %g (for messages).
std::string format_number(double x);

/// Writes text atomically (for JSON outputs).
void write_text_file(const std::string& path, const std::string& text);

}  // namespace isocurv::app
