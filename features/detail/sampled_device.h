#pragma once
// The device side of features::compute(..., Device&): features_kernels.cl's two kernels over
// every vertex, for one radius. Internal.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "features/detail/geodesic_web.h"
#include "volume/dense_field.h"

namespace isocurv::features::detail {

/// Called with the number of vertices done after each launch of kLaunchVertices.
using ProgressFn = std::function<void(std::size_t)>;
inline constexpr std::size_t kLaunchVertices = 8192;

/// features_web at radius r for every vertex (the device's trace_web); `normals` unit, one per
/// vertex. `work_group` the launch's local size (tests use sizes above 1 as a GPU would).
std::vector<WebSums> web_on_device(Device& device, const volume::DenseField& field, float iso,
                                   const Mesh& mesh, const std::vector<Vec3f>& normals, double r,
                                   int azimuths, bool adaptive, double threshold,
                                   std::uint32_t seed, int work_group = 64,
                                   const ProgressFn& progress = {});

/// What features_ball gives per vertex (VolumeBall::Result).
struct BallOnDevice {
  std::vector<float> vr, h;
  std::vector<std::uint8_t> leaves;
};

/// features_ball at radius r for every vertex (the device's VolumeBall::inside_volume).
BallOnDevice ball_on_device(Device& device, const volume::DenseField& field, float iso,
                            const Mesh& mesh, const std::vector<Vec3f>& normals, double r,
                            int azimuths, const std::vector<double>& nodes,
                            const std::vector<double>& weights, int work_group = 64,
                            const ProgressFn& progress = {});

}  // namespace isocurv::features::detail
