#pragma once
// VTK's vtkFlyingEdges3D on a volume's dense domain: the peer the mesher tests compare against.
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include "volume/volume.h"

namespace isocurv::test {

struct FlyingEdgesSurface {
  std::size_t points = 0, triangles = 0;
  double area = 0;
};

/// Counts and area of flying edges' surface of `v` at `iso` (same spacing and origin as v).
inline FlyingEdgesSurface flying_edges(const volume::Volume& v, float iso) {
  const openvdb::Coord d = v.domain.dim();
  vtkNew<vtkImageData> image;
  image->SetDimensions(d.x(), d.y(), d.z());
  const openvdb::Vec3d sp = v.spacing(), org = v.grid->transform().indexToWorld(v.domain.min());
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

}  // namespace isocurv::test
