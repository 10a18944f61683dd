// Distributed extraction at 1-64 ranks, counted rather than timed: this machine has two cores, so
// the ranks are simulated one after another in this process, each extracting its slab with its
// margin exactly as `mpirun -np N isocurv extract` does (dist/). Per rank count it prints the
// work each rank does (its slab's triangles, and those it makes again in its margin), the seam
// vertices, the voxels it reads beyond its slab, and the bytes it sends; from them a model of the
// time at N ranks (the single process's extraction time scaled by the busiest rank's share), and
// the rank count at which a rank's margin costs more than its own work. Not a test: a table.
//
//   bench_distributed [--size N] [--ranks 1,2,4,...] [--volume PATH [--iso V]]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "dist/piece.h"
#include "dist/slabs.h"
#include "mc/extract.h"
#include "mc/frame.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

struct RankCounts {
  std::size_t owned = 0;       // triangles its slab owns
  std::size_t extracted = 0;   // triangles it extracts (slab and margin)
  std::size_t seam = 0;        // vertices in its piece that another rank owns
  std::size_t ghost_cells = 0; // ghost-ring triangles
  std::uint64_t ghost_voxels = 0;  // voxels read beyond its slab
  std::uint64_t layers = 0;        // voxel layers (index z) of its slab
  std::uint64_t totals_bytes = 0;  // sent for the totals (counters, component links)
  std::uint64_t gather_bytes = 0;  // sent with --gather (owned vertices and triangles)
};

void run(const std::string& name, const volume::Volume& v, float iso, const std::vector<int>& rank_counts) {
  Device& dev = Device::default_device();
  mc::Mesher mesher(v, dev);
  mc::Options mo;
  const mc::Frame whole = mc::make_frame(v, iso, mo);
  double t1 = 0;
  std::size_t total = 0;
  {
    const bench::Timed one{[&] { total = mesher.extract(iso, mo).triangles.size(); }, 3};
    t1 = bench::medians_ms({one})[0];
  }
  const std::vector<openvdb::Coord> bricks = mesher.surface_bricks(iso, mo);
  const int first = whole.cells.min().z() & ~7;
  std::vector<std::uint64_t> layers(std::size_t((whole.cells.max().z() - first) / 8 + 1), 0);
  for (const openvdb::Coord& b : bricks) ++layers[std::size_t((b.z() - first) / 8)];
  const openvdb::Coord dim = v.domain.dim();
  const std::uint64_t slice = std::uint64_t(dim.x()) * std::uint64_t(dim.y());
  std::printf("\n%s: %d x %d x %d voxels, %zu triangles, %zu surface bricks in %zu brick layers; one process "
              "extracts in %.1f ms (median of 3). Per rank, the largest: slab (voxel layers), triangles owned and made "
              "(the margin's too), margin work as a share of own work, seam vertices (owned elsewhere), voxels read "
              "beyond the slab, bytes sent for the totals and for --gather\n",
              name.c_str(), dim.x(), dim.y(), dim.z(), total, bricks.size(), layers.size(), t1);
  std::printf("%6s %9s %11s %11s %9s %9s %13s %11s %11s %10s %8s\n", "ranks", "slab max", "owned max", "made max",
              "margin %", "seam max", "ghost vox max", "totals B", "gather B", "model ms", "speedup");
  int seams_win = 0;
  for (int n : rank_counts) {
    const dist::Slabs slabs = dist::balance_slabs(layers, first, n, whole.key_origin.z());
    std::vector<RankCounts> c(static_cast<std::size_t>(n));
    std::size_t owned_sum = 0;
    for (int r = 0; r < n; ++r) {
      mc::Options local = mo;
      local.keep_edge_keys = true;
      std::tie(local.cells_min[2], local.cells_max[2]) = slabs.extract_range(r, dist::kExtractGhostCells);
      const Mesh m = mesher.extract(iso, local);
      const dist::Piece p = dist::cut_piece(m, slabs, r);
      RankCounts& k = c[std::size_t(r)];
      k.owned = p.owned_triangles;
      k.extracted = m.triangles.size();
      k.ghost_cells = p.mesh.triangles.size() - p.owned_triangles;
      for (std::uint8_t g : p.point_ghost) k.seam += g != 0;
      // Voxels read beyond the slab: the margin's layers inside the volume, and the sample layer
      // above the last cell.
      const long long dz0 = v.domain.min().z(), dz1 = v.domain.max().z();
      const long long held_lo = std::max<long long>(local.cells_min[2], dz0);
      const long long held_hi = std::min<long long>((long long)local.cells_max[2] + 1, dz1);
      const long long own_lo = std::max<long long>(slabs.cuts[std::size_t(r)], dz0);
      const long long own_hi = std::min<long long>((long long)slabs.cuts[std::size_t(r) + 1] - 1, dz1);
      const long long held = std::max<long long>(0, held_hi - held_lo + 1);
      const long long own = std::max<long long>(0, own_hi - own_lo + 1);
      k.ghost_voxels = std::uint64_t(std::max<long long>(0, held - own)) * slice;
      k.layers = std::uint64_t(own);
      std::size_t link_vertices = 0;
      std::vector<char> linked(p.mesh.positions.size(), 0);
      for (std::size_t t = p.owned_triangles; t < p.mesh.triangles.size(); ++t)
        for (std::uint32_t vtx : p.mesh.triangles[t]) linked[vtx] = 1;
      for (char l : linked) link_vertices += l != 0;
      k.totals_bytes = 8 * 8 + 4 + 12 * link_vertices;
      std::size_t owned_vertices = 0;
      for (std::uint8_t g : p.point_ghost) owned_vertices += g == 0;
      k.gather_bytes = 16 + owned_vertices * (8 + 12) + p.owned_triangles * 24;
      owned_sum += k.owned;
    }
    auto max_of = [&](auto field) {
      std::uint64_t m = 0;
      for (const RankCounts& k : c) m = std::max<std::uint64_t>(m, k.*field);
      return m;
    };
    const std::uint64_t made = max_of(&RankCounts::extracted), owned = max_of(&RankCounts::owned);
    // The busiest rank's extraction, as a share of the whole one's, sets the time.
    const double model = t1 * double(made) / double(std::max<std::size_t>(total, 1));
    std::uint64_t margin_work = 0, own_work = 0;
    for (const RankCounts& k : c) {
      margin_work = std::max<std::uint64_t>(margin_work, k.extracted - k.owned);
      own_work = std::max<std::uint64_t>(own_work, k.owned);
    }
    if (!seams_win && margin_work > own_work) seams_win = n;
    int used = 0;
    for (const RankCounts& k : c) used += k.owned > 0;
    std::printf("%6d %9llu %11llu %11llu %8.1f%% %9llu %13llu %11llu %11llu %10.1f %7.2fx%s\n", n,
                (unsigned long long)max_of(&RankCounts::layers), (unsigned long long)owned, (unsigned long long)made,
                100.0 * double(margin_work) / double(std::max<std::uint64_t>(own_work, 1)),
                (unsigned long long)max_of(&RankCounts::seam), (unsigned long long)max_of(&RankCounts::ghost_voxels),
                (unsigned long long)max_of(&RankCounts::totals_bytes),
                (unsigned long long)max_of(&RankCounts::gather_bytes), model, t1 / model,
                used < n ? (" (" + std::to_string(n - used) + " ranks idle)").c_str() : "");
    if (owned_sum != total) std::printf("       owned triangles add up to %zu, not %zu\n", owned_sum, total);
  }
  if (seams_win)
    std::printf("the margin outweighs a rank's own work from %d ranks on\n", seams_win);
  else
    std::printf("the margin stays below a rank's own work at every rank count here\n");
}

std::vector<int> parse_ranks(const std::string& text) {
  std::vector<int> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = text.find(',', at);
    out.push_back(std::stoi(text.substr(at, comma - at)));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  int size = 256;
  std::vector<int> ranks = {1, 2, 4, 8, 16, 32, 64};
  std::string volume_path;
  std::optional<float> iso;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw Error(a + " needs a value");
        return argv[++i];
      };
      if (a == "--size") size = std::stoi(value());
      else if (a == "--ranks") ranks = parse_ranks(value());
      else if (a == "--volume") volume_path = value();
      else if (a == "--iso") iso = std::stof(value());
      else throw Error("unknown argument " + a + " (bench_distributed [--size N] [--ranks 1,2,4] [--volume PATH [--iso V]])");
    }
    if (!volume_path.empty()) {
      volume::Volume v = volume::load(volume_path);
      const float value = iso ? *iso : float(v.stats.suggested_isovalue);
      run(std::filesystem::path(volume_path).filename().string(), v, value, ranks);
      return 0;
    }
    auto gyroid = datasets::make_field("gyroid");
    run("gyroid " + std::to_string(size) + "^3", datasets::sample(*gyroid, size), float(gyroid->isovalue()), ranks);
    const std::string lidc = std::string(ISOCURV_SHARED_DATASETS) + "/lidc2_ct/LIDC2_256x256x133_uint8.raw.gz";
    if (std::filesystem::exists(lidc)) {
      volume::LoadOptions lo;
      lo.raw.dims = {256, 256, 133};
      lo.raw.type = "uint8";
      run("LIDC2 CT 256x256x133", volume::load(lidc, lo), 60.0f, ranks);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_distributed: %s\n", e.what());
    return 1;
  }
  return 0;
}
