#pragma once
// Shared by the benchmarks: median wall time, peak extra memory of one run, dense VTK images.
#include <malloc.h>

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/huge_pages.h"
#include "volume/volume.h"

namespace isocurv::bench {

/// Keeps freed heap memory in the process (core/huge_pages.h), so every method's repeated runs
/// reuse touched pages rather than timing fresh page faults, for whichever method happens to free
/// and re-map. Call once, first thing.
inline void keep_freed_memory() { retain_freed_memory(); }

/// A method to time and how many timed calls it gets.
struct Timed {
  std::function<void()> f;
  int runs;
};

/// Median wall time in ms of each method's timed calls. Each first gets untimed warm-up calls
/// (at least 2, then until half a second has passed or 10 were made: the first calls pay for first
/// touches of memory, JIT compiles and the like); then the methods are timed in turns, one call
/// each a round, so a shared machine slowing down or speeding up weighs on all of them alike. Each
/// round takes them in a fresh random order (fixed seed), so each follows every other about equally
/// often: a call runs slower after a heavy one (caches emptied, its idle threads still spinning).
inline std::vector<double> medians_ms(const std::vector<Timed>& methods) {
  for (const Timed& m : methods) {
    const auto warm_start = std::chrono::steady_clock::now();
    for (int i = 0; i < 10; ++i) {
      m.f();
      if (i >= 1 && std::chrono::steady_clock::now() - warm_start > std::chrono::milliseconds(500)) break;
    }
  }
  std::vector<std::vector<double>> t(methods.size());
  std::vector<std::size_t> order(methods.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::mt19937 rng(20261201);
  for (bool more = true; more;) {
    more = false;
    std::shuffle(order.begin(), order.end(), rng);
    for (const std::size_t i : order) {
      if (int(t[i].size()) >= std::max(1, methods[i].runs)) continue;
      const auto t0 = std::chrono::steady_clock::now();
      methods[i].f();
      t[i].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      more = true;
    }
  }
  std::vector<double> medians;
  for (auto& ti : t) {
    std::sort(ti.begin(), ti.end());
    medians.push_back(ti[ti.size() / 2]);
  }
  return medians;
}

inline long status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(std::string(key).size()));
  return -1;
}

/// Peak memory (MiB) that one call of f adds on top of what the process holds: the high-water
/// mark is reset first (Linux /proc/self/clear_refs) and freed heap handed back (malloc_trim).
/// In-process, since OpenCL runtimes do not survive fork().
inline double peak_extra_mib(const std::function<void()>& f) {
  malloc_trim(0);
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  const long before = status_kb("VmRSS:");
  f();
  const long peak = status_kb("VmHWM:");
  return (peak - before) / 1024.0;
}

/// The volume's dense domain as a vtkImageData (float scalars, spacing and origin of the
/// transform's diagonal), what VTK's filters take.
inline vtkSmartPointer<vtkImageData> to_image(const volume::Volume& v) {
  const openvdb::CoordBBox box = v.domain;
  const openvdb::Coord d = box.dim();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(d.x(), d.y(), d.z());
  const openvdb::Vec3d sp = v.spacing();
  const openvdb::Vec3d org = v.grid->transform().indexToWorld(box.min());
  image->SetSpacing(sp.x(), sp.y(), sp.z());
  image->SetOrigin(org.x(), org.y(), org.z());
  auto values = vtkSmartPointer<vtkFloatArray>::New();
  values->SetNumberOfTuples(vtkIdType(d.x()) * d.y() * d.z());
  float* out = values->GetPointer(0);
  auto acc = v.grid->getConstAccessor();
  for (int z = 0; z < d.z(); ++z)
    for (int y = 0; y < d.y(); ++y)
      for (int x = 0; x < d.x(); ++x) *out++ = acc.getValue(box.min() + openvdb::Coord(x, y, z));
  image->GetPointData()->SetScalars(values);
  return image;
}

}  // namespace isocurv::bench
