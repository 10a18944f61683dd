// The device mesher against VTK's vtkFlyingEdges3D on the same dense volumes.
#include <gtest/gtest.h>

#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include "core/cl_device.h"
#include "mc/extract.h"
#include "mc/mesh_check.h"
#include "tests/mc/volumes.h"

using namespace isocurv;

namespace {

struct VtkSurface {
  std::size_t points = 0, triangles = 0;
  double area = 0;
};

// Flying edges on the volume's dense domain (unit spacing: compare shapes in index space).
VtkSurface flying_edges(const volume::Volume& v, float iso) {
  const openvdb::Coord d = v.domain.dim();
  vtkNew<vtkImageData> image;
  image->SetDimensions(d.x(), d.y(), d.z());
  const openvdb::Vec3d sp = v.spacing(), org = v.origin();
  image->SetSpacing(sp.x(), sp.y(), sp.z());
  image->SetOrigin(org.x(), org.y(), org.z());
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
  fe->ComputeScalarsOff();
  fe->Update();
  vtkNew<vtkMassProperties> mass;
  mass->SetInputConnection(fe->GetOutputPort());
  mass->Update();
  return {std::size_t(fe->GetOutput()->GetNumberOfPoints()), std::size_t(fe->GetOutput()->GetNumberOfPolys()),
          mass->GetSurfaceArea()};
}

void compare(const volume::Volume& v, float iso) {
  const Mesh m = mc::extract(v, iso, Device::default_device());
  const mc::MeshCheck c = mc::check_mesh(m);
  const VtkSurface ref = flying_edges(v, iso);
  ASSERT_GT(ref.triangles, 0u);
  EXPECT_NEAR(double(m.positions.size()), double(ref.points), 0.005 * ref.points);
  EXPECT_NEAR(double(m.triangles.size()), double(ref.triangles), 0.005 * ref.triangles);
  EXPECT_NEAR(c.area, ref.area, 0.001 * ref.area);
  std::printf("isocurv %zu vertices %zu triangles area %.3f | flying edges %zu %zu %.3f\n", m.positions.size(),
              m.triangles.size(), c.area, ref.points, ref.triangles, ref.area);
}

}  // namespace

TEST(VtkCompare, SphereTorusAndGyroidAgreeWithFlyingEdges) {
  compare(test::ball(64, 25.3, 31.6), 0.0f);
  compare(test::sampled([](double x, double y, double z) { return test::torus_density(x - 40, y - 40, z - 20, 24, 9); },
                        {80, 80, 40}, {0.5, 0.5, 0.7}, {3, -2, 1}),
          0.0f);
  compare(test::sampled([](double x, double y, double z) {
            const double s = 2 * M_PI / 17;
            return float(std::sin(s * x) * std::cos(s * y) + std::sin(s * y) * std::cos(s * z) + std::sin(s * z) * std::cos(s * x));
          }, {70, 60, 50}),
          0.2f);
}
