#include "datasets/sample.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "volume/from_dense.h"

namespace isocurv::datasets {

volume::Volume sample(const Field& field, int resolution, const SampleOptions& options) {
  const std::string path = "generated:" + field.name();
  if (resolution < 2) throw Error(path, "resolution must be at least 2, got " + std::to_string(resolution));
  if (!(options.anisotropy.minCoeff() > 0)) throw Error(path, "anisotropy factors must be positive");

  const Eigen::Vector3d extent = field.box().sizes();
  const double h = extent.maxCoeff() / (resolution - 1);
  const Eigen::Vector3d spacing = h * options.anisotropy;
  const Eigen::Vector3d origin = field.box().min() + options.origin_offset;
  std::array<int, 3> dims{};
  for (int a = 0; a < 3; ++a) dims[a] = static_cast<int>(std::ceil(extent[a] / spacing[a] - 1e-9)) + 1;

  const std::size_t nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<float> data(nx * ny * nz);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ny * nz), [&](const tbb::blocked_range<std::size_t>& rows) {
    std::vector<double> row_values(nx);
    for (std::size_t row = rows.begin(); row != rows.end(); ++row) {
      const std::size_t j = row % ny, k = row / ny;
      field.values_along_x(origin.x(), spacing.x(), origin.y() + j * spacing.y(), origin.z() + k * spacing.z(),
                           dims[0], row_values.data());
      std::copy(row_values.begin(), row_values.end(), data.begin() + row * nx);  // to float
    }
  });

  auto xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(spacing.x(), spacing.y(), spacing.z()));
  xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));

  volume::DenseSource source;
  source.path = path;
  source.format = "generated";
  source.voxel_type = "float";
  source.inside = field.inside();
  source.grid_name = field.inside() == volume::Inside::Below ? "levelset" : "density";
  volume::Volume v = volume::from_dense(data.data(), dims, xform, source);

  if (field.inside() == volume::Inside::Below) {
    v.grid->setGridClass(openvdb::GRID_LEVEL_SET);
    v.grid_class = "level set";
  } else if (v.stats.min >= 0) {
    v.grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    v.grid_class = "fog volume";
  } else {
    v.grid->setGridClass(openvdb::GRID_UNKNOWN);
    v.grid_class = "unknown";
  }
  v.grid->setName(source.grid_name);
  v.grid_name = source.grid_name;
  v.inside = field.inside();
  return v;
}

}  // namespace isocurv::datasets
