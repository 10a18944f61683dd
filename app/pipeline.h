#pragma once
// What the isocurv subcommands share: options, reading a volume or mesh, the stages, timings.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/volume_options.h"
#include "core/cl_device.h"
#include "core/mesh.h"
#include "core/progress.h"
#include "curvature/curvature_field.h"
#include "curvature/estimator.h"
#include "curvature/options.h"
#include "curvature/request.h"
#include "io/compression.h"
#include "io/mesh_file.h"
#include "labels/label_merge.h"
#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::app {

/// Options common to the commands that run stages.
struct CommonOptions {
  VolumeOptions volume;
  std::optional<float> iso;       ///< --iso; default: the volume's suggested isovalue
  std::string device;             ///< --device: "" the default, an OpenCL device number, or "reference"
  bool cap = false;               ///< --cap
  float snap = mc::kDefaultSnap;  ///< --snap (mc::Options::snap)
  bool json = false;              ///< --json
  bool quiet = false;             ///< --quiet
  std::string normals;            ///< --normals mesh|volume; empty: volume for volume input
  bool flip = false;              ///< --flip: reverse a mesh file's triangles
  float ao_scale = 0;             ///< --ao-scale; 0: 4 x the mean edge length
  io::Compression compress;       ///< --compress (.vtp outputs)
  std::string estimator;          ///< --estimator (curvature::estimator_names); empty: rusinkiewicz
  std::string scale = "auto";     ///< --scale: sigma in world units, a list "1,2,4", or "auto"
  std::string batagelo_weights;   ///< --batagelo-weights uniform|inverse-square; empty: uniform
  std::string ao;                 ///< --ao-method (ao::method_names); empty: griffin, the estimators' own
  bool hattori_half = false;      ///< --hattori-half
  bool labels = false;            ///< --labels: one surface per label of a label map
  std::string label_list;         ///< --label 3,7: those labels only (implies --labels)
  bool split = false;             ///< --split: one mesh file per label, in the -o folder
  /// True when the input is to be read as a label map (--labels or --label).
  bool labelled() const { return labels || !label_list.empty(); }
};

/// The scales of a --scale value, as written: {"auto"}, {"1.5"} or {"1", "2", "4"}. Throws Error
/// for an entry that is not a positive finite number, a repeated one, or auto among several.
std::vector<std::string> parse_scales(const std::string& text);

/// Sets what --scale (its first value; 0 for auto) and --batagelo-weights ask for in `co`.
void apply_estimator_parameters(const CommonOptions& o, curvature::Options& co);

/// Adds --iso --device --cap --snap --json --quiet and the volume options.
void add_common_options(CLI::App& cmd, CommonOptions& o, bool with_iso = true);
/// Adds --estimator, --scale, --normals, --batagelo-weights and --ao-scale, and --flip when the
/// command takes mesh files.
void add_curvature_options(CLI::App& cmd, CommonOptions& o, bool mesh_input = false);

/// Adds --ao-method METHOD and --hattori-half (named so, as SEEDS-SPEC G-AO2 does: --ao is
/// render's shortcut for --shading ambient-ao) (curvature, run, render, view).
void add_ao_options(CLI::App& cmd, CommonOptions& o);

/// Adds --compress none|lz4|zlib[:LEVEL] (io/compression.h) for the commands that write meshes.
void add_compress_option(CLI::App& cmd, CommonOptions& o);

/// Wall-clock timings of the stages of one command, reported as "timings_ms", with a progress
/// bar on a terminal for each stage that runs over half a second (StageBar; none with --quiet).
/// Time spent building OpenCL programs inside a stage (the first extraction or curvature of a
/// process, unless the program cache had them) is moved out of that stage into "compile".
class StageTimer {
 public:
  /// Starts timing `stage` (and its bar); the previous stage (if any) ends here.
  void start(const std::string& stage);
  void stop();
  /// Moves `ms` of stage `from`'s time to stage `to`: a step timed inside a stage (the AO inside
  /// the curvature stage, EstimatorReport::ao_ms) reported as its own.
  void move(const std::string& from, const std::string& to, double ms);
  const nlohmann::json& json() const { return timings_; }

 private:
  std::unique_ptr<StageBar> bar_;
  std::string current_;
  std::chrono::steady_clock::time_point t0_;
  double compile0_ = 0;  ///< program_build_stats().ms when the stage started
  nlohmann::json timings_ = nlohmann::json::object();
};

/// Applies --ao-method to a `field` not estimated here (a file's own curvature; stage "ao";
/// nothing for the default griffin, which every estimator already gives): curvature::apply_ao at
/// --ao-scale (or 4 mean edge lengths). Its rules are curvature::check_ao's, worded with the
/// options: a ray cast without `volume` (a mesh file) is an Error saying it needs the volume;
/// --hattori-half without --ao-method hattori is an Error.
void apply_ao(const Mesh& mesh, curvature::CurvatureField& field, const volume::Volume* volume,
              float isovalue, const CommonOptions& o, StageTimer& timer);

/// True for a mesh file extension (.vtp .ply .obj .stl), false for anything else (a volume).
bool is_mesh_path(const std::string& path);

/// Which normals the curvature estimate used, and how many vertices fell back to face normals.
struct NormalsUsed {
  std::string source;           ///< "mesh" or "volume"; empty before any estimate
  std::size_t opposed = 0;      ///< volume: gradient normal against the faces (face normal used)
  std::size_t weak = 0;         ///< volume: gradient near zero (face normal used)
  std::size_t caps = 0;         ///< volume with --cap: cap vertices given the box face's normal
};

/// A loaded input: a volume (then `mesh` is extracted from it) or a mesh file.
struct Surface {
  std::optional<volume::Volume> volume;
  float isovalue = 0;
  Mesh mesh;
  std::optional<curvature::CurvatureField> field;  ///< carried by a mesh file, or estimated
  NormalsUsed normals;       ///< set by estimate_curvature
  curvature::EstimatorReport estimator;  ///< set by estimate_curvature
  std::size_t welded = 0;    ///< duplicate vertices merged by prepare_mesh_for_curvature
  bool flipped = false;      ///< triangles reversed by --flip
  io::Metadata file_metadata;  ///< a mesh file's field data (io::MeshFile::metadata)
  /// A label map's surfaces (app/label_surfaces.h): each triangle's label (the "Label" cell
  /// array the mesh files carry), and where each label's vertices and triangles lie; empty
  /// otherwise.
  io::CellArrays label_cells;
  std::vector<labels::LabelPart> label_parts;
};

/// Where a surface came from, for titles, legends and anatomical views: from its volume, or from
/// the field data of a mesh file isocurv wrote (context_metadata), so that `render mesh.vtp`
/// shows what `run` showed.
struct SurfaceContext {
  std::optional<float> isovalue;  ///< the isovalue the mesh was extracted at
  std::string length_unit;        ///< world length unit ("mm"); empty: unknown
  std::string world_space;        ///< Volume::world_space ("RAS", "LPS", ...); empty: none
  /// A mesh file's curvature as titles name it: "volume, scale 1.5" (estimator_title of the
  /// file's "estimator" and "scale"); empty for volumes and files without them.
  std::string file_estimator;
  /// The radius of support of a features mesh computed at one radius (`features` writes it as
  /// field data "feature_radius", as the user gave it: "3%", "0.5"); empty otherwise.
  std::string feature_radius;
};

/// The context of `s`: its volume's (isovalue, Volume::length_unit, world_space), else its mesh
/// file's field data.
SurfaceContext surface_context(const Surface& s);

/// The context of `s` as the field-data pairs io::write_mesh adds to a .vtp: "isovalue" (%.9g),
/// "length_unit" (`length_unit` when given, e.g. --unit, else the context's), "world_space" and
/// "source" (the input's file name), and for a label map's surfaces "labels" ("1,2,5") instead of
/// the isovalue; empty values are left out.
io::Metadata context_metadata(const Surface& s, const std::string& input,
                              const std::string& length_unit = "");

/// True for --device reference: the C++ references (mc::extract_reference, the double-precision
/// curvature::estimate_reference) instead of OpenCL. Slow, single-threaded, needs no driver.
bool reference_device(const CommonOptions& o);

/// The OpenCL device chosen by --device (opened once per process). With no OpenCL platform the
/// Error names the packages to install and suggests --device reference. Not for the reference.
Device& device_for(const CommonOptions& o);

/// The name of the device --device chose, for reports ("reference (C++)" for the reference).
std::string device_name(const CommonOptions& o);

/// The isosurface of `v` at `isovalue` on the chosen device (OpenCL or the reference).
Mesh extract_surface(const volume::Volume& v, float isovalue, const CommonOptions& o);

/// Loads a volume (stage "load") and checks --iso against its value range: an isovalue outside
/// [min, max], or at the end of the range where no voxel can be inside (a voxel equal to the
/// isovalue is outside: the maximum for --inside above, the minimum for below), is an Error
/// naming the file.
volume::Volume load_volume(const std::string& path, const CommonOptions& o, StageTimer& timer, float* iso);

/// The isovalue to use on `v`: `requested`, or the suggested one when it is empty; checked as
/// load_volume describes (volume::checked_isovalue; an Error naming `path` when outside the range
/// or at its inside end).
float checked_isovalue(const std::string& path, const volume::Volume& v,
                       std::optional<float> requested);

/// What a command does when the isosurface has no triangles (README, "The empty surface"):
/// `error` for the commands that need triangles (curvature, run, render, check), `warn` for
/// extract, which writes the empty mesh after one warning line on stderr (unless --quiet).
enum class EmptySurface { error, warn };

/// Applies that rule to `s` (a volume's isosurface at s.isovalue): nothing when it has triangles,
/// else an Error naming `path` (`error`) or one warning line unless --quiet (`warn`).
void handle_empty_surface(const Surface& s, const std::string& path, const CommonOptions& o,
                          EmptySurface empty);

/// Volume path -> load + extract (stage "extract"), the empty surface handled per `empty`; mesh
/// path -> read (stage "load"), an Error when volume-only options (--iso --cap --grid --inside
/// --dims --type --endian --spacing --origin) were given, since they cannot apply.
Surface load_surface(const std::string& path, const CommonOptions& o, StageTimer& timer,
                     EmptySurface empty = EmptySurface::error);

/// Throws Error(path, ...) unless `path` is a mesh format that carries curvature arrays (.vtp,
/// .ply): .obj and .stl would silently drop them.
void require_curvature_format(const std::string& path);

/// Readies a mesh file's mesh for curvature (nothing for a volume's isosurface): welds exact
/// duplicate vertices (a note on stderr unless --quiet), applies --flip (an Error on volume
/// input), and warns (one line on stderr) when the closed part of the mesh is oriented inward.
void prepare_mesh_for_curvature(Surface& s, const std::string& path, const CommonOptions& o);

/// Re-estimates the curvature of `s` (prepare_mesh_for_curvature, then estimate_curvature into
/// s.field, s.normals, s.estimator) keeping the extra arrays the file carried (features, _s<S>
/// scales) when the vertices are still the file's (no welding): render with --flip or a mesh
/// without H must not lose what it is asked to colour.
void reestimate_keeping_extras(Surface& s, const std::string& path, const CommonOptions& o,
                               StageTimer& timer);

/// The normals the mesh estimators take for --normals (curvature::resolve's rule): the option,
/// else the volume's gradient with a volume input, else the mesh's faces. Throws isocurv::Error for
/// --normals volume without a volume.
curvature::NormalsSource mesh_estimators_normals(const CommonOptions& o, bool volume_input);

/// The estimator a command runs (curvature::default_estimator): --estimator when given, else
/// volume for volume input without --normals, else rusinkiewicz.
curvature::Estimator default_estimator(const CommonOptions& o, bool volume_input);

/// Estimates the curvature of `mesh` (stage "curvature") on the chosen device with --estimator
/// and the AO --ao-method chooses (curvature::estimate_field; the AO's time reported as stage
/// "ao"). The request's rules
/// are curvature::resolve's (curvature/request.h), its errors worded with the options: the mesh
/// estimators' normals are --normals, by default volume when `volume` is given, else mesh; volume
/// normals come from volume::gradient_normals_for_mesh (face normals where the gradient disagrees
/// or vanishes). --normals volume without a volume (a mesh file) is an Error. The volume estimator
/// (at --scale, from `volume` at `isovalue`) takes no --normals and needs a volume. `used` and `report`, when given, receive what was used. `piece`: `mesh` is one
/// piece of a distributed surface (curvature::Options::piece; collective).
curvature::CurvatureField estimate_curvature(const Mesh& mesh, const volume::Volume* volume,
                                             float isovalue, const CommonOptions& o,
                                             StageTimer& timer, NormalsUsed* used = nullptr,
                                             curvature::EstimatorReport* report = nullptr,
                                             const SurfacePiece* piece = nullptr);

/// Mesh and curvature statistics for --json and stats.json: counts, area, Euler characteristic,
/// genus, the normals used and their fallbacks, and, when a field is present, the area-weighted
/// min/max/mean/percentiles of H, K, k1, k2 over the reliable vertices (curvature::field_stats).
nlohmann::json surface_report(const Surface& s);

/// The OpenCL program builds of this process, for --json: {"compiled", "from_cache", "rejected",
/// "cache_dir"} (core/program_cache.h; cache_dir null when the cache is off).
nlohmann::json program_report();

/// The size of a written file in bytes (0 when it cannot be read), for reports.
std::uint64_t file_bytes(const std::string& path);

/// "1.23 MB" (10^6 bytes), for the normal summaries.
std::string format_bytes(std::uint64_t bytes);

/// A number as %g (for messages).
std::string format_number(double x);

/// Writes text atomically (for JSON outputs).
void write_text_file(const std::string& path, const std::string& text);

}  // namespace isocurv::app
