#pragma once
// from_dense for 8-bit data, without an intermediate float copy (most large volumes are uint8).
// Tested through the loaders of 8-bit files: tests/volume/test_loaders.cpp.
#include <cstdint>

#include "volume/from_dense.h"

namespace isocurv::volume {

/// Same as from_dense, reading uint8 voxels (X fastest) directly.
Volume from_dense_u8(const std::uint8_t* data, const std::array<int, 3>& dims, openvdb::math::Transform::Ptr xform,
                     const DenseSource& source, const DensePart& part = {});

}  // namespace isocurv::volume
