#pragma once
// The camera keywords lines() and screen() share (the CLI's --view --azimuth --elevation --zoom
// --ortho --size), and the camera they report.
#include <array>
#include <string>

#include "core/camera.h"
#include "python/detail/args.h"

namespace isocurv::python {

/// The camera keywords (the CLI's --view --azimuth --elevation --zoom --ortho) as a ViewSpec.
ViewSpec view_of(const std::string& view, double azimuth, double elevation, double zoom,
                 bool ortho);

/// size=(width, height) as the CLI's --size WIDTHxHEIGHT, each 16..8192.
std::array<int, 2> size_of(const py::object& size);

/// A camera as the results' 'camera' dict: {position, focal_point, view_up, ortho, view_angle,
/// parallel_scale}.
py::dict camera_dict(const Camera& c);

}  // namespace isocurv::python
