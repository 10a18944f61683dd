#pragma once
// mc::extract: a volume's isosurface as a fused, indexed triangle mesh, computed on the device.
// Tested in tests/mc/extract_test.cpp, tests/mc/real_volume_test.cpp.
#include <memory>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::mc {

/// Time spent in each step of one extraction, milliseconds.
struct ExtractTimings {
  double prepare = 0;   ///< Mesher construction: per-block value ranges, kernels (one-shot extract() only)
  double select = 0;    ///< choosing straddling bricks (host)
  double gather = 0;    ///< copying their samples with aprons (host)
  double device = 0;    ///< classify, scans, seams, sort, emit, read back
  // The device steps, separated (queue drained after each) only when timings are requested:
  double classify = 0;  ///< upload, cell cases, triangle/vertex/seam-vertex counts per brick, scans
  double seams = 0;     ///< the vertices other bricks look up: edge hash, key, vertex number
  double sort = 0;      ///< radix sort of their (hash, j) pairs
  double emit = 0;      ///< lookup table; positions; every triangle corner's vertex (mc_emit)
  double read = 0;      ///< the mesh's arrays: allocated, and read back from non-CPU devices
  double snap = 0;      ///< moving vertices onto nearby voxels and merging them (host)
  double total = 0;
  std::size_t bricks = 0;         ///< bricks processed
  std::size_t seam_vertices = 0;  ///< vertices other bricks look up (hashed, sorted, searched)
  std::size_t snapped = 0;        ///< vertices placed by snapping, one a merged group (Options::snap)
  std::size_t merged = 0;         ///< vertices merged into another there
  std::size_t pushed = 0;         ///< vertices moved out along their edge where no merge could be
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
  /// Index-space origins (multiples of 8) of the 8^3-cell bricks that may hold surface at
  /// `isovalue` within the options' cells, in x, y, z order (z fastest): the work an extraction
  /// will do, for balancing the pieces of a distributed one (dist/slabs.h). Host only; cheap.
  std::vector<openvdb::Coord> surface_bricks(float isovalue, const Options& options = {}) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One-shot extraction (Mesher(v, device).extract(isovalue, options)).
Mesh extract(const volume::Volume& v, float isovalue, Device& device, const Options& options = {},
             ExtractTimings* timings = nullptr);

}  // namespace isocurv::mc
