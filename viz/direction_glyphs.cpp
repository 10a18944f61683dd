#include "viz/direction_glyphs.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

namespace isocurv::viz {
namespace {

double length(const Vec3f& v) { return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]); }

bool usable(const Vec3f& v) {
  const double l = length(v);
  return std::isfinite(l) && l > 1e-12;
}

}  // namespace

vtkSmartPointer<vtkPolyData> direction_glyphs(const Mesh& mesh, const curvature::CurvatureField& field) {
  auto glyphs = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  glyphs->SetPoints(points);
  glyphs->SetLines(lines);
  glyphs->GetCellData()->SetScalars(colors);

  const std::size_t n = mesh.positions.size();
  const double edge = mean_edge_length(mesh);
  if (n == 0 || edge <= 0 || !std::isfinite(edge) || field.dir1.size() != n || field.dir2.size() != n) return glyphs;

  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Vec3f& p : mesh.positions)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], double(p[c])), hi[c] = std::max(hi[c], double(p[c]));
  const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double spacing = std::max(2.5 * edge, diagonal / 120.0);
  const double half = 0.35 * spacing;
  const double lift = 0.1 * edge;
  const bool have_normals = field.normals.size() == n;

  std::unordered_set<std::uint64_t> taken;
  auto cell_key = [&](const Vec3f& p) {
    std::uint64_t key = 0;  // at most ~121 cells per axis: 21 bits each is exact
    for (int c = 0; c < 3; ++c)
      key = (key << 21) | (static_cast<std::uint64_t>(std::floor((p[c] - lo[c]) / spacing)) & 0x1fffff);
    return key;
  };
  auto add_segment = [&](const double centre[3], const Vec3f& d, const unsigned char* rgb) {
    const double s = half / length(d);
    const vtkIdType a = points->InsertNextPoint(centre[0] - s * d[0], centre[1] - s * d[1], centre[2] - s * d[2]);
    const vtkIdType b = points->InsertNextPoint(centre[0] + s * d[0], centre[1] + s * d[1], centre[2] + s * d[2]);
    const vtkIdType ids[2] = {a, b};
    lines->InsertNextCell(2, ids);
    colors->InsertNextTypedTuple(rgb);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable(field.dir1[i]) || !usable(field.dir2[i])) continue;
    if (!taken.insert(cell_key(mesh.positions[i])).second) continue;
    double centre[3] = {mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]};
    if (have_normals && usable(field.normals[i])) {
      const double s = lift / length(field.normals[i]);
      for (int c = 0; c < 3; ++c) centre[c] += s * field.normals[i][c];
    }
    add_segment(centre, field.dir1[i], kDir1Color);
    add_segment(centre, field.dir2[i], kDir2Color);
  }
  return glyphs;
}

}  // namespace isocurv::viz
