#include "viz/camera_file.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace isocurv::viz {
namespace {

constexpr std::size_t kMaxCameraFileBytes = 1 << 16;

std::array<double, 3> vec3(const nlohmann::json& j, const char* name, const std::string& path) {
  if (!j.contains(name) || !j[name].is_array() || j[name].size() != 3)
    throw Error(path, std::string("camera file needs \"") + name + "\": [x, y, z]");
  std::array<double, 3> v{};
  for (int i = 0; i < 3; ++i) {
    if (!j[name][i].is_number())
      throw Error(path, std::string("camera \"") + name + "\" holds a non-number");
    v[i] = j[name][i].get<double>();
    if (!std::isfinite(v[i]))
      throw Error(path, std::string("camera \"") + name + "\" is not finite");
  }
  return v;
}

}  // namespace

void save_camera(const std::string& path, const Camera& cam) {
  const nlohmann::json j = {{"position", cam.position},
                            {"focal_point", cam.focal_point},
                            {"view_up", cam.view_up},
                            {"ortho", cam.ortho},
                            {"view_angle_deg", cam.view_angle_deg},
                            {"parallel_scale", cam.parallel_scale}};
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << j.dump(2) << "\n";
    out.close();
    if (!out) throw Error(path, "cannot write the camera file");
  });
}

Camera load_camera(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open the camera file");
  std::string text(kMaxCameraFileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxCameraFileBytes) throw Error(path, "camera file is too large for a camera");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path, std::string("camera file is not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw Error(path, "camera file must hold a JSON object");
  Camera cam;
  cam.position = vec3(j, "position", path);
  cam.focal_point = vec3(j, "focal_point", path);
  cam.view_up = vec3(j, "view_up", path);
  if (j.contains("ortho")) {
    if (!j["ortho"].is_boolean()) throw Error(path, "camera \"ortho\" must be true or false");
    cam.ortho = j["ortho"].get<bool>();
  }
  for (auto [name, field] : {std::pair{"view_angle_deg", &cam.view_angle_deg},
                             std::pair{"parallel_scale", &cam.parallel_scale}}) {
    if (!j.contains(name)) continue;
    if (!j[name].is_number())
      throw Error(path, std::string("camera \"") + name + "\" must be a number");
    *field = j[name].get<double>();
  }
  if (!(cam.view_angle_deg > 0 && cam.view_angle_deg < 180))
    throw Error(path, "camera view_angle_deg must lie in (0, 180)");
  if (!(cam.parallel_scale > 0) || !std::isfinite(cam.parallel_scale))
    throw Error(path, "camera parallel_scale must be positive");
  const std::array<double, 3> d = cam.toward_camera();
  const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0.5)) throw Error(path, "camera position equals its focal_point");
  const auto& u = cam.view_up;
  const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double along = std::fabs(u[0] * d[0] + u[1] * d[1] + u[2] * d[2]);
  if (!(ul > 0) || along > 0.999 * ul)
    throw Error(path, "camera view_up is parallel to the view direction");
  // keep view_up perpendicular to the view direction, as Camera documents
  const double a = (u[0] * d[0] + u[1] * d[1] + u[2] * d[2]);
  std::array<double, 3> up{u[0] - a * d[0], u[1] - a * d[1], u[2] - a * d[2]};
  const double n = std::sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
  for (double& c : up) c /= n;
  cam.view_up = up;
  return cam;
}

}  // namespace isocurv::viz
