#include "lines/visibility.h"

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include <cmath>

#include "core/mesh_measures.h"

namespace isocurv::lines {

struct VisibilityTester::Impl {
  Mesh mesh;
  vtkSmartPointer<vtkPolyData> poly = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkStaticCellLocator> locator =
      vtkSmartPointer<vtkStaticCellLocator>::New();
  vtkSmartPointer<vtkGenericCell> cell = vtkSmartPointer<vtkGenericCell>::New();
  double edge = 0;     // mean edge length
  double diagonal = 0; // of the mesh's box

  /// True when the ray from `start` to the eye (for an orthographic camera: along the view
  /// vector `v` out of the box) meets no triangle.
  bool clear_ray(const double start[3], const std::array<double, 3> &v,
                 const Camera &camera) const;
};

VisibilityTester::VisibilityTester(const Mesh &mesh)
    : impl_(std::make_unique<Impl>()) {
  Impl &m = *impl_;
  m.mesh.positions = mesh.positions;
  m.mesh.triangles = mesh.triangles;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(vtkIdType(mesh.positions.size()));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    points->SetPoint(vtkIdType(i), mesh.positions[i][0], mesh.positions[i][1],
                     mesh.positions[i][2]);
  vtkNew<vtkCellArray> tris;
  double edge_sum = 0;
  for (const Tri &t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    tris->InsertNextCell(3, ids);
    for (int j = 0; j < 3; ++j) {
      const Vec3f &a = mesh.positions[t[j]],
                  &b = mesh.positions[t[(j + 1) % 3]];
      edge_sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) +
                            double(a[1] - b[1]) * (a[1] - b[1]) +
                            double(a[2] - b[2]) * (a[2] - b[2]));
    }
  }
  m.edge = mesh.triangles.empty()
               ? 0
               : edge_sum / (3.0 * double(mesh.triangles.size()));
  m.poly->SetPoints(points);
  m.poly->SetPolys(tris);
  double b[6];
  m.poly->GetBounds(b);
  m.diagonal =
      std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
                (b[5] - b[4]) * (b[5] - b[4]));
  m.locator->SetDataSet(m.poly);
  m.locator->BuildLocator();
}

VisibilityTester::~VisibilityTester() = default;

bool VisibilityTester::Impl::clear_ray(const double start[3], const std::array<double, 3> &v,
                                       const Camera &camera) const {
  double end[3];
  const double far = camera.ortho ? 2 * diagonal + 1 : 0;
  for (int c = 0; c < 3; ++c)
    end[c] = camera.ortho ? start[c] + far * v[c] : camera.position[c];
  double t = 0, x[3], pcoords[3];
  int sub = 0;
  vtkIdType hit = -1;
  return locator->IntersectWithLine(start, end, 0.0, t, x, pcoords, sub, hit, cell) == 0;
}

namespace {

/// The midpoint of segment `s`.
Vec3f midpoint(const Segment &s) {
  return {0.5f * (s.a[0] + s.b[0]), 0.5f * (s.a[1] + s.b[1]), 0.5f * (s.a[2] + s.b[2])};
}

/// The unit normal of face `face` of `mesh`, or zero.
std::array<double, 3> face_normal(const Mesh &mesh, std::uint32_t face) {
  std::array<double, 3> n{0, 0, 0};
  if (face >= mesh.triangles.size())
    return n;
  const std::array<double, 3> a = triangle_area_vector(mesh, mesh.triangles[face]);
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (len > 0)
    for (int c = 0; c < 3; ++c)
      n[c] = a[c] / len;
  return n;
}

} // namespace

bool VisibilityTester::visible(const Vec3f &p, std::uint32_t face,
                               const Camera &camera) const {
  const Impl &m = *impl_;
  if (m.mesh.triangles.empty())
    return true;
  const std::array<double, 3> q{p[0], p[1], p[2]};
  const std::array<double, 3> v = camera.view_vector(q);
  const std::array<double, 3> n = face_normal(m.mesh, face);
  double start[3];
  for (int c = 0; c < 3; ++c)
    start[c] = q[c] + m.edge * v[c] + 0.05 * m.edge * n[c];
  return m.clear_ray(start, v, camera);
}

bool VisibilityTester::visible_contour(const Segment &s,
                                       const Camera &camera) const {
  const Impl &m = *impl_;
  const Vec3f mid = midpoint(s);
  if (visible(mid, s.face, camera))
    return true;
  // The side of the line in the image: across the segment and the view.
  const std::array<double, 3> q{mid[0], mid[1], mid[2]};
  const std::array<double, 3> v = camera.view_vector(q);
  const double d[3] = {double(s.b[0]) - s.a[0], double(s.b[1]) - s.a[1],
                       double(s.b[2]) - s.a[2]};
  double side[3] = {d[1] * v[2] - d[2] * v[1], d[2] * v[0] - d[0] * v[2],
                    d[0] * v[1] - d[1] * v[0]};
  const double len = std::sqrt(side[0] * side[0] + side[1] * side[1] + side[2] * side[2]);
  if (!(len > 0))
    return false;
  for (double sign : {1.0, -1.0}) {
    double start[3];
    for (int c = 0; c < 3; ++c)
      start[c] = q[c] + m.edge * v[c] + sign * kContourSideEdges * m.edge * side[c] / len;
    if (m.clear_ray(start, v, camera))
      return true;
  }
  return false;
}

std::vector<bool>
VisibilityTester::visible_segments(const Segments &segments,
                                   const Camera &camera) const {
  std::vector<bool> out(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment &s = segments[i];
    out[i] = s.type == LineType::contour ? visible_contour(s, camera)
                                         : visible(midpoint(s), s.face, camera);
  }
  return out;
}

} // namespace isocurv::lines
