#pragma once
// mc::extract: a volume's isosurface as a fused, indexed triangle mesh, computed on the device.
#include <memory>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::mc {

/// Time spent in each step of one extraction, milliseconds.
struct ExtractTimings {
  double select = 0;    ///< choosing straddling bricks (host)
  double gather = 0;    ///< copying their samples with aprons (host)
  double device = 0;    ///< classify, scans, generate, sort, fuse, read back
  // The device steps, separated (queue drained after each) only when timings are requested:
  double classify = 0;  ///< upload, triangle and vertex counts per cell and their scans
  double generate = 0;  ///< one vertex per crossed edge: position, edge key, hash
  double sort = 0;      ///< radix sort of (hash, vertex) pairs
  double fuse = 0;      ///< lookup table; every triangle corner's vertex (binary search, walk)
  double read = 0;      ///< positions, triangles (and edge keys) read back to the host
  double total = 0;
  std::size_t bricks = 0;  ///< bricks processed
};

/// A volume prepared for repeated extraction (the explorer's slider): the per-block value ranges
/// are computed once; each extract() touches only bricks straddling its isovalue.
class Mesher {
 public:
  Mesher(const volume::Volume& v, Device& device);
  ~Mesher();
  /// The isosurface at `isovalue`: world-space positions, triangles wound so normals point out of
  /// the object, no duplicate or unreferenced vertices. An isovalue outside the value range gives
  /// an empty mesh. Deterministic. `timings` (optional) receives the step times.
  Mesh extract(float isovalue, const Options& options = {}, ExtractTimings* timings = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One-shot extraction (Mesher(v, device).extract(isovalue, options)).
Mesh extract(const volume::Volume& v, float isovalue, Device& device, const Options& options = {},
             ExtractTimings* timings = nullptr);

}  // namespace isocurv::mc
