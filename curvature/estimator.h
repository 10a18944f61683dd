#pragma once
// curvature::estimate_field: every curvature estimator behind one call (Options::estimator), all
// returning the same CurvatureField (names and conventions of curvature_field.h), with the AO
// Options::ao_method asks for (apply_ao).
// Tested in tests/curvature/ct_classes_test.cpp, tests/curvature/volume_estimate_test.cpp.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// The estimator's name as the command line and the reports spell it: "rusinkiewicz", "volume".
const char* estimator_name(Estimator e);
/// The estimator called `name`, or nothing for an unknown name.
std::optional<Estimator> estimator_from_name(const std::string& name);
/// Every estimator's name, in enum order (for help texts and error messages).
std::vector<std::string> estimator_names();

/// The CurvatureField arrays (file names: "Normals", "Area", ...) estimator `e` fills; the others
/// stay empty and are absent from output files.
std::vector<std::string> arrays_filled(Estimator e);

/// True when estimator `e` needs the volume the mesh was extracted from.
bool needs_volume(Estimator e);

/// The volume a mesh was extracted from, for the estimators that read it.
struct VolumeSource {
  const volume::Volume* volume = nullptr;  ///< must outlive the call
  float isovalue = 0;                      ///< the mesh's isovalue
};

/// What an estimate_field call used, for reports (--json, stats.json, the VTP's field data).
struct EstimatorReport {
  std::string estimator;  ///< estimator_name
  /// The estimator's parameters by name, in a fixed order, e.g. {"scale", 1.5} (world units).
  std::vector<std::pair<std::string, double>> parameters;
  /// How a parameter chosen from the data was chosen, e.g. {"scale", "auto"}; empty otherwise.
  std::vector<std::pair<std::string, std::string>> notes;
  /// Vertices flagged "Unreliable": the estimator's own (volume: vanishing gradient) and the
  /// implausible ones (flag_implausible, field_stats.h).
  std::size_t unreliable = 0;
  std::size_t implausible = 0;  ///< of those, flagged by flag_implausible
  /// volume: vertices measured at a finer scale than asked (the per-vertex "Scale" array)
  std::size_t finer_scale = 0;
  /// volume: vertices whose smoothing reaches outside the volume's box at their scale (flagged
  /// Boundary)
  std::size_t outside = 0;
  /// volume on a device: wall time of its steps in ms, in order: auto_scale (when the scale was
  /// chosen from the data), then VolumeStepTimes's plan, gather, passes, vertices, host. Not in
  /// the field's metadata (outputs stay deterministic).
  /// volume: the pyramid's coarse bricks kept from an earlier estimate on the same volume
  /// (volume::PyramidLease; reports only, never written to files: it depends on what ran before).
  std::size_t pyramid_bricks_kept = 0;
  std::vector<std::pair<std::string, double>> steps_ms;
  /// Wall time of apply_ao in ms, when it computed an AO (ao_method other than griffin); not in
  /// the field's metadata.
  std::optional<double> ao_ms;
};

/// Per-vertex curvature of `mesh` by options.estimator, on `device` or, when device is nullptr,
/// by the estimator's double-precision C++ reference. The volume estimator needs `source` (with a
/// volume; else Error "needs a volume"); the mesh estimators ignore it. The last step is apply_ao
/// (options.ao_method; the ray casts read `source` too). Deterministic. Throws isocurv::Error for
/// invalid input or options, or an OpenCL failure. `report`, when given, receives what was used.
/// resolve (curvature/request.h) states the rules the options must follow.
CurvatureField estimate_field(const Mesh& mesh, const VolumeSource& source, Device* device,
                              const Options& options, EstimatorReport* report = nullptr);

/// The AO array of `field` by options.ao_method at options.ao_scale: nothing for griffin (every
/// estimator's own AO, already in the field), else ao::compute (ao/ao.h: the array, and the
/// field's "ao*" metadata) with options.hattori_half. estimate_field's last step, and the same
/// step on a field it did not estimate (a mesh file's own curvature). Returns whether it computed
/// (false for griffin). check_ao states the rules; a ray cast without source.volume throws
/// ao::compute's Error.
bool apply_ao(const Mesh& mesh, CurvatureField& field, const VolumeSource& source,
              const Options& options);

}  // namespace isocurv::curvature
