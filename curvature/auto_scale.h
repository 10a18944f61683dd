#pragma once
// --scale auto: the volume estimator's Gaussian scale chosen from the data.
// Tested in tests/curvature/volume_estimate_test.cpp, tests/curvature/volume_piece_test.cpp.
#include <string>

#include "core/mesh.h"
#include "core/surface_piece.h"
#include "curvature/adaptive_scale.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// The noise level (noise / edge step per voxel) that kAutoScaleExponent maps to one voxel
/// (before the clamp below);
/// chosen on the CT-like test volumes (bench/bench_accuracy) as the value whose choice lands
/// nearest the best fixed scale there.
inline constexpr double kAutoReferenceNoise = 0.004;
/// The scale grows as (noise level / kAutoReferenceNoise)^(2/7): with Gaussian derivative
/// filters the noise in the Hessian falls as sigma^-7/2 (3-D, second derivatives), so this keeps
/// the noise in the curvature near what it is at one voxel for kAutoReferenceNoise.
inline constexpr double kAutoScaleExponent = 2.0 / 7.0;
/// The chosen scale stays within [kAutoMinVoxels, kAutoMaxVoxels] voxels (the geometric mean
/// spacing; and never under volume::kMinScaleVoxels of the largest).
/// On smooth fields the error is the smoothing's own bias, about (sigma k)^2 (bench_accuracy,
/// torus 128^3: H 0.27% at one voxel, 0.13% at 0.7), and the B-spline reconstruction does not
/// alias at 0.7 voxel (sphere H 0.03%), so smooth fields get 0.8 voxel.
inline constexpr double kAutoMinVoxels = 0.8, kAutoMaxVoxels = 4.0;

/// The scale of a binary volume (two values: masks, voxelised parts), in voxels. Its noise is
/// all quantisation, one step the whole contrast, and not white: the noise model above does not
/// hold (it would ask for its 4-voxel cap), nor does a measured noise of zero (0.8 voxel, which
/// keeps the voxel staircase). Chosen on bench_accuracy's binary sphere, torus and CAD part (the
/// best fixed scales lie at 1.5-2 voxels) and the published torus of DGtal's normal currents.
inline constexpr double kBinaryScaleVoxels = 2.0;

/// True when `volume` holds exactly two values (its histogram has only its first and last bins):
/// a mask or a voxelised part.
bool is_binary(const volume::Volume& volume);

/// How the scale was chosen (reported in the JSON).
struct ScaleChoice {
  double scale = 0;           ///< the chosen sigma, world units
  double voxel = 0;           ///< the geometric mean spacing (sx sy sz)^(1/3), world units
  bool binary = false;        ///< the volume holds two values (kBinaryScaleVoxels)
  double noise = 0;           ///< voxel noise, value units: max(measured, quantisation)
  double measured_noise = 0;  ///< volume::estimate_noise's
  double quantisation = 0;    ///< step / sqrt(12) for integer voxel types (step 1), else 0
  double edge_step = 0;       ///< median over the vertices of |gradient| per voxel, value units
  double noise_level = 0;     ///< noise / edge_step
  /// The noise model of the per-vertex choice (curvature/adaptive_scale.h): `noise` (a binary
  /// volume's: kBinaryNoise times its contrast) on cells of sx sy sz.
  NoiseModel model;
};

/// The scale for the volume estimator on `mesh` (extracted from `volume` at `isovalue`):
/// sigma = voxel * clamp((noise_level / kAutoReferenceNoise)^kAutoScaleExponent, kAutoMinVoxels,
/// kAutoMaxVoxels), with noise_level the voxel noise (measured near the surface by
/// volume::estimate_noise, at least the quantisation noise of an integer voxel type) over the
/// step the field makes per voxel across the surface (the median world gradient times the voxel,
/// Gaussian at one voxel, over kEdgeSamples vertices: those whose positions hash lowest, a
/// choice that does not depend on the vertices' order, so a surface divided among processes
/// samples the same ones). On an anisotropic grid the voxel
/// is the geometric mean spacing: a Gaussian of world deviation sigma averages sigma^3 /
/// (sx sy sz) samples whatever their shape, so that is the length the noise scales with; no axis
/// gets under volume::kMinScaleVoxels of its spacing. A binary volume gets kBinaryScaleVoxels,
/// and its noise is its staircase's (kBinaryNoise times the contrast).
/// A smooth float field thus gets 0.8 voxel, noisy 8-bit data about 2. This is the first pilot
/// scale of the per-vertex choice (curvature/adaptive_scale.h). Deterministic. Throws what
/// volume::grid_frame throws.
/// With a `piece` (core/surface_piece.h), collective: `mesh` is the piece's, and every piece
/// gets the scale the single process gets on the whole surface (the noise blocks and the edge
/// samples chosen over every piece's own vertices, each measured by the piece that has it).
ScaleChoice auto_scale(const volume::Volume& volume, const Mesh& mesh, float isovalue,
                       const SurfacePiece* piece = nullptr);

/// The vertices the edge step is measured at (at most this many).
inline constexpr std::size_t kEdgeSamples = 1024;

}  // namespace isocurv::curvature
