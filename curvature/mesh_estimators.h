#pragma once
// Every per-vertex curvature estimator that needs only the mesh (and its normals), by name: the
// project's Rusinkiewicz estimator, the seeds' one-pass estimators (Batagelo, Prantl) and the
// comparison estimators (quadric and cubic fits, normal-curvature sampling, Meyer's operators).
// Tested in tests/deform/prepared_test.cpp.
#include <optional>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/options.h"

namespace isocurv::curvature {

enum class MeshEstimator { rusinkiewicz, batagelo, prantl3, prantl2, quadric, cubic, sampling, meyer };

/// What an estimator is and produces.
struct MeshEstimatorInfo {
  MeshEstimator id;
  const char* name;     ///< as the command line spells it: "rusinkiewicz", "batagelo", ...
  const char* summary;  ///< one line for help texts and reports
  bool kernels;         ///< has an OpenCL path (else only the double reference runs)
  bool directions;      ///< fills dir1 and dir2
  bool derivative;      ///< fills dcurv
};

/// All of them, in enum order.
const std::vector<MeshEstimatorInfo>& mesh_estimators();
/// The estimator's entry.
const MeshEstimatorInfo& mesh_estimator_info(MeshEstimator e);
/// The estimator called `name`, or nothing.
std::optional<MeshEstimator> mesh_estimator_from_name(const std::string& name);

/// Per-vertex curvature of `mesh` by `e`: its kernel path on `device` when it has one and device
/// is not nullptr, else its double-precision reference. Prantl's variants average by area. The
/// arrays the estimator does not produce are left empty (mesh_estimator_info). `timings` (kernel
/// paths only) receives the step times.
/// @throw isocurv::Error for invalid input (check_input) or an OpenCL failure
CurvatureField estimate_mesh(MeshEstimator e, const Mesh& mesh, Device* device,
                             const Options& options = {}, Timings* timings = nullptr);

}  // namespace isocurv::curvature
