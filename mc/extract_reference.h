#pragma once
// The plain sequential marching cubes: the specification the device mesher is tested against.
// Tested in tests/mc/extract_test.cpp, tests/mc/snap_test.cpp.
#include "core/mesh.h"
#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::mc {

/// Visits every cell of the frame (mc/frame.h) in z, y, x order and fuses vertices with an
/// ordered map from edge key to vertex index. Same vertex placement, case table and winding as
/// mc::extract; vertex order may differ. Slow: for tests on small volumes.
Mesh extract_reference(const volume::Volume& v, float isovalue, const Options& options = {});

}  // namespace isocurv::mc
