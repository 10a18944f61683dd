// The camera keywords lines() and screen() share (python/detail/camera.h).
#include "python/detail/camera.h"

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "screen/image_files.h"

namespace isocurv::python {

ViewSpec view_of(const std::string& view, double azimuth, double elevation, double zoom,
                 bool ortho) {
  ViewSpec spec;
  try {
    spec.view = parse_named_view(view);
  } catch (const Error& e) {
    throw py::value_error(std::string("view: ") + e.what());
  }
  if (!(azimuth >= -360 && azimuth <= 360))
    throw py::value_error("azimuth: expected -360..360 degrees");
  if (!(elevation >= -90 && elevation <= 90))
    throw py::value_error("elevation: expected -90..90 degrees");
  if (!(zoom >= 0.05 && zoom <= 50)) throw py::value_error("zoom: expected 0.05..50");
  spec.azimuth_deg = azimuth, spec.elevation_deg = elevation, spec.zoom = zoom, spec.ortho = ortho;
  return spec;
}

std::array<int, 2> size_of(const py::object& size) {
  std::array<int, 2> wh{};
  try {
    const auto v = size.cast<std::vector<long>>();
    if (v.size() != 2) throw py::cast_error();
    wh = {int(std::clamp<long>(v[0], -1, 1 << 20)), int(std::clamp<long>(v[1], -1, 1 << 20))};
  } catch (const py::cast_error&) {
    throw py::type_error("size: expected (width, height), two ints");
  }
  if (wh[0] < 16 || wh[1] < 16 || wh[0] > screen::kMaxImageSide || wh[1] > screen::kMaxImageSide)
    throw py::value_error("size: expected (width, height), each 16..8192");
  return wh;
}

py::dict camera_dict(const Camera& c) {
  py::dict d;
  d["position"] = py::make_tuple(c.position[0], c.position[1], c.position[2]);
  d["focal_point"] = py::make_tuple(c.focal_point[0], c.focal_point[1], c.focal_point[2]);
  d["view_up"] = py::make_tuple(c.view_up[0], c.view_up[1], c.view_up[2]);
  d["ortho"] = c.ortho;
  d["view_angle"] = c.view_angle_deg;
  d["parallel_scale"] = c.parallel_scale;
  return d;
}

}  // namespace isocurv::python
