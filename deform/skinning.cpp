#include "deform/skinning.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "deform/detail/deform_program.h"

namespace isocurv::deform {
namespace {

using nlohmann::json;

constexpr double kWeightSumTolerance = 1e-3;

template <std::size_t N>
std::array<double, N> numbers(const json& j, const std::string& what, const std::string& name) {
  if (!j.is_array() || j.size() != N)
    throw Error("deform: " + name + ": " + what + " must be an array of " + std::to_string(N) +
                " numbers");
  std::array<double, N> a{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>()))
      throw Error("deform: " + name + ": " + what + " must be an array of " + std::to_string(N) +
                  " finite numbers");
    a[i] = j[i].get<double>();
  }
  return a;
}

const json& member(const json& j, const char* key, const std::string& name) {
  if (!j.is_object() || !j.contains(key))
    throw Error("deform: " + name + ": missing \"" + key + "\"");
  return j.at(key);
}

std::array<double, 4> normalised(std::array<double, 4> q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}

// Shortest-arc spherical interpolation of unit quaternions.
std::array<double, 4> slerp(const std::array<double, 4>& a, std::array<double, 4> b, double u) {
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  if (d < 0) {
    for (double& c : b) c = -c;
    d = -d;
  }
  std::array<double, 4> q;
  if (d > 0.9995) {  // nearly parallel: lerp and normalise
    for (int i = 0; i < 4; ++i) q[i] = a[i] + u * (b[i] - a[i]);
    return normalised(q);
  }
  const double theta = std::acos(d), s = std::sin(theta);
  const double wa = std::sin((1 - u) * theta) / s, wb = std::sin(u * theta) / s;
  for (int i = 0; i < 4; ++i) q[i] = wa * a[i] + wb * b[i];
  return q;
}

// M p = R (p - c) + c + T as a 3 x 4 matrix.
Affine bone_matrix(const std::array<double, 4>& q, const std::array<double, 3>& t,
                   const std::array<double, 3>& c) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  Affine m;
  for (int r = 0; r < 3; ++r) {
    double rc = 0;
    for (int k = 0; k < 3; ++k) {
      m[4 * r + k] = float(R[r][k]);
      rc += R[r][k] * c[k];
    }
    m[4 * r + 3] = float(c[r] - rc + t[r]);
  }
  return m;
}

}  // namespace

Skin parse_skin(const std::string& text, const std::string& name, std::size_t vertex_count) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    const std::size_t colon = what.find("parse error");
    throw Error("deform: " + name + ": not valid JSON (" +
                (colon == std::string::npos ? what : what.substr(colon)) + ")");
  }
  Skin skin;
  const json& bones = member(j, "bones", name);
  if (!bones.is_array() || bones.empty())
    throw Error("deform: " + name + ": \"bones\" must be a non-empty array");
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const json& bone = bones[b];
    if (!bone.is_object())
      throw Error("deform: " + name + ": bone " + std::to_string(b) + " must be an object");
    skin.bone_names.push_back(bone.contains("name") && bone["name"].is_string()
                                  ? bone["name"].get<std::string>()
                                  : "bone" + std::to_string(b));
    skin.pivots.push_back(
        bone.contains("pivot")
            ? numbers<3>(bone["pivot"], "bone " + std::to_string(b) + " pivot", name)
            : std::array<double, 3>{0, 0, 0});
  }
  const std::size_t nb = bones.size();

  const json& weights = member(j, "weights", name);
  if (!weights.is_array())
    throw Error("deform: " + name + ": \"weights\" must be an array (one entry per vertex)");
  if (weights.size() != vertex_count)
    throw Error("deform: " + name + ": the skin has weights for " + std::to_string(weights.size()) +
                " vertices but the mesh has " + std::to_string(vertex_count));
  skin.bones.assign(vertex_count, {0, 0, 0, 0});
  skin.weights.assign(vertex_count, {0, 0, 0, 0});
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const json& list = weights[v];
    const std::string where = "vertex " + std::to_string(v);
    if (!list.is_array() || list.empty() || list.size() > 4)
      throw Error("deform: " + name + ": " + where + " must have 1 to 4 [bone, weight] pairs");
    double sum = 0;
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::array<double, 2> bw = numbers<2>(list[k], where + " [bone, weight]", name);
      if (bw[0] < 0 || bw[0] != std::floor(bw[0]) || bw[0] >= double(nb))
        throw Error("deform: " + name + ": " + where + " refers to bone " +
                    json(list[k][0]).dump() + " but the skin has " + std::to_string(nb) + " bones");
      if (bw[1] < 0) throw Error("deform: " + name + ": " + where + " has a negative weight");
      skin.bones[v][k] = std::uint32_t(bw[0]);
      skin.weights[v][k] = float(bw[1]);
      sum += bw[1];
    }
    if (std::abs(sum - 1) > kWeightSumTolerance) {
      std::ostringstream s;
      s << "deform: " << name << ": " << where << "'s weights sum to " << sum << ", not 1";
      throw Error(s.str());
    }
  }

  const json& keys = member(j, "keyframes", name);
  if (!keys.is_array() || keys.empty())
    throw Error("deform: " + name + ": \"keyframes\" must be a non-empty array");
  for (std::size_t f = 0; f < keys.size(); ++f) {
    const std::string where = "keyframe " + std::to_string(f);
    const json& key = keys[f];
    Keyframe kf;
    const json& time = member(key, "time", name);
    if (!time.is_number() || !std::isfinite(time.get<double>()))
      throw Error("deform: " + name + ": " + where + " time must be a finite number");
    kf.time = time.get<double>();
    if (f > 0 && !(kf.time > skin.keyframes.back().time))
      throw Error("deform: " + name + ": " + where + " time " + time.dump() +
                  " is not after the previous keyframe's");
    const json& pose = member(key, "pose", name);
    if (!pose.is_array() || pose.size() != nb)
      throw Error("deform: " + name + ": " + where + " must have a pose for each of the " +
                  std::to_string(nb) + " bones");
    for (std::size_t b = 0; b < nb; ++b) {
      const std::string bwhere = where + " bone " + std::to_string(b);
      if (!pose[b].is_object())
        throw Error("deform: " + name + ": " + bwhere + " must be an object");
      BonePose p;
      if (pose[b].contains("rotation")) {
        p.rotation = numbers<4>(pose[b]["rotation"], bwhere + " rotation", name);
        const double n2 = p.rotation[0] * p.rotation[0] + p.rotation[1] * p.rotation[1] +
                          p.rotation[2] * p.rotation[2] + p.rotation[3] * p.rotation[3];
        if (!(n2 > 1e-12))
          throw Error("deform: " + name + ": " + bwhere + " rotation is the zero quaternion");
        p.rotation = normalised(p.rotation);
      }
      if (pose[b].contains("translation"))
        p.translation = numbers<3>(pose[b]["translation"], bwhere + " translation", name);
      kf.pose.push_back(p);
    }
    skin.keyframes.push_back(std::move(kf));
  }
  return skin;
}

Skin load_skin(const std::string& path, std::size_t vertex_count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("deform: cannot open skin file " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_skin(text.str(), path, vertex_count);
}

std::vector<Affine> bone_matrices(const Skin& skin, double t) {
  const std::vector<Keyframe>& k = skin.keyframes;
  std::size_t hi = 0;
  while (hi < k.size() && k[hi].time < t) ++hi;
  std::size_t lo = hi == 0 ? 0 : hi - 1;
  if (hi == k.size()) hi = lo = k.size() - 1;
  if (hi == 0) lo = 0;
  const double span = k[hi].time - k[lo].time;
  const double u = span > 0 ? std::clamp((t - k[lo].time) / span, 0.0, 1.0) : 0.0;
  std::vector<Affine> m(skin.bone_count());
  for (std::size_t b = 0; b < skin.bone_count(); ++b) {
    const BonePose &a = k[lo].pose[b], &c = k[hi].pose[b];
    const std::array<double, 4> q = u == 0 ? a.rotation : slerp(a.rotation, c.rotation, u);
    std::array<double, 3> tr;
    for (int i = 0; i < 3; ++i)
      tr[i] = a.translation[i] + u * (c.translation[i] - a.translation[i]);
    m[b] = bone_matrix(q, tr, skin.pivots[b]);
  }
  return m;
}

DeviceSkin::DeviceSkin(Device& device, const Skin& skin)
    : device_(device), vertex_count_(skin.vertex_count()), bone_count_(skin.bone_count()) {
  device_call(device, "deform: uploading the skin", [&] {
    std::vector<cl_uint4> b(std::max<std::size_t>(vertex_count_, 1));
    std::vector<cl_float4> w(b.size());
    for (std::size_t v = 0; v < vertex_count_; ++v)
      for (int k = 0; k < 4; ++k) b[v].s[k] = skin.bones[v][k], w[v].s[k] = skin.weights[v][k];
    const cl_mem_flags flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    bones_ = cl::Buffer(device.context(), flags, b.size() * sizeof(cl_uint4), b.data());
    weights_ = cl::Buffer(device.context(), flags, w.size() * sizeof(cl_float4), w.data());
    matrices_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY,
                           std::max<std::size_t>(bone_count_, 1) * sizeof(Affine));
  });
}

void DeviceSkin::apply(const cl::Buffer& rest, const std::vector<Affine>& matrices,
                       cl::Buffer& out) {
  if (matrices.size() != bone_count_)
    throw Error("deform: " + std::to_string(matrices.size()) + " bone matrices for a skin of " +
                std::to_string(bone_count_) + " bones");
  detail::DeformKernels& k = detail::deform_kernels(device_);
  std::lock_guard<std::mutex> lock(k.mutex);
  device_call(device_, "deform: skinning", [&] {
    cl::CommandQueue& q = device_.queue();
    q.enqueueWriteBuffer(matrices_, CL_TRUE, 0, matrices.size() * sizeof(Affine), matrices.data());
    set_args(k.skin, rest, bones_, weights_, cl_uint(vertex_count_), matrices_, out);
    launch(q, k.skin, vertex_count_, detail::kGroup);
  });
}

Positions skin_reference(const Positions& rest, const Skin& skin,
                         const std::vector<Affine>& matrices) {
  Positions out(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const float x = rest[i][0], y = rest[i][1], z = rest[i][2];
    float acc[3] = {0, 0, 0};
    for (int j = 0; j < 4; ++j) {
      const float w = skin.weights[i][j];
      if (w == 0.0f) continue;
      const Affine& m = matrices[skin.bones[i][j]];
      for (int r = 0; r < 3; ++r)
        acc[r] += w * (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3]);
    }
    out[i] = {acc[0], acc[1], acc[2]};
  }
  return out;
}

}  // namespace isocurv::deform
