// The volume estimator on a piece of a surface (core/surface_piece.h; distributed runs): a
// vertex's values depend on the volume around it and on nothing else in the mesh, so a sub-mesh
// gets the whole mesh's values to the bit on its vertices away from its cut, on the device as in
// the reference; and the whole-surface reductions (automatic scale, weak-gradient median) give
// each piece the single process's numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <random>

#include "core/cl_device.h"
#include "core/surface_piece.h"
#include "curvature/auto_scale.h"
#include "curvature/volume_estimate.h"
#include "mc/extract.h"
#include "volume/from_dense.h"

namespace isocurv::test {
namespace {

// A gyroid on a grid whose world coordinates are not whole numbers (spacing 2/47, origin -1),
// so that any dependence of the float arithmetic on which vertices share a call shows.
volume::Volume gyroid_volume() {
  const int n = 48;
  const double h = 2.0 / (n - 1), k = 2 * M_PI;
  std::vector<float> data(std::size_t(n) * n * n);
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double px = -1 + h * x, py = -1 + h * y, pz = -1 + h * z;
        data[i++] = float(std::sin(k * px) * std::cos(k * py) + std::sin(k * py) * std::cos(k * pz) +
                          std::sin(k * pz) * std::cos(k * px));
      }
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
  xform->postTranslate(openvdb::Vec3d(-1, -1, -1));
  volume::DenseSource src;
  src.path = "gyroid";
  src.format = "generated";
  src.voxel_type = "float";
  src.inside = volume::Inside::Above;
  return volume::from_dense(data.data(), {n, n, n}, xform, src);
}

// The triangles whose vertices all lie above z = `cut` (world), re-indexed; `from` maps each
// sub-mesh vertex to the mesh's.
Mesh above(const Mesh& m, float cut, std::vector<std::uint32_t>& from) {
  std::map<std::uint32_t, std::uint32_t> index;
  Mesh sub;
  from.clear();
  for (const Tri& t : m.triangles) {
    if (m.positions[t[0]][2] <= cut || m.positions[t[1]][2] <= cut || m.positions[t[2]][2] <= cut) continue;
    Tri s;
    for (int c = 0; c < 3; ++c) {
      auto [it, fresh] = index.emplace(t[c], std::uint32_t(from.size()));
      if (fresh) {
        from.push_back(t[c]);
        sub.positions.push_back(m.positions[t[c]]);
      }
      s[c] = it->second;
    }
    sub.triangles.push_back(s);
  }
  return sub;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(VolumeEstimatorPiece, SubMeshGetsTheWholeMeshValuesToTheBit) {
  const volume::Volume v = gyroid_volume();
  Device& device = Device::default_device();
  const Mesh m = mc::extract(v, 0.0f, device, {});
  ASSERT_GT(m.positions.size(), 1000u);
  const double sigma = 1.5 * 2.0 / 47;
  std::vector<std::uint32_t> from;
  const Mesh sub = above(m, -0.3f, from);
  ASSERT_GT(sub.positions.size(), 100u);
  for (const bool on_device : {true, false}) {
    auto run = [&](const Mesh& mesh) {
      curvature::VolumeOptions o = curvature::fixed_scale(sigma, 1.0f);
      o.point = curvature::VolumePoint::vertex;
      return on_device ? curvature::volume_estimate(mesh, v, 0.0f, o, device)
                       : curvature::volume_estimate_reference(mesh, v, 0.0f, o);
    };
    const curvature::CurvatureField whole = run(m), part = run(sub);
    std::size_t compared = 0, differ = 0;
    for (std::size_t i = 0; i < sub.positions.size(); ++i) {
      if (sub.positions[i][2] < 0.2f) continue;  // the cut's neighbourhood: the box test sees it
      const std::uint32_t w = from[i];
      if (whole.unreliable[w] || part.unreliable[i]) continue;  // the weak median is each mesh's own
      ++compared;
      bool same = same_bits(whole.k1[w], part.k1[i]) && same_bits(whole.k2[w], part.k2[i]) &&
                  same_bits(whole.H[w], part.H[i]) && same_bits(whole.K[w], part.K[i]);
      for (int a = 0; a < 3; ++a) same = same && same_bits(whole.normals[w][a], part.normals[i][a]);
      differ += !same;
    }
    EXPECT_GT(compared, 100u);
    EXPECT_EQ(differ, 0u) << (on_device ? "device" : "reference") << ": " << differ << " of " << compared
                          << " vertices differ from the whole mesh's";
  }
}

// A world of one piece that owns the vertices `owned` says: the reductions return what they are
// given, so the piece's paths (histogram selection, pooled samples) run against the plain ones.
class OnePiece final : public SurfacePiece {
 public:
  std::vector<double> all(const std::vector<double>& mine) const override { return mine; }
  std::vector<std::int64_t> sum(const std::vector<std::int64_t>& mine) const override { return mine; }
  bool holds_cells_at(int) const override { return true; }
};

TEST(SurfacePiece, KthSmallestByHistogramsIsExact) {
  std::mt19937 rng(7);
  std::lognormal_distribution<float> spread(0.0f, 3.0f);
  std::vector<float> values(5000);
  for (float& v : values) v = spread(rng);
  values[17] = std::numeric_limits<float>::infinity();
  values[18] = values[19];  // a tie
  std::vector<float> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  const OnePiece piece;
  for (std::uint64_t k : {0ul, 1ul, 2499ul, 2500ul, 4998ul, 4999ul}) {
    EXPECT_EQ(kth_smallest_positive(&piece, values, k), sorted[k]) << k;
    EXPECT_EQ(kth_smallest_positive(nullptr, values, k), sorted[k]) << k;
  }
  EXPECT_THROW(kth_smallest_positive(&piece, values, 5000), std::out_of_range);
}

// The automatic scale samples vertices by a hash of their positions, not by their order, and
// pools what the pieces measure: reordering the vertices, or going through a piece's path,
// changes nothing.
TEST(SurfacePiece, AutoScaleDoesNotDependOnVertexOrder) {
  volume::Volume v = gyroid_volume();
  Device& device = Device::default_device();
  const Mesh m = mc::extract(v, 0.0f, device, {});
  Mesh shuffled = m;
  std::vector<std::uint32_t> order(m.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  for (std::size_t i = 0; i < order.size(); ++i) shuffled.positions[i] = m.positions[order[i]];
  std::vector<std::uint32_t> where(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) where[order[i]] = std::uint32_t(i);
  for (Tri& t : shuffled.triangles)
    for (auto& c : t) c = where[c];
  OnePiece piece;
  piece.owned_vertices.assign(m.positions.size(), 1);
  piece.owned_triangles.assign(m.triangles.size(), 1);
  const curvature::ScaleChoice a = curvature::auto_scale(v, m, 0.0f);
  const curvature::ScaleChoice b = curvature::auto_scale(v, shuffled, 0.0f);
  const curvature::ScaleChoice c = curvature::auto_scale(v, m, 0.0f, &piece);
  EXPECT_GT(a.edge_step, 0);
  EXPECT_GT(a.measured_noise, 0);
  for (const curvature::ScaleChoice* o : {&b, &c}) {
    EXPECT_EQ(o->scale, a.scale);
    EXPECT_EQ(o->edge_step, a.edge_step);
    EXPECT_EQ(o->measured_noise, a.measured_noise);
  }
}

}  // namespace
}  // namespace isocurv::test
