// The mesher on real integer CT/MR volumes from ../shared/datasets (skipped when absent): voxels
// equal to the isovalue must leave no duplicate vertices, non-manifold edges or flipped triangles
// (where VTK's meshers leave duplicates or non-manifold edges), and between voxel values the
// surface agrees with vtkFlyingEdges3D.
#include <gtest/gtest.h>

#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <filesystem>

#include "core/cl_device.h"
#include "mc/extract.h"
#include "mc/mesh_check.h"
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

struct FlyingEdges {
  std::size_t points, triangles;
  double area;
};

FlyingEdges flying_edges(const volume::Volume& v, float iso) {
  const openvdb::Coord d = v.domain.dim();
  vtkNew<vtkImageData> image;
  image->SetDimensions(d.x(), d.y(), d.z());
  const openvdb::Vec3d sp = v.spacing();
  image->SetSpacing(sp.x(), sp.y(), sp.z());
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(vtkIdType(d.x()) * d.y() * d.z());
  auto acc = v.grid->getConstAccessor();
  vtkIdType i = 0;
  for (int z = 0; z < d.z(); ++z)
    for (int y = 0; y < d.y(); ++y)
      for (int x = 0; x < d.x(); ++x) values->SetValue(i++, acc.getValue(v.domain.min() + openvdb::Coord(x, y, z)));
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(image);
  fe->SetValue(0, iso);
  fe->ComputeNormalsOff();
  fe->Update();
  vtkNew<vtkMassProperties> mass;
  mass->SetInputConnection(fe->GetOutputPort());
  mass->Update();
  return {std::size_t(fe->GetOutput()->GetNumberOfPoints()), std::size_t(fe->GetOutput()->GetNumberOfPolys()),
          mass->GetSurfaceArea()};
}

}  // namespace

TEST_P(MesherOnRealVolume, CleanAtVoxelValuesAndAgreesWithFlyingEdgesBetweenThem) {
  const std::string path = std::string(ISOCURV_SHARED_DATASETS) + "/" + GetParam().file;
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

  const float between = GetParam().iso + 0.5f;  // no voxel holds it: both meshers see the same cases
  const Mesh m = mc::extract(v, between, dev);
  const mc::MeshCheck cb = mc::check_mesh(m);
  const FlyingEdges fe = flying_edges(v, between);
  EXPECT_NEAR(double(m.positions.size()), double(fe.points), 0.005 * fe.points);
  EXPECT_NEAR(double(m.triangles.size()), double(fe.triangles), 0.005 * fe.triangles);
  EXPECT_NEAR(cb.area, fe.area, 0.001 * fe.area);
}

INSTANTIATE_TEST_SUITE_P(Shared, MesherOnRealVolume, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::to_string(info.index); });
