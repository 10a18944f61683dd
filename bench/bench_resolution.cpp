// A real volume and the same volume averaged 2x2x2 (rounded back to the file's integer type, as a
// coarser scan would store it): does the curvature agree? Each is extracted at the same isovalue
// and estimated with the defaults (the volume estimator's per-vertex scale) and at fixed world
// scales; every vertex of the coarse surface is matched to the nearest vertex of the fine one
// (within kMatchVoxels coarse voxels), and the table gives the
// Pearson correlation of H over the matched pairs that neither side flags Unreliable or
// Boundary, with the RMS difference relative to the RMS of H, again over the pairs whose |H| is
// at most kResolvedH (radii of 4 fine voxels and more: shapes both grids resolve), and the
// median scale each side used. Not a test (issue 52's real-data target: correlation >= 0.9 at
// the defaults).
//
//   bench_resolution [PATH] [--iso V] [--scales S1,S2,...] [--surface]
//
// PATH defaults to ../shared/datasets/lobster/lobster.vol; V to its suggested isovalue; the
// scales (world units) to 2 and 4 voxels beside the default; --surface evaluates at the smoothed
// surface's points (curvature::VolumePoint::surface) instead of the vertices.
#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/ao_scale.h"
#include "curvature/estimator.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

/// A coarse vertex is matched to the nearest fine vertex within this many coarse voxels.
constexpr double kMatchVoxels = 0.5;
/// The second correlation's bound on |H|, per fine voxel.
constexpr double kResolvedH = 0.25;

// `v` averaged over 2x2x2 blocks from its domain's first voxel: spacing doubled, the coarse
// sample at the centre of its block (so the two describe the same object in world space).
volume::Volume block_average(const volume::Volume& v) {
  const openvdb::CoordBBox d = v.domain;
  const openvdb::Coord n((d.dim()[0]) / 2, (d.dim()[1]) / 2, (d.dim()[2]) / 2);
  if (n[0] < 8 || n[1] < 8 || n[2] < 8) throw Error("bench_resolution: the volume is too small to halve");
  volume::Volume c = v;
  c.grid = openvdb::FloatGrid::create(v.grid->background());
  const openvdb::Vec3d h = v.spacing();
  const openvdb::Vec3d first = v.grid->transform().indexToWorld(d.min().asVec3d() + openvdb::Vec3d(0.5));
  openvdb::math::Transform::Ptr t = openvdb::math::Transform::createLinearTransform(1.0);
  t->preScale(openvdb::Vec3d(2 * h[0], 2 * h[1], 2 * h[2]));
  t->postTranslate(first);
  c.grid->setTransform(t);
  const bool round = volume::is_integer_type(v.voxel_type);
  openvdb::FloatGrid::ConstAccessor in = v.grid->getConstAccessor();
  openvdb::FloatGrid::Accessor out = c.grid->getAccessor();
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        double sum = 0;
        for (int k = 0; k < 2; ++k)
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i)
              sum += in.getValue(d.min() + openvdb::Coord(2 * x + i, 2 * y + j, 2 * z + k));
        const double mean = sum / 8;
        out.setValue(openvdb::Coord(x, y, z), float(round ? std::nearbyint(mean) : mean));
      }
  c.domain = openvdb::CoordBBox(openvdb::Coord(0), n - openvdb::Coord(1));
  c.path = v.path + " (2x2x2 average)";
  c.slab.reset();
  return c;
}

struct Estimate {
  Mesh mesh;
  curvature::CurvatureField field;
  std::vector<std::uint8_t> skip;  // Unreliable or Boundary
  double ms = 0;
};

Estimate estimate(const volume::Volume& v, float iso, double scale, Device& dev, bool surface = false) {
  Estimate e;
  e.mesh = mc::extract(v, iso, dev);
  curvature::Options o;
  o.estimator = curvature::Estimator::volume;
  o.scale = scale;  // 0: the default, per vertex
  o.ao_scale = curvature::default_ao_scale(e.mesh);
  if (surface) o.volume_point = curvature::VolumePoint::surface;
  const auto t0 = std::chrono::steady_clock::now();
  e.field = curvature::estimate_field(e.mesh, {&v, iso}, &dev, o);
  e.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  e.skip.assign(e.mesh.positions.size(), 0);
  for (std::size_t i = 0; i < e.skip.size(); ++i)
    e.skip[i] = (!e.field.unreliable.empty() && e.field.unreliable[i]) ||
                (!e.field.boundary.empty() && e.field.boundary[i]);
  return e;
}

struct Agreement {
  std::size_t pairs = 0;
  double correlation = 0, relative_rms = 0;
};

// Each coarse vertex against the nearest fine vertex within `radius` (world units).
Agreement agree(const Estimate& fine, const Estimate& coarse, double radius, double hmax = 1e30) {
  using Key = std::tuple<long, long, long>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::size_t(std::get<0>(k) * 73856093L ^ std::get<1>(k) * 19349663L ^ std::get<2>(k) * 83492791L);
    }
  };
  auto key = [&](const Vec3f& p) {
    return Key{long(std::floor(p[0] / radius)), long(std::floor(p[1] / radius)), long(std::floor(p[2] / radius))};
  };
  std::unordered_map<Key, std::vector<std::uint32_t>, KeyHash> cells;
  for (std::size_t i = 0; i < fine.mesh.positions.size(); ++i)
    if (!fine.skip[i]) cells[key(fine.mesh.positions[i])].push_back(std::uint32_t(i));
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, sd = 0;
  Agreement a;
  for (std::size_t i = 0; i < coarse.mesh.positions.size(); ++i) {
    if (coarse.skip[i]) continue;
    const Vec3f& p = coarse.mesh.positions[i];
    const auto [kx, ky, kz] = key(p);
    double best = radius * radius;
    long found = -1;
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find(Key{kx + dx, ky + dy, kz + dz});
          if (it == cells.end()) continue;
          for (std::uint32_t j : it->second) {
            const Vec3f& q = fine.mesh.positions[j];
            const double d2 = double(p[0] - q[0]) * (p[0] - q[0]) + double(p[1] - q[1]) * (p[1] - q[1]) +
                              double(p[2] - q[2]) * (p[2] - q[2]);
            if (d2 < best) best = d2, found = long(j);
          }
        }
    if (found < 0) continue;
    const double x = fine.field.H[std::size_t(found)], y = coarse.field.H[i];
    if (std::abs(x) > hmax || std::abs(y) > hmax) continue;
    sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y, sd += (x - y) * (x - y);
    ++a.pairs;
  }
  if (a.pairs < 2) return a;
  const double n = double(a.pairs);
  const double cov = sab / n - sa / n * sb / n, va = saa / n - sa / n * sa / n, vb = sbb / n - sb / n * sb / n;
  a.correlation = cov / std::sqrt(va * vb);
  a.relative_rms = std::sqrt(sd / n) / std::sqrt(saa / n);
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(ISOCURV_SHARED_DATASETS) + "/lobster/lobster.vol";
  std::vector<double> scales = {0};  // 0: the default
  bool iso_given = false;
  float iso = 0;
  std::string given_scales;
  bool surface = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--iso" && i + 1 < argc) {
      iso = std::strtof(argv[++i], nullptr), iso_given = true;
    } else if (a == "--surface") {
      surface = true;
    } else if (a == "--scales" && i + 1 < argc) {
      given_scales = argv[++i];
    } else if (!a.empty() && a[0] != '-') {
      path = a;
    } else {
      std::fprintf(stderr, "usage: bench_resolution [PATH] [--iso V] [--scales S1,S2,...] [--surface]\n");
      return 2;
    }
  }
  try {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    openvdb::initialize();
    const volume::Volume fine = volume::load(path);
    const volume::Volume coarse = block_average(fine);
    const openvdb::Vec3d h = fine.spacing();
    const double voxel = std::cbrt(h[0] * h[1] * h[2]);
    if (given_scales.empty()) {
      for (double s : {2.0, 4.0}) scales.push_back(s * voxel);
    } else {
      std::stringstream in(given_scales);
      for (std::string s; std::getline(in, s, ',');) scales.push_back(std::stod(s));
    }
    const float value = iso_given ? iso : float(fine.stats.suggested_isovalue);
    Device& dev = Device::default_device();
    std::printf("%s, iso %g: the volume (spacing %g %g %g) and its 2x2x2 average; H at coarse vertices "
                "matched to the nearest fine vertex within %g coarse voxel%s; resolved: |H| <= %g per "
                "fine voxel; scales in world units\n",
                std::filesystem::path(path).filename().string().c_str(), double(value), h[0], h[1], h[2],
                kMatchVoxels, surface ? ", at the smoothed surface's points" : "", kResolvedH);
    std::printf("%-22s %8s %8s %7s %7s %7s %9s %7s %12s %8s %8s\n", "scale", "fine", "coarse", "pairs",
                "corr", "RMS d/H", "resolved", "corr", "p50 scale f/c", "fine ms", "coarse ms");
    estimate(fine, value, 0, dev, surface);  // warm-up (program builds)
    auto median_scale = [](const Estimate& e) {
      const std::vector<float>* scale = e.field.find_extra("Scale");
      if (!scale || scale->empty()) return 0.0;
      std::vector<float> v = *scale;
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return double(v[v.size() / 2]);
    };
    for (double s : scales) {
      const Estimate f = estimate(fine, value, s, dev, surface), c = estimate(coarse, value, s, dev, surface);
      const Agreement a = agree(f, c, kMatchVoxels * 2 * voxel);
      const Agreement r = agree(f, c, kMatchVoxels * 2 * voxel, kResolvedH / voxel);
      char name[64], used[32];
      if (s == 0)
        std::snprintf(name, sizeof name, "default (per vertex)");
      else
        std::snprintf(name, sizeof name, "fixed %.3g world", s);
      std::snprintf(used, sizeof used, "%.3g/%.3g", median_scale(f), median_scale(c));
      std::printf("%-22s %8zu %8zu %7zu %7.3f %7.3f %9zu %7.3f %12s %8.1f %8.1f\n", name,
                  f.mesh.positions.size(), c.mesh.positions.size(), a.pairs, a.correlation,
                  a.relative_rms, r.pairs, r.correlation, used, f.ms, c.ms);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_resolution: %s\n", e.what());
    return 1;
  }
  return 0;
}
