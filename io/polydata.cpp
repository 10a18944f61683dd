#include "io/polydata.h"

#include <cstring>
#include <limits>
#include <type_traits>

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include "core/error.h"
#include "io/field_arrays.h"

namespace isocurv::io {
namespace {

template <class Element>
using ScalarOf = std::conditional_t<std::is_same_v<Element, std::uint8_t>, std::uint8_t, float>;

template <class Element, class Alloc>
vtkSmartPointer<vtkDataArray> make_array(const char* name, const std::vector<Element, Alloc>& values) {
  using Scalar = ScalarOf<Element>;
  using VtkArray = std::conditional_t<std::is_same_v<Scalar, float>, vtkFloatArray, vtkUnsignedCharArray>;
  constexpr int nc = components_of<Element>();
  static_assert(sizeof(Element) == nc * sizeof(Scalar), "field elements must be packed scalars");
  auto array = vtkSmartPointer<VtkArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(nc);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  if (!values.empty()) std::memcpy(array->GetPointer(0), values.data(), values.size() * sizeof(Element));
  return array;
}

template <class IndexArray>
vtkSmartPointer<vtkCellArray> make_triangles(const Triangles& triangles) {
  using Value = typename IndexArray::ValueType;
  auto offsets = vtkSmartPointer<IndexArray>::New();
  auto connectivity = vtkSmartPointer<IndexArray>::New();
  const vtkIdType n = static_cast<vtkIdType>(triangles.size());
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(3 * n);
  for (vtkIdType i = 0; i <= n; ++i) offsets->SetValue(i, static_cast<Value>(3 * i));
  for (vtkIdType i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      connectivity->SetValue(3 * i + c, static_cast<Value>(triangles[static_cast<std::size_t>(i)][c]));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

template <class Element>
void read_array(vtkDataArray* array, const char* name, vtkIdType n, std::vector<Element>& out,
                const std::string& source) {
  using Scalar = ScalarOf<Element>;
  constexpr int nc = components_of<Element>();
  if (array->GetNumberOfComponents() != nc)
    throw Error(source, std::string("array '") + name + "' has " +
                            std::to_string(array->GetNumberOfComponents()) + " components, expected " +
                            std::to_string(nc));
  if (array->GetNumberOfTuples() != n)
    throw Error(source, std::string("array '") + name + "' has " +
                            std::to_string(array->GetNumberOfTuples()) + " values for " +
                            std::to_string(n) + " points");
  out.resize(static_cast<std::size_t>(n));
  const bool same_type = std::is_same_v<Scalar, float> ? array->GetDataType() == VTK_FLOAT
                                                         : array->GetDataType() == VTK_UNSIGNED_CHAR;
  if (same_type) {
    if (n > 0) std::memcpy(out.data(), array->GetVoidPointer(0), out.size() * sizeof(Element));
    return;
  }
  auto* dst = reinterpret_cast<Scalar*>(out.data());
  for (vtkIdType i = 0; i < n; ++i)
    for (int c = 0; c < nc; ++c) dst[i * nc + c] = static_cast<Scalar>(array->GetComponent(i, c));
}

}  // namespace

vtkSmartPointer<vtkPolyData> to_polydata(const Mesh& mesh, const curvature::CurvatureField* field,
                                         const Metadata* context, const CellArrays* cells) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(make_array("Points", mesh.positions));
  poly->SetPoints(points);
  const bool small = 3 * mesh.triangles.size() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  poly->SetPolys(small ? make_triangles<vtkTypeInt32Array>(mesh.triangles)
                       : make_triangles<vtkTypeInt64Array>(mesh.triangles));
  if (field) {
    vtkPointData* pd = poly->GetPointData();
    for_each_array(*field, [&](const char* name, const auto& values) {
      if (values.empty()) return;
      auto array = make_array(name, values);
      if (std::strcmp(name, "Normals") == 0) pd->SetNormals(array);
      else pd->AddArray(array);
    });
  }
  if (cells)
    for (const CellArray& c : *cells) {
      auto array = vtkSmartPointer<vtkTypeInt32Array>::New();
      array->SetName(c.name.c_str());
      array->SetNumberOfTuples(static_cast<vtkIdType>(c.values.size()));
      std::copy(c.values.begin(), c.values.end(), array->GetPointer(0));
      poly->GetCellData()->AddArray(array);
    }
  auto add_text = [&](const std::string& key, const std::string& value) {
    if (poly->GetFieldData()->GetAbstractArray(key.c_str())) return;  // the field's wins
    auto text = vtkSmartPointer<vtkStringArray>::New();
    text->SetName(key.c_str());
    text->InsertNextValue(value);
    poly->GetFieldData()->AddArray(text);
  };
  if (field)
    for (const auto& [key, value] : field->metadata) add_text(key, value);  // how it was made
  if (context)
    for (const auto& [key, value] : *context) add_text(key, value);  // where it came from
  return poly;
}

MeshFile from_polydata(vtkPolyData* poly, const std::string& source) {
  MeshFile out;
  const vtkIdType n = poly->GetNumberOfPoints();
  if (static_cast<unsigned long long>(n) > std::numeric_limits<std::uint32_t>::max())
    throw Error(source, "too many points for 32-bit indices");
  out.mesh.positions.resize(static_cast<std::size_t>(n));
  if (n > 0) {
    vtkDataArray* pts = poly->GetPoints()->GetData();
    if (pts->GetDataType() == VTK_FLOAT && pts->GetNumberOfComponents() == 3) {
      std::memcpy(out.mesh.positions.data(), pts->GetVoidPointer(0), out.mesh.positions.size() * sizeof(Vec3f));
    } else {
      for (vtkIdType i = 0; i < n; ++i) {
        double p[3];
        pts->GetTuple(i, p);
        out.mesh.positions[static_cast<std::size_t>(i)] = {static_cast<float>(p[0]), static_cast<float>(p[1]),
                                                           static_cast<float>(p[2])};
      }
    }
  }

  auto idx = [&](vtkIdType v) {
    if (v < 0 || v >= n) throw Error(source, "cell refers to point " + std::to_string(v) + " of " + std::to_string(n));
    return static_cast<std::uint32_t>(v);
  };
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  // The cell each triangle came from (cells are numbered verts, lines, polys, strips).
  std::vector<vtkIdType> cell_of;
  vtkIdType cell = poly->GetNumberOfVerts() + poly->GetNumberOfLines();
  auto polys = vtk::TakeSmartPointer(poly->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell(), ++cell) {
    polys->GetCurrentCell(count, ids);
    for (vtkIdType k = 2; k < count; ++k) {
      out.mesh.triangles.push_back({idx(ids[0]), idx(ids[k - 1]), idx(ids[k])});
      cell_of.push_back(cell);
    }
  }
  auto strips = vtk::TakeSmartPointer(poly->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell(), ++cell) {
    strips->GetCurrentCell(count, ids);
    for (vtkIdType k = 2; k < count; ++k) {
      if (k % 2 == 0) out.mesh.triangles.push_back({idx(ids[k - 2]), idx(ids[k - 1]), idx(ids[k])});
      else out.mesh.triangles.push_back({idx(ids[k - 1]), idx(ids[k - 2]), idx(ids[k])});
      cell_of.push_back(cell);
    }
  }
  // One-component integer cell arrays (the Label of label maps), one value per triangle.
  if (vtkCellData* cd = poly->GetCellData())
    for (int i = 0; i < cd->GetNumberOfArrays(); ++i) {
      vtkDataArray* array = cd->GetArray(i);
      if (!array || !array->GetName() || array->GetNumberOfComponents() != 1 ||
          array->GetDataType() == VTK_FLOAT || array->GetDataType() == VTK_DOUBLE)
        continue;
      if (array->GetNumberOfTuples() != cell)
        throw Error(source, std::string("cell array '") + array->GetName() + "' has " +
                                std::to_string(array->GetNumberOfTuples()) + " values for " +
                                std::to_string(cell) + " cells");
      CellArray c{array->GetName(), std::vector<std::int32_t>(cell_of.size())};
      for (std::size_t t = 0; t < cell_of.size(); ++t)
        c.values[t] = static_cast<std::int32_t>(array->GetComponent(cell_of[t], 0));
      out.cells.push_back(std::move(c));
    }

  vtkPointData* pd = poly->GetPointData();
  curvature::CurvatureField field;
  bool any = false;
  for_each_array(field, [&](const char* name, auto& values) {
    vtkDataArray* array = pd->GetArray(name);
    if (!array && std::strcmp(name, "Normals") == 0) array = pd->GetNormals();
    if (!array) return;
    read_array(array, name, n, values, source);
    any = true;
  });
  // Other one-component float arrays (features/ writes LBE, H_ii, ...) come back as extras.
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i) {
    vtkDataArray* array = pd->GetArray(i);
    const char* name = array ? array->GetName() : nullptr;
    if (!name || is_curvature_array(name) || array->GetNumberOfComponents() != 1 ||
        array->GetDataType() != VTK_FLOAT)
      continue;
    curvature::CurvatureField::Named e{name, {}};
    read_array(array, name, n, e.values, source);
    field.extra.push_back(std::move(e));
    any = true;
  }
  // The field data's text: how the curvature was made, where the surface came from.
  if (vtkFieldData* fd = poly->GetFieldData())
    for (int i = 0; i < fd->GetNumberOfArrays() && out.metadata.size() < 64; ++i) {
      auto* text = vtkStringArray::SafeDownCast(fd->GetAbstractArray(i));
      if (!text || !text->GetName() || text->GetNumberOfValues() != 1) continue;
      const std::string value = text->GetValue(0);
      if (value.size() > 1024) continue;
      out.metadata.emplace_back(text->GetName(), value);
    }
  if (any) {
    field.metadata = out.metadata;
    out.field = std::move(field);
  }
  return out;
}

}  // namespace isocurv::io
