#pragma once
// Feature lines out: vtkPolyData, .vtp files and SVG drawings.
// Tested in tests/lines/test_svg_visibility.cpp.
#include <array>
#include <string>

#include <vtkSmartPointer.h>

#include "core/camera.h"
#include "lines/polylines.h"

class vtkPolyData;

namespace isocurv::lines {

/// The lines as vtkPolyData polylines with cell arrays `LineType` (unsigned
/// char, the LineType values) and `Strength` (float).
vtkSmartPointer<vtkPolyData> to_polydata(const Polylines &lines);

/// Writes to_polydata(lines) as a .vtp (binary, zlib), atomically. @throw Error
/// on failure.
void write_vtp(const std::string &path, const Polylines &lines);

/// Where world point `p` lands in a width x height picture taken with `camera`
/// as VTK renders it (vertical view angle, square pixels): x to the right and y
/// down from the top-left corner, in pixels, and the depth along the view
/// direction (world units; > 0 in front of a perspective eye).
std::array<double, 3> project(const Camera &camera,
                              const std::array<double, 3> &p, int width,
                              int height);

/// Writes the lines projected by `camera` into a width x height SVG drawing
/// (white background, one <polyline> each, grouped by type: contours black,
/// suggestive contours dark grey, ridges red, valleys blue; opacity from
/// Strength), atomically. Hidden-line removal is the caller's
/// (VisibilityTester; `isocurv lines` passes only the visible segments). @throw
/// Error for a size outside 16..16384 or a failed write.
void write_svg(const std::string &path, const Polylines &lines,
               const Camera &camera, int width, int height);

} // namespace isocurv::lines
