#include "lines/line_files.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkErrorCode.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/vec3.h"
#include "io/vtk_errors.h"

namespace isocurv::lines {
namespace {

using V3 = std::array<double, 3>;
using vec3::sub;
using vec3::dot;
using vec3::cross;
using vec3::normalized;

struct Style {
  const char *id;
  const char *colour;
  double width;
};
// Indexed by LineType.
constexpr Style kStyles[kLineTypeCount] = {{"contours", "#000000", 2.0},
                                           {"suggestive", "#404040", 1.5},
                                           {"ridges", "#c0392b", 1.2},
                                           {"valleys", "#1f5fbf", 1.2}};

} // namespace

vtkSmartPointer<vtkPolyData> to_polydata(const Polylines &lines) {
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(vtkIdType(lines.points.size()));
  for (std::size_t i = 0; i < lines.points.size(); ++i)
    points->SetPoint(vtkIdType(i), lines.points[i][0], lines.points[i][1],
                     lines.points[i][2]);
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkUnsignedCharArray> type;
  type->SetName("LineType");
  vtkNew<vtkFloatArray> strength;
  strength->SetName("Strength");
  for (std::size_t l = 0; l < lines.line_count(); ++l) {
    cells->InsertNextCell(vtkIdType(lines.offsets[l + 1] - lines.offsets[l]));
    for (std::uint32_t j = lines.offsets[l]; j < lines.offsets[l + 1]; ++j)
      cells->InsertCellPoint(j);
    type->InsertNextValue(static_cast<unsigned char>(lines.type[l]));
    strength->InsertNextValue(lines.strength[l]);
  }
  poly->SetPoints(points);
  poly->SetLines(cells);
  poly->GetCellData()->AddArray(type);
  poly->GetCellData()->AddArray(strength);
  return poly;
}

void write_vtp(const std::string &path, const Polylines &lines) {
  const auto poly = to_polydata(lines);
  write_atomically(path, [&](const std::string &tmp) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    io::VtkErrorCapture errors(writer);
    writer->SetInputData(poly);
    writer->SetFileName(tmp.c_str());
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToZLib();
    writer->SetHeaderTypeToUInt64();
    const int ok = writer->Write();
    if (!ok || errors.failed() ||
        writer->GetErrorCode() != vtkErrorCode::NoError)
      throw Error(path, errors.failed() ? errors.message()
                                        : vtkErrorCode::GetStringFromErrorCode(
                                              writer->GetErrorCode()));
  });
}

std::array<double, 3> project(const Camera &camera,
                              const std::array<double, 3> &p, int width,
                              int height) {
  const V3 dop = normalized(
      sub(camera.focal_point, camera.position)); // direction of projection
  const V3 right = normalized(cross(dop, camera.view_up));
  const V3 up = cross(right, dop);
  const double aspect = double(width) / double(height);
  double x, y, depth;
  if (camera.ortho) {
    const V3 r = sub(p, camera.focal_point);
    depth = dot(sub(p, camera.position), dop);
    x = dot(r, right) / (camera.parallel_scale * aspect);
    y = dot(r, up) / camera.parallel_scale;
  } else {
    const V3 r = sub(p, camera.position);
    depth = dot(r, dop);
    const double h =
        std::tan(camera.view_angle_deg * 3.14159265358979323846 / 360) * depth;
    x = dot(r, right) / (h * aspect);
    y = dot(r, up) / h;
  }
  return {(x + 1) * 0.5 * width, (1 - y) * 0.5 * height, depth};
}

void write_svg(const std::string &path, const Polylines &lines,
               const Camera &camera, int width, int height) {
  if (width < 16 || height < 16 || width > 16384 || height > 16384)
    throw Error(path, "drawing size " + std::to_string(width) + "x" +
                          std::to_string(height) +
                          " out of range (16 to 16384 pixels a side)");
  write_atomically(path, [&](const std::string &tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out)
      throw Error(path, "cannot write the SVG file");
    char buf[96];
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
        << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " "
        << height << "\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (int t = 0; t < kLineTypeCount; ++t) {
      const Style &s = kStyles[t];
      out << "<g id=\"" << s.id << "\" fill=\"none\" stroke=\"" << s.colour
          << "\" stroke-width=\"" << s.width
          << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
      for (std::size_t l = 0; l < lines.line_count(); ++l) {
        if (int(lines.type[l]) != t)
          continue;
        out << "<polyline points=\"";
        for (std::uint32_t j = lines.offsets[l]; j < lines.offsets[l + 1];
             ++j) {
          const Vec3f &q = lines.points[j];
          const auto xy = project(camera, {q[0], q[1], q[2]}, width, height);
          std::snprintf(buf, sizeof buf, "%s%.2f,%.2f",
                        j == lines.offsets[l] ? "" : " ", xy[0], xy[1]);
          out << buf;
        }
        out << "\"";
        if (lines.strength[l] < 1) {
          std::snprintf(buf, sizeof buf, " stroke-opacity=\"%.3f\"",
                        std::max(0.0f, lines.strength[l]));
          out << buf;
        }
        out << "/>\n";
      }
      out << "</g>\n";
    }
    out << "</svg>\n";
    out.flush();
    if (!out)
      throw Error(path, "write failed (disk full?)");
  });
}

} // namespace isocurv::lines
