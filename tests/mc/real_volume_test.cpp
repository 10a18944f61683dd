// The mesher on real integer CT/MR volumes from ../shared/datasets (skipped when absent): voxels
// equal to the isovalue must leave no duplicate vertices, non-manifold edges or flipped triangles
// (where VTK's meshers leave duplicates or non-manifold edges), and between voxel values the
// surface agrees with vtkFlyingEdges3D.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <filesystem>

#include "core/cl_device.h"
#include "mc/extract.h"
#include "mc/mesh_check.h"
#include "tests/mc/flying_edges.h"
#include "mc/triangle_quality.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

struct RealCase {
  const char* file;
  float iso;  // a value many voxels hold exactly
};

const RealCase kCases[] = {{"lobster/lobster_301x324x56_uint8.raw", 40.0f},
                           {"headsq/headsq_64x64x93_int16le.raw", 500.0f},
                           {"nucleon/nucleon_41x41x41_uint8.raw", 80.0f},
                           {"headmr/HeadMRVolume.mhd", 80.0f}};

class MesherOnRealVolume : public ::testing::TestWithParam<RealCase> {};

void PrintTo(const RealCase& c, std::ostream* os) { *os << c.file; }

}  // namespace

TEST_P(MesherOnRealVolume, CleanAtVoxelValuesAndAgreesWithFlyingEdgesBetweenThem) {
  const std::string path = std::string(isocurv::test_paths::shared_datasets()) + "/" + GetParam().file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const volume::Volume v = volume::load(path);
  Device& dev = Device::default_device();

  const Mesh at = mc::extract(v, GetParam().iso, dev);
  const mc::MeshCheck c = mc::check_mesh(at);
  EXPECT_GT(c.triangles, 1000u);
  EXPECT_EQ(c.duplicate_vertices, 0u);
  EXPECT_EQ(c.unreferenced_vertices, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_EQ(c.non_manifold_edges, 0u);
  EXPECT_EQ(c.misoriented_edges, 0u);

  // Snapping leaves no slivers at the voxel value, and no more thin triangles than between values.
  const float between = GetParam().iso + 0.5f;  // no voxel holds it: both meshers see the same cases
  mc::Options plain;  // no snapping (as Flying Edges)
  plain.snap = 0;
  const double voxel = mc::voxel_face_area(v);
  const mc::TriangleQuality q = mc::triangle_quality(at, voxel);
  const mc::TriangleQuality qb = mc::triangle_quality(mc::extract(v, between, dev), voxel);
  const mc::TriangleQuality unsnapped = mc::triangle_quality(mc::extract(v, GetParam().iso, dev, plain), voxel);
  auto thin = [](const mc::TriangleQuality& t) { return double(t.thin) / double(t.triangles); };
  std::printf("smallest %.3g voxel^2; under 1e-4 voxel^2: %zu (unsnapped %zu); under 1 degree %.4f%% (unsnapped %.4f%%), at iso + 0.5 "
              "%.4f%%\n", q.min_area / voxel, q.small, unsnapped.small, 100 * thin(q), 100 * thin(unsnapped), 100 * thin(qb));
  EXPECT_LE(thin(q), thin(qb));
  EXPECT_LE(q.small * 10, unsnapped.small);  // at least 90% of the slivers gone
  // Where a merge is refused the vertices move out to the snap distance: no triangle is left at
  // the mesher's 1/1024-voxel nudge (about 1e-6 voxel^2).
  EXPECT_GE(q.min_area, 1e-6 * voxel);

  const Mesh m = mc::extract(v, between, dev, plain);
  const mc::MeshCheck cb = mc::check_mesh(m);
  const test::FlyingEdgesSurface fe = test::flying_edges(v, between);
  EXPECT_NEAR(double(m.positions.size()), double(fe.points), 0.005 * fe.points);
  EXPECT_NEAR(double(m.triangles.size()), double(fe.triangles), 0.005 * fe.triangles);
  EXPECT_NEAR(cb.area, fe.area, 0.001 * fe.area);
}

INSTANTIATE_TEST_SUITE_P(Shared, MesherOnRealVolume, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::to_string(info.index); });
