#include "mc/frame.h"

#include <algorithm>

#include "core/error.h"
#include "mc/edge_key.h"

namespace isocurv::mc {

Frame make_frame(const volume::Volume& v, float iso, const Options& options) {
  if (!v.grid) throw Error(v.path, "volume has no grid");
  if (options.hash_bits < 1 || options.hash_bits > 32)
    throw Error("hash width must be 1..32 bits, not " + std::to_string(options.hash_bits));
  if (!(options.snap >= 0 && options.snap <= 0.5f))
    throw Error("snap distance must be 0..0.5 voxel, not " + std::to_string(options.snap));
  Frame f;
  f.isovalue = iso;
  f.sign = v.inside == volume::Inside::Above ? 1.0f : -1.0f;
  double span = std::max({std::abs(v.stats.max - iso), std::abs(v.stats.min - iso), 1e-6});
  f.outside = -static_cast<float>(std::min(span, 1e30));
  f.domain = v.domain;
  if (v.domain.empty()) {
    f.cells = openvdb::CoordBBox();  // empty
  } else if (v.dense) {
    f.clip = true;
    if (options.cap) {
      f.cells = openvdb::CoordBBox(v.domain.min() - openvdb::Coord(1), v.domain.max());
    } else {
      f.cells = openvdb::CoordBBox(v.domain.min(), v.domain.max() - openvdb::Coord(1));
    }
  } else {
    f.cells = openvdb::CoordBBox(v.domain.min() - openvdb::Coord(1), v.domain.max());
  }
  f.key_origin = f.cells.min() - openvdb::Coord(1);
  if (!f.cells.empty()) {
    openvdb::Coord ext = f.cells.max() - f.key_origin;
    if (ext.x() > kMaxKeySpan || ext.y() > kMaxKeySpan || ext.z() > kMaxKeySpan)
      throw Error(v.path, "volume spans more than 2^20 voxels along an axis; cannot mesh it");
    // A piece (Options::cells_min/max): fewer cells, the same keys.
    const openvdb::CoordBBox piece(openvdb::Coord(options.cells_min[0], options.cells_min[1], options.cells_min[2]),
                                   openvdb::Coord(options.cells_max[0], options.cells_max[1], options.cells_max[2]));
    f.cells.intersect(piece);
  }
  const openvdb::math::Transform& xf = v.grid->transform();
  if (!xf.isLinear()) throw Error(v.path, "grid transform is not affine (frustum grids are not supported)");
  openvdb::Mat4d m = xf.baseMap()->getAffineMap()->getMat4();
  // OpenVDB multiplies row vectors: world = [i j k 1] * m.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) f.world[r * 4 + c] = static_cast<float>(m(c, r));
    f.world[r * 4 + 3] = static_cast<float>(m(3, r));
  }
  return f;
}

}  // namespace isocurv::mc
