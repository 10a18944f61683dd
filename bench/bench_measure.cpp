// The OpenVDB peer of the shape-measure benchmark (issue 43; bench/python/bench_measure.py runs
// it beside isocurv and scikit-image and prints the tables). Reads a volume through isocurv's
// loader, makes a narrow-band level set (negative inside) of its isosurface as
// openvdb::tools::levelSetRebuild does (tools::VolumeToMesh at the isovalue, then
// tools::meshToVolume, --half-width voxels each side), and measures it with
// openvdb::tools::LevelSetMeasure.
//   - The object above the isovalue (densities, CT): the volume and the isovalue are negated first.
//   - levelSetRebuild's meshToVolume takes the sign from a flood fill from outside the mesh, which
//     fills enclosed cavities: a hollow object loses its inner surface (tried: the box with a
//     cavity came out without it). Here meshToVolume makes an unsigned distance band
//     (UNSIGNED_DISTANCE_FIELD) and each active voxel's sign is the volume's own (which side of
//     the isovalue the voxel is), then tools::signedFloodFill. --rebuild uses levelSetRebuild as is.
//   (tools::fogToSdf / sdfToSdf, fast sweeping over the whole volume, were tried: area about 1%
//   low and int K dA several 2 pi off even on an exact distance field, and fogToSdf throws on a
//   0/255 mask; not used.)
// Prints one JSON object on stdout: area, volume, integral_H (totMeanCurvature: OpenVDB's mean
// curvature is (k1 + k2) / 2 with the normal pointing out, as isocurv's, so its total is int H dA
// as it is), integral_K (totGaussianCurvature), euler_characteristic (OpenVDB's: round(int K dA /
// 2 pi)), and the median wall times in ms of the negation (once), the level set, the measure and
// both, over --repeat runs (the load is timed once, apart).
//   bench_measure VOLUME --iso V [--inside above|below] [--repeat N] [--half-width W] [--rebuild]
#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <openvdb/tools/ValueTransformer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "volume/load.h"

using namespace isocurv;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// levelSetRebuild's steps with the sign from the volume: the isosurface of `source` at `level`
/// (VolumeToMesh), an unsigned distance band of half_width voxels around it (meshToVolume), each
/// active voxel negative where source < level (a voxel equal to the level is outside, as
/// isocurv's extraction has it), then the inactive values' signs by flood fill.
openvdb::FloatGrid::Ptr signed_band(const openvdb::FloatGrid& source, float level, float half_width) {
  openvdb::tools::VolumeToMesh mesher(level);
  mesher(source);
  const openvdb::math::Transform& xform = source.transform();
  std::vector<openvdb::Vec3s> points(mesher.pointListSize());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = xform.worldToIndex(openvdb::Vec3d(mesher.pointList()[i]));
  std::vector<openvdb::Vec4I> prims;
  for (std::size_t n = 0; n < mesher.polygonPoolListSize(); ++n) {
    const openvdb::tools::PolygonPool& pool = mesher.polygonPoolList()[n];
    for (std::size_t i = 0; i < pool.numQuads(); ++i) prims.push_back(pool.quad(i));
    for (std::size_t i = 0; i < pool.numTriangles(); ++i) {
      const openvdb::Vec3I& t = pool.triangle(i);
      prims.emplace_back(t[0], t[1], t[2], openvdb::util::INVALID_IDX);
    }
  }
  openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec4I> mesh(points, prims);
  openvdb::FloatGrid::Ptr ls = openvdb::tools::meshToVolume<openvdb::FloatGrid>(
      mesh, xform, half_width, half_width,
      openvdb::tools::UNSIGNED_DISTANCE_FIELD | openvdb::tools::DISABLE_RENORMALIZATION);
  auto acc = source.getConstAccessor();
  for (auto leaf = ls->tree().beginLeaf(); leaf; ++leaf)
    for (auto it = leaf->beginValueOn(); it; ++it) {
      const float d = std::abs(*it);
      it.setValue(acc.getValue(it.getCoord()) < level ? -d : d);
    }
  openvdb::tools::signedFloodFill(ls->tree());
  ls->setGridClass(openvdb::GRID_LEVEL_SET);
  return ls;
}

int usage() {
  std::fprintf(stderr, "usage: bench_measure VOLUME --iso V [--inside above|below] [--repeat N] [--half-width W] [--rebuild]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  std::string path = argv[1], inside = "above";
  bool rebuild = false;
  double iso = 0;
  bool have_iso = false;
  int repeat = 5;
  float half_width = float(openvdb::LEVEL_SET_HALF_WIDTH);
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--rebuild") {
      rebuild = true;
      continue;
    }
    if (i + 1 >= argc) return usage();
    if (a == "--iso") iso = std::atof(argv[++i]), have_iso = true;
    else if (a == "--inside") inside = argv[++i];
    else if (a == "--repeat") repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--half-width") half_width = float(std::atof(argv[++i]));
    else return usage();
  }
  if (inside != "above" && inside != "below") return usage();
  try {
    openvdb::initialize();
    volume::LoadOptions lo;
    lo.inside = inside == "above" ? volume::Inside::Above : volume::Inside::Below;
    auto t0 = std::chrono::steady_clock::now();
    const volume::Volume vol = volume::load(path, lo);
    const double load_ms = ms_since(t0);
    if (!have_iso) iso = vol.stats.suggested_isovalue;

    // The level set's source: negative inside. A density (inside above) is negated, with its iso.
    openvdb::FloatGrid::Ptr source = vol.grid;
    float level = float(iso);
    double negate_ms = 0;
    if (lo.inside == volume::Inside::Above) {
      t0 = std::chrono::steady_clock::now();
      source = vol.grid->deepCopy();
      openvdb::tools::foreach(source->beginValueAll(),
                              [](const openvdb::FloatGrid::ValueAllIter& it) { it.setValue(-*it); });
      source->tree().root().setBackground(-vol.grid->background(), false);
      level = -level;
      negate_ms = ms_since(t0);
    }

    std::vector<double> rebuild_t, measure_t, total_t;
    double area = 0, volume = 0, int_h = 0, int_k = 0;
    int euler = 0;
    std::size_t active = 0;
    for (int r = 0; r < repeat; ++r) {
      t0 = std::chrono::steady_clock::now();
      openvdb::FloatGrid::Ptr ls = rebuild ? openvdb::tools::levelSetRebuild(*source, level, half_width, half_width)
                                           : signed_band(*source, level, half_width);
      ls->setGridClass(openvdb::GRID_LEVEL_SET);
      const double t_rebuild = ms_since(t0);
      const auto t1 = std::chrono::steady_clock::now();
      openvdb::tools::LevelSetMeasure<openvdb::FloatGrid> m(*ls);
      area = m.area(true);
      volume = m.volume(true);
      int_h = m.totMeanCurvature(true);
      int_k = m.totGaussianCurvature(true);
      euler = m.eulerCharacteristic();
      const double t_measure = ms_since(t1);
      rebuild_t.push_back(t_rebuild);
      measure_t.push_back(t_measure);
      total_t.push_back(ms_since(t0));
      active = std::size_t(ls->activeVoxelCount());
    }
    std::printf(
        "{\"area\": %.10g, \"volume\": %.10g, \"integral_H\": %.10g, \"integral_K\": %.10g, "
        "\"euler_characteristic\": %d, \"iso\": %.10g, \"inside\": \"%s\", \"method\": \"%s\", "
        "\"active_voxels\": %zu, \"half_width\": %g, \"repeat\": %d, \"timings_ms\": {\"load\": %.3f, "
        "\"negate\": %.3f, \"level_set\": %.3f, \"measure\": %.3f, \"level_set_measure\": %.3f}}\n",
        area, volume, int_h, int_k, euler, iso, inside.c_str(), rebuild ? "levelSetRebuild" : "unsigned band + volume sign", active, double(half_width),
        repeat, load_ms, negate_ms, median(rebuild_t), median(measure_t), median(total_t));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
