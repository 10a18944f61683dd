#pragma once
// The surface samples of a vertex's ball: the vertices within Euclidean
// distance r of it that are reached along mesh edges without leaving the ball
// (so other sheets passing within r through the air are not counted), each
// weighted by its Area, and the sums the features take of them.
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "features/detail/mesh_graph.h"

namespace isocurv::features::detail {

/// Area-weighted sums over the ball's samples q_i (not counting the centre p
/// for the direction terms, which are undefined there).
struct BallSums {
  double area = 0; ///< sum A_i, p included
  double bending =
      0; ///< sum A_i |n - n_i|^2 / |p - q_i|^2          (LBE numerator)
  double horizon =
      0; ///< sum A_i (1 - (q_i - p).n / |q_i - p|) / 2  (NSV numerator)
  double horizon_area =
      0; ///< sum A_i over the samples with a direction (p excluded)
  double height =
      0; ///< sum A_i (q_i - p).n                        (mean height)
  bool touches_boundary = false; ///< an open-boundary vertex lies in the ball
};

/// Walks the ball of radius r around vertex v. `stamp` and `queue` are scratch
/// (stamp sized to the vertex count, all entries different from `mark`); the
/// caller changes `mark` per call.
BallSums ball_sums(const Mesh &mesh, const MeshGraph &graph,
                   const std::vector<Vec3f> &normals,
                   const std::vector<float> &area, std::uint32_t v, double r,
                   std::vector<std::uint32_t> &stamp, std::uint32_t mark,
                   std::vector<std::uint32_t> &queue);

} // namespace isocurv::features::detail
