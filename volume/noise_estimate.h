#pragma once
// A robust estimate of a volume's voxel noise near a surface (for choosing a smoothing scale).
// Tested in tests/volume/test_noise_estimate.cpp.
#include <cstddef>

#include "core/mesh.h"
#include "core/surface_piece.h"
#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// Voxels within this many voxels (along each axis) of an isovalue crossing are left out of the
/// noise estimate: there the surface's own profile, not noise, dominates the residual.
inline constexpr int kNoiseEdgeDistance = 3;

/// The noise estimate and what it rests on.
struct NoiseEstimate {
  double sigma = 0;        ///< standard deviation of the voxel noise, in the volume's value units
  std::size_t voxels = 0;  ///< voxels it was measured on
};

/// The variance of the residual below for white noise of unit variance: 18^2 for the centre,
/// 16 for each of the 6 face neighbours, 1 for each of the 6 at distance 2.
inline constexpr double kFourthDifferenceVariance = 18.0 * 18.0 + 6 * 16 + 6;

/// Noise of `grid` in the 8^3 blocks holding the points (up to `max_blocks` of them, taken
/// evenly): the residual r = sum over the three axes of the fourth difference
/// v(-2) - 4 v(-1) + 6 v - 4 v(+1) + v(+2) of every voxel there that is not within
/// kNoiseEdgeDistance voxels of an `isovalue` crossing along an axis (nor, for a clamped dense
/// frame, of the domain's border), and sigma = 1.4826 MAD(r) / sqrt(kFourthDifferenceVariance)
/// (MAD, the median absolute deviation from the median, ignores the few voxels structure still
/// dominates). Fourth differences vanish on cubics, so a smooth field's own shape is not taken
/// for noise (a six-neighbour residual read a 128^3 torus distance field as noise 0.0038 of its
/// step). sigma = 0 when no voxel qualifies. Deterministic.
/// With a `piece` (core/surface_piece.h), collective: `points` are the piece's own, the blocks
/// are chosen from every piece's together, each is measured by the piece that holds its cells,
/// and the residuals are pooled, so every piece gets the single process's estimate.
NoiseEstimate estimate_noise(const openvdb::FloatGrid& grid, const GridFrame& frame,
                             const Positions& points, float isovalue, std::size_t max_blocks = 256,
                             const SurfacePiece* piece = nullptr);

}  // namespace isocurv::volume
