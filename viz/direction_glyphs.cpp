#include "viz/direction_glyphs.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/vec3.h"
#include "io/vtk_errors.h"

namespace isocurv::viz {
namespace {

constexpr double kPixelsPerSite = 36;         // default density: one site per 36x36 pixels
constexpr double kMinSpacingEdges = 2.5;      // never denser than this many mean edges
constexpr double kLengthOfSpacing = 0.7;      // default segment length
constexpr double kLiftEdges = 0.15;           // off the surface along the normal
constexpr double kMaxCellsPerAxis = 1 << 20;  // the cell key holds 21 bits per axis

double length(const Vec3f& v) { return std::sqrt(vec3::wide_dot(v, v)); }

bool usable(const Vec3f& v) {
  const double l = length(v);
  return std::isfinite(l) && l > 1e-12;
}

double surface_area(const Mesh& mesh) {
  double area = 0;
  for (const Tri& t : mesh.triangles) {
    const std::array<double, 3> c = triangle_area_vector(mesh, t);
    area += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  return area;
}

}  // namespace

int default_glyph_count(int image_width, int image_height) {
  const double px = std::max(1.0, double(image_width) * double(image_height));
  return std::max(16, static_cast<int>(px / (kPixelsPerSite * kPixelsPerSite)));
}

vtkSmartPointer<vtkPolyData> direction_glyphs(const Mesh& mesh,
                                              const curvature::CurvatureField& field,
                                              const GlyphOptions& options) {
  auto glyphs = vtkSmartPointer<vtkPolyData>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  auto halo = vtkSmartPointer<vtkUnsignedCharArray>::New();
  auto which = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  halo->SetName("Halo");
  halo->SetNumberOfComponents(3);
  which->SetName("Direction");
  glyphs->SetPoints(points);
  glyphs->SetLines(lines);
  glyphs->GetCellData()->SetScalars(colors);
  glyphs->GetCellData()->AddArray(halo);
  glyphs->GetCellData()->AddArray(which);

  const std::size_t n = mesh.positions.size();
  const double edge = mean_edge_length(mesh);
  if (n == 0 || edge <= 0 || !std::isfinite(edge) || field.dir1.size() != n ||
      field.dir2.size() != n)
    return glyphs;

  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Vec3f& p : mesh.positions)
    for (int c = 0; c < 3; ++c)
      lo[c] = std::min(lo[c], double(p[c])), hi[c] = std::max(hi[c], double(p[c]));
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const int count = options.count > 0
                        ? options.count
                        : default_glyph_count(options.image_width, options.image_height);
  const double area = surface_area(mesh);
  double spacing = std::max(kMinSpacingEdges * edge, std::sqrt(area / count));
  spacing = std::max(spacing, extent / kMaxCellsPerAxis);
  const double half = 0.5 * (options.length > 0 ? options.length : kLengthOfSpacing * spacing);
  const double lift = kLiftEdges * edge;
  const bool have_normals = field.normals.size() == n;

  std::unordered_set<std::uint64_t> taken;
  auto cell_key = [&](const Vec3f& p) {
    std::uint64_t key = 0;  // at most 2^20 cells per axis: 21 bits each is exact
    for (int c = 0; c < 3; ++c)
      key = (key << 21) |
            (static_cast<std::uint64_t>(std::floor((p[c] - lo[c]) / spacing)) & 0x1fffff);
    return key;
  };
  auto add_segment = [&](const double centre[3], const Vec3f& d, const unsigned char* rgb,
                         const unsigned char* halo_rgb, unsigned char direction) {
    const double s = half / length(d);
    const vtkIdType a =
        points->InsertNextPoint(centre[0] - s * d[0], centre[1] - s * d[1], centre[2] - s * d[2]);
    const vtkIdType b =
        points->InsertNextPoint(centre[0] + s * d[0], centre[1] + s * d[1], centre[2] + s * d[2]);
    const vtkIdType ids[2] = {a, b};
    lines->InsertNextCell(2, ids);
    colors->InsertNextTypedTuple(rgb);
    halo->InsertNextTypedTuple(halo_rgb);
    which->InsertNextValue(direction);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!usable(field.dir1[i]) || !usable(field.dir2[i])) continue;
    if (!taken.insert(cell_key(mesh.positions[i])).second) continue;
    double centre[3] = {mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]};
    if (have_normals && usable(field.normals[i])) {
      const double s = lift / length(field.normals[i]);
      for (int c = 0; c < 3; ++c) centre[c] += s * field.normals[i][c];
    }
    add_segment(centre, field.dir1[i], kDir1Color, kDir1Halo, 1);
    add_segment(centre, field.dir2[i], kDir2Color, kDir2Halo, 2);
  }
  return glyphs;
}

void check_glyphs_path(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (lower.size() < 4 || lower.compare(lower.size() - 4, 4, ".vtp") != 0)
    throw Error(path, "direction glyphs are written as .vtp (line cells for ParaView)");
}

void write_glyphs(const std::string& path, vtkPolyData* glyphs) {
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    io::VtkErrorCapture errors(writer);
    writer->SetInputData(glyphs);
    writer->SetFileName(tmp.c_str());
    writer->SetDataModeToBinary();
    if (writer->Write() != 1 || errors.failed())
      throw Error(path, "cannot write the direction glyphs" +
                            (errors.failed() ? ": " + errors.message() : std::string()));
  });
}

}  // namespace isocurv::viz
