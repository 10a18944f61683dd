#include "curvature/mesh_estimators.h"

#include "curvature/batagelo.h"
#include "curvature/cubic_fit.h"
#include "curvature/meyer.h"
#include "curvature/normal_sampling.h"
#include "curvature/prantl.h"
#include "curvature/quadric_fit.h"
#include "curvature/reference.h"

namespace isocurv::curvature {

const std::vector<MeshEstimatorInfo>& mesh_estimators() {
  static const std::vector<MeshEstimatorInfo> list = {
      {MeshEstimator::rusinkiewicz, "rusinkiewicz",
       "per-face tensors from normal differences, averaged (Rusinkiewicz 2004, Griffin 2012)",
       true, true, true},
      {MeshEstimator::batagelo, "batagelo",
       "one pass over each vertex's 1-ring, with derivative (Batagelo & Wu 2007)", true, true,
       true},
      {MeshEstimator::prantl3, "prantl3",
       "per-triangle shape operator from 3 edges, H and K averaged (Prantl et al. 2017)", true,
       false, false},
      {MeshEstimator::prantl2, "prantl2",
       "per-triangle shape operator from 2 edges (same H as prantl3)", true, false, false},
      {MeshEstimator::quadric, "quadric", "quadric fit to the 1-ring positions (Taubin-style)",
       false, true, false},
      {MeshEstimator::cubic, "cubic",
       "cubic fit to the 1-ring positions and normals (Goldfeather & Interrante 2004)", false,
       true, false},
      {MeshEstimator::sampling, "sampling",
       "Euler fit to normal curvatures sampled along the edges (Batagelo eq. 12)", false, true,
       false},
      {MeshEstimator::meyer, "meyer",
       "cotangent mean and angle-deficit Gaussian curvature (Meyer et al. 2003)", false, false,
       false}};
  return list;
}

const MeshEstimatorInfo& mesh_estimator_info(MeshEstimator e) {
  return mesh_estimators()[static_cast<std::size_t>(e)];
}

std::optional<MeshEstimator> mesh_estimator_from_name(const std::string& name) {
  for (const MeshEstimatorInfo& i : mesh_estimators())
    if (name == i.name) return i.id;
  return std::nullopt;
}

CurvatureField estimate_mesh(MeshEstimator e, const Mesh& mesh, Device* device,
                             const Options& options, Timings* timings) {
  switch (e) {
    case MeshEstimator::rusinkiewicz:
      return device ? estimate(mesh, *device, options, timings) : estimate_reference(mesh, options);
    case MeshEstimator::batagelo:
      return device ? estimate_batagelo(mesh, *device, options, timings)
                    : estimate_batagelo_reference(mesh, options);
    case MeshEstimator::prantl3:
    case MeshEstimator::prantl2: {
      const int edges = e == MeshEstimator::prantl3 ? 3 : 2;
      return device ? estimate_prantl(mesh, *device, options, edges, PrantlAveraging::area, timings)
                    : estimate_prantl_reference(mesh, options, edges);
    }
    case MeshEstimator::quadric:
      return estimate_quadric_fit_reference(mesh, options);
    case MeshEstimator::cubic:
      return estimate_cubic_fit_reference(mesh, options);
    case MeshEstimator::sampling:
      return estimate_normal_sampling_reference(mesh, options);
    case MeshEstimator::meyer:
      return estimate_meyer_reference(mesh, options);
  }
  return {};
}

}  // namespace isocurv::curvature
