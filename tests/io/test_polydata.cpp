// io::to_polydata / io::from_polydata.
#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "core/error.h"
#include "io/polydata.h"
#include "test_meshes.h"

using namespace isocurv;

TEST(IoPolydata, CarriesGeometryAndNamedArrays) {
  const Mesh mesh = test::grid_mesh();
  const auto field = test::random_field(mesh.vertex_count());
  auto poly = io::to_polydata(mesh, &field);
  EXPECT_EQ(poly->GetNumberOfPoints(), static_cast<vtkIdType>(mesh.vertex_count()));
  EXPECT_EQ(poly->GetNumberOfPolys(), static_cast<vtkIdType>(mesh.triangle_count()));
  ASSERT_NE(poly->GetPointData()->GetNormals(), nullptr);
  EXPECT_STREQ(poly->GetPointData()->GetNormals()->GetName(), "Normals");
  ASSERT_NE(poly->GetPointData()->GetArray("dcurv"), nullptr);
  EXPECT_EQ(poly->GetPointData()->GetArray("dcurv")->GetNumberOfComponents(), 4);
  EXPECT_EQ(poly->GetPointData()->GetArray("H")->GetComponent(4, 0), field.H[4]);

  const io::MeshFile back = io::from_polydata(poly, "memory");
  EXPECT_TRUE(test::same_bits(back.mesh.positions, mesh.positions));
  EXPECT_TRUE(test::same_bits(back.mesh.triangles, mesh.triangles));
  ASSERT_TRUE(back.field.has_value());
  EXPECT_TRUE(test::same_bits(back.field->dcurv, field.dcurv));
  EXPECT_TRUE(test::same_bits(back.field->boundary, field.boundary));
}

TEST(IoPolydata, ConvertsOtherTypesAndTriangulatesPolygons) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  for (double p : {0.0, 1.0, 2.0, 3.0, 4.0}) points->InsertNextPoint(p, p * p, 0.5);
  poly->SetPoints(points);
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType pentagon[] = {0, 1, 2, 3, 4};
  polys->InsertNextCell(5, pentagon);
  poly->SetPolys(polys);
  auto k = vtkSmartPointer<vtkDoubleArray>::New();
  k->SetName("K");
  for (int i = 0; i < 5; ++i) k->InsertNextValue(0.25 * i);
  poly->GetPointData()->AddArray(k);

  const io::MeshFile back = io::from_polydata(poly, "memory");
  EXPECT_EQ(back.mesh.triangle_count(), 3u);
  EXPECT_EQ(back.mesh.positions[3], (Vec3f{3.f, 9.f, 0.5f}));
  ASSERT_TRUE(back.field.has_value());
  EXPECT_EQ(back.field->K, (std::vector<float>{0, 0.25f, 0.5f, 0.75f, 1.f}));
}

TEST(IoPolydata, WrongComponentCountIsAnError) {
  const Mesh mesh = test::grid_mesh();
  auto poly = io::to_polydata(mesh);
  auto bad = vtkSmartPointer<vtkDoubleArray>::New();
  bad->SetName("dir1");
  bad->SetNumberOfComponents(2);
  bad->SetNumberOfTuples(poly->GetNumberOfPoints());
  bad->Fill(0);
  poly->GetPointData()->AddArray(bad);
  EXPECT_THROW(io::from_polydata(poly, "memory"), Error);
}
