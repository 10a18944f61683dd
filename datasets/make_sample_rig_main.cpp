// isocurv_make_sample_rig OUTDIR: the sample skinned mesh for `isocurv deform --deformer skin`
// (docs/time-series.md): OUTDIR/finger.vtp, a closed capsule along z (radius 0.25, a body from
// z = -1 to 1 with hemispherical caps; 48 segments around, 3,410 vertices, 6,816 triangles, wound
// outward), and OUTDIR/finger_rig.json, its skin (deform/skinning.h): two bones pivoting at the
// origin, "base" (never moves) and "tip", weighted by a smoothstep in z from all base at z <= -0.5
// to all tip at z >= 0.5, and three keyframes: rest at t = 0, the tip bent 90 degrees about the x
// axis at t = 1, rest again at t = 2. Below z = -0.5 the finger never moves; above z = 0.5 it moves
// rigidly; in between linear-blend skinning bends (and, on the inside of the bend, pinches) it.
// Runs at build time into <build>/datasets/. Deterministic: the same bytes on every run.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "io/mesh_file.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadius = 0.25, kHalfBody = 1.0;
constexpr int kSegments = 48;  // around
constexpr int kBodyRings = 49;  // z = -1 .. 1
constexpr int kCapRings = 11;   // per cap, excluding the pole and the body's end ring
constexpr double kBlendFrom = -0.5, kBlendTo = 0.5;

// The finger: the bottom pole, the rings from the bottom up, the top pole.
isocurv::Mesh finger(std::vector<double>& zs) {
  std::vector<std::pair<double, double>> profile;  // (rho, z) per ring, bottom to top
  for (int i = 1; i <= kCapRings; ++i) {
    const double phi = kPi / 2 * i / (kCapRings + 1);
    profile.push_back({kRadius * std::sin(phi), -kHalfBody - kRadius * std::cos(phi)});
  }
  for (int j = 0; j < kBodyRings; ++j)
    profile.push_back({kRadius, -kHalfBody + 2 * kHalfBody * j / (kBodyRings - 1)});
  for (int i = kCapRings; i >= 1; --i) {
    const double phi = kPi / 2 * i / (kCapRings + 1);
    profile.push_back({kRadius * std::sin(phi), kHalfBody + kRadius * std::cos(phi)});
  }
  isocurv::Mesh m;
  auto add = [&](double x, double y, double z) {
    m.positions.push_back({float(x), float(y), float(z)});
    zs.push_back(z);
  };
  add(0, 0, -kHalfBody - kRadius);
  for (const auto& [rho, z] : profile)
    for (int s = 0; s < kSegments; ++s) {
      const double theta = 2 * kPi * s / kSegments;
      add(rho * std::cos(theta), rho * std::sin(theta), z);
    }
  add(0, 0, kHalfBody + kRadius);
  const auto rings = std::uint32_t(profile.size());
  const auto top = std::uint32_t(m.positions.size() - 1);
  auto at = [](std::uint32_t ring, int s) {
    return std::uint32_t(1 + ring * kSegments + std::uint32_t(s % kSegments));
  };
  for (int s = 0; s < kSegments; ++s) m.triangles.push_back({0, at(0, s + 1), at(0, s)});
  for (std::uint32_t k = 0; k + 1 < rings; ++k)
    for (int s = 0; s < kSegments; ++s) {
      const std::uint32_t a = at(k, s), b = at(k, s + 1), c = at(k + 1, s + 1), d = at(k + 1, s);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  for (int s = 0; s < kSegments; ++s)
    m.triangles.push_back({top, at(rings - 1, s), at(rings - 1, s + 1)});
  return m;
}

// The tip bone's weight at height z: a smoothstep from kBlendFrom to kBlendTo.
double tip_weight(double z) {
  const double t = std::clamp((z - kBlendFrom) / (kBlendTo - kBlendFrom), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

std::string rig_json(const std::vector<double>& zs) {
  std::string s =
      "{\"comment\": \"isocurv sample rig for finger.vtp (datasets/make_sample_rig_main.cpp): "
      "the tip bends 90 degrees about x and back\",\n"
      " \"bones\": [{\"name\": \"base\", \"pivot\": [0, 0, 0]}, "
      "{\"name\": \"tip\", \"pivot\": [0, 0, 0]}],\n"
      " \"keyframes\": [{\"time\": 0, \"pose\": [{}, {}]},\n"
      "               {\"time\": 1, \"pose\": [{}, {\"rotation\": [0.70710678, 0.70710678, 0, 0]}]},\n"
      "               {\"time\": 2, \"pose\": [{}, {}]}],\n"
      " \"weights\": [";
  char buf[96];
  for (std::size_t i = 0; i < zs.size(); ++i) {
    const double w = tip_weight(zs[i]);
    if (w <= 0)
      std::snprintf(buf, sizeof buf, "[[0, 1]]");
    else if (w >= 1)
      std::snprintf(buf, sizeof buf, "[[1, 1]]");
    else
      std::snprintf(buf, sizeof buf, "[[0, %.6f], [1, %.6f]]", 1 - w, w);
    s += (i ? (i % 8 == 0 ? ",\n  " : ", ") : "");
    s += buf;
  }
  return s + "]}\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 || argv[1][0] == '-') {
    std::fprintf(argc == 2 ? stdout : stderr,
                 "usage: isocurv_make_sample_rig OUTDIR\n"
                 "Writes OUTDIR/finger.vtp (a capsule along z) and OUTDIR/finger_rig.json (its "
                 "two-bone skin) for isocurv deform --deformer skin.\n");
    return argc == 2 ? 0 : 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    std::vector<double> zs;
    const isocurv::Mesh m = finger(zs);
    isocurv::io::write_mesh((dir / "finger.vtp").string(), m);
    // Written beside and renamed, so a reader never sees half a rig.
    const std::filesystem::path rig = dir / "finger_rig.json", tmp = dir / "finger_rig.json.tmp";
    {
      std::ofstream out(tmp, std::ios::binary);
      out << rig_json(zs);
      if (!out.flush()) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, rig);
    std::printf("%s: %zu vertices, %zu triangles; %s: 2 bones, 3 keyframes\n",
                (dir / "finger.vtp").string().c_str(), m.positions.size(), m.triangles.size(),
                rig.string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isocurv_make_sample_rig: %s\n", e.what());
    return 1;
  }
  return 0;
}
