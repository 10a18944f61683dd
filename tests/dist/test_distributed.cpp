// Distributed extraction and curvature (dist/, app/distributed.cpp): the slabs; the pieces cut
// in-process, which must fit together into exactly the whole extraction; and `mpirun -np 1..4
// isocurv extract|curvature` on analytic and real volumes, read back through VTK's
// vtkXMLPPolyDataReader and matched by global id against the single process.
#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPPolyDataReader.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <set>

#include "core/cl_device.h"
#include "datasets/ct_like.h"
#include "dist/piece.h"
#include "io/mesh_file.h"
#include "dist/slabs.h"
#include "mc/bricks.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/frame.h"
#include "tests/app/cli.h"
#include "volume/load.h"

namespace isocurv {
namespace {

using test::CliResult;
using test::TempDir;
namespace fs = std::filesystem;
using IdTri = std::array<std::int64_t, 3>;

// A triangle as its vertices' ids, rotated to start at the lowest (its orientation kept).
IdTri canonical(std::int64_t a, std::int64_t b, std::int64_t c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

bool same_bits(const Vec3f& a, const Vec3f& b) { return std::memcmp(a.data(), b.data(), sizeof a) == 0; }

// The whole extraction, by edge key: positions and triangles.
struct ById {
  std::map<std::int64_t, Vec3f> points;
  std::multiset<IdTri> triangles;
};

ById by_id(const Mesh& m) {
  ById r;
  for (std::size_t v = 0; v < m.positions.size(); ++v) r.points[std::int64_t(m.edge_keys[v])] = m.positions[v];
  for (const Tri& t : m.triangles)
    r.triangles.insert(canonical(std::int64_t(m.edge_keys[t[0]]), std::int64_t(m.edge_keys[t[1]]),
                                 std::int64_t(m.edge_keys[t[2]])));
  return r;
}

// Expects the owned parts of `pieces` to be `whole` exactly: each vertex owned once at the same
// bits, each triangle owned once; ghost triangles are whole triangles too.
void expect_fit(const ById& whole, const std::vector<ById>& owned, const std::vector<ById>& ghosts,
                const std::string& what) {
  std::map<std::int64_t, Vec3f> points;
  std::multiset<IdTri> triangles;
  std::size_t twice = 0, moved = 0;
  for (const ById& p : owned) {
    for (const auto& [id, x] : p.points) {
      const auto [it, fresh] = points.emplace(id, x);
      twice += !fresh;
    }
    triangles.insert(p.triangles.begin(), p.triangles.end());
  }
  EXPECT_EQ(twice, 0u) << what << ": vertices owned by two pieces";
  ASSERT_EQ(points.size(), whole.points.size()) << what;
  for (const auto& [id, x] : whole.points) {
    const auto it = points.find(id);
    if (it == points.end() || !same_bits(it->second, x)) ++moved;
  }
  EXPECT_EQ(moved, 0u) << what << ": vertices missing or not bit-identical";
  EXPECT_EQ(triangles.size(), whole.triangles.size()) << what;
  EXPECT_TRUE(triangles == whole.triangles) << what << ": triangles missing, doubled or different at the seams";
  for (const ById& g : ghosts)
    for (const IdTri& t : g.triangles) ASSERT_TRUE(whole.triangles.count(t)) << what << ": a ghost triangle the whole lacks";
}

std::vector<std::uint64_t> bricks_per_layer(const volume::Volume& v, float iso, const mc::Options& mo, int* first) {
  const mc::Frame f = mc::make_frame(v, iso, mo);
  *first = f.cells.min().z() & ~7;
  std::vector<std::uint64_t> layers(std::size_t((f.cells.max().z() - *first) / 8 + 1), 0);
  for (const openvdb::Coord& b : mc::BrickIndex(v).candidates(f)) ++layers[std::size_t((b.z() - *first) / 8)];
  return layers;
}

TEST(Slabs, BalancedByTheBricksThatCarrySurface) {
  const std::vector<std::uint64_t> layers = {0, 0, 10, 10, 0, 0, 10, 10, 0};
  auto bricks_of = [&](const dist::Slabs& s, int r) {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < layers.size(); ++i) n += s.owner_of_cell(16 + 8 * int(i)) == r ? layers[i] : 0;
    return n;
  };
  const dist::Slabs two = dist::balance_slabs(layers, 16, 2, 15);
  EXPECT_EQ(bricks_of(two, 0), 20u);
  EXPECT_EQ(bricks_of(two, 1), 20u);
  const dist::Slabs four = dist::balance_slabs(layers, 16, 4, 15);
  for (int r = 0; r < 4; ++r) EXPECT_EQ(bricks_of(four, r), 10u) << r;
  // Cuts between brick layers, ordered; each cell in exactly one slab, the open ends included.
  for (int r = 1; r < 4; ++r) {
    EXPECT_EQ((four.cuts[r] - 16) % 8, 0);
    EXPECT_LE(four.cuts[r - 1], four.cuts[r]);
  }
  EXPECT_EQ(four.owner_of_cell(INT_MIN), 0);
  EXPECT_EQ(four.owner_of_cell(INT_MAX - 1), 3);
  // A key's owner is its lower end's cell: key z counts from the key origin.
  EXPECT_EQ(four.owner_of_key(std::uint64_t(four.cuts[2] - 15) << 2), 2);
  EXPECT_EQ(four.owner_of_key(std::uint64_t(four.cuts[2] - 16) << 2), 1);
  // More ranks than layers with surface: every layer still has one owner, some slabs stay empty.
  const dist::Slabs many = dist::balance_slabs({5, 5, 5}, 0, 8, -1);
  std::set<int> owners;
  for (int z = 0; z < 24; ++z) owners.insert(many.owner_of_cell(z));
  EXPECT_EQ(owners.size(), 3u);
  // No surface at all: one slab holds everything.
  const dist::Slabs none = dist::balance_slabs({0, 0, 0}, 0, 3, -1);
  EXPECT_EQ(none.owner_of_cell(0), none.owner_of_cell(23));
  // The cells a rank extracts: its slab and the margin, clamped at the open ends.
  const auto [lo, hi] = four.extract_range(1, 4);
  EXPECT_EQ(lo, four.cuts[1] - 4);
  EXPECT_EQ(hi, four.cuts[2] + 3);
  EXPECT_EQ(four.extract_range(0, 4).first, INT_MIN);
  EXPECT_EQ(four.extract_range(3, 4).second, INT_MAX);
}

// Read in part, each rank also reads and builds its slab: a layer's blocks weigh in beside its
// surface, so the air above an object no longer all falls to the last rank.
TEST(Slabs, ReadInPartWeighsEachLayersBlocks) {
  const std::vector<std::uint64_t> surface = {50, 50, 0, 0, 0, 0, 0, 0}, leaves(8, 100);
  const std::vector<std::uint64_t> cost = dist::read_in_part_costs(surface, leaves, 100);
  EXPECT_EQ(cost[0], 50 * dist::kSurfaceBrickCost + 100 * dist::kBlockReadCost + 100 * dist::kLeafBuildCost);
  EXPECT_EQ(cost[7], 100 * dist::kBlockReadCost + 100 * dist::kLeafBuildCost);
  auto layers_of = [](const dist::Slabs& s, int r) {
    int n = 0;
    for (int i = 0; i < 8; ++i) n += s.owner_of_cell(8 * i) == r;
    return n;
  };
  const dist::Slabs by_surface = dist::balance_slabs(surface, 0, 2, -1);
  EXPECT_EQ(layers_of(by_surface, 0), 1);  // the surface split: rank 1 reads 7 layers of air
  const dist::Slabs by_cost = dist::balance_slabs(cost, 0, 2, -1);
  EXPECT_GE(layers_of(by_cost, 0), 3);
  EXPECT_LE(layers_of(by_cost, 0), 4);
}

// The pieces of 1..4 ranks, each cut from its own margin-limited extraction, are the whole
// extraction: on CT-like volumes (8-bit, voxels at the isovalue: snapping merges vertices at the
// seams), a thick-slice one, and on the device's mesher as well as the reference.
TEST(Pieces, FitTogetherIntoTheWholeExtraction) {
  for (const std::string name : {"torus_u8", "ellipsoid_u16_thick", "sphere_binary"}) {
    const datasets::CtCase c = datasets::ct_like_case(name, true);
    for (const bool device : {false, true}) {
      mc::Options mo;
      mo.keep_edge_keys = true;
      auto extract = [&](const mc::Options& o) {
        return device ? mc::extract(c.volume, c.iso, Device::default_device(), o)
                      : mc::extract_reference(c.volume, c.iso, o);
      };
      const Mesh whole_mesh = extract(mo);
      ASSERT_GT(whole_mesh.triangles.size(), 1000u) << name;
      const ById whole = by_id(whole_mesh);
      int first = 0;
      const std::vector<std::uint64_t> layers = bricks_per_layer(c.volume, c.iso, mo, &first);
      const int key_z = mc::make_frame(c.volume, c.iso, mo).key_origin.z();
      for (int n = 1; n <= 4; ++n) {
        const dist::Slabs slabs = dist::balance_slabs(layers, first, n, key_z);
        std::vector<ById> owned(n), ghosts(n);
        for (int r = 0; r < n; ++r) {
          mc::Options local = mo;
          std::tie(local.cells_min[2], local.cells_max[2]) = slabs.extract_range(r, dist::kExtractGhostCells);
          const dist::Piece p = dist::cut_piece(extract(local), slabs, r);
          ASSERT_TRUE(std::is_sorted(p.global_ids.begin(), p.global_ids.end()));
          for (std::size_t v = 0; v < p.global_ids.size(); ++v) {
            if (!p.point_ghost[v]) owned[r].points[p.global_ids[v]] = p.mesh.positions[v];
          }
          for (std::size_t t = 0; t < p.mesh.triangles.size(); ++t) {
            const Tri& tri = p.mesh.triangles[t];
            const IdTri id = canonical(p.global_ids[tri[0]], p.global_ids[tri[1]], p.global_ids[tri[2]]);
            EXPECT_EQ(p.cell_ghost[t] == 0, t < p.owned_triangles);
            (p.cell_ghost[t] ? ghosts[r] : owned[r]).triangles.insert(id);
          }
        }
        expect_fit(whole, owned, ghosts, name + (device ? " device" : " reference") + " at " + std::to_string(n) + " ranks");
      }
    }
  }
}

// ---- mpirun ----

const char* kMpirun = "/usr/bin/mpirun";
// OpenMPI refuses root (CI runs as root) unless told, and needs --oversubscribe for more ranks
// than this machine's cores.
const std::vector<std::string> kMpiEnv = {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                                          "OMPI_MCA_rmaps_base_oversubscribe=1"};

CliResult mpirun(int ranks, std::vector<std::string> args) {
  // -q: mpirun's own notices (a rank exited non-zero, ...) stay out of stderr.
  std::vector<std::string> all = {"-q", "-np", std::to_string(ranks), test::isocurv_exe()};
  all.insert(all.end(), args.begin(), args.end());
  CliResult r = test::run_program(kMpirun, all, 240, kMpiEnv);
  // OpenMPI's event library (libevent) may print "[warn] Epoll MOD(1) on fd N failed ..." when
  // ranks exit together on a loaded machine: mpirun's noise, not isocurv's output.
  std::istringstream in(r.err);
  std::string kept;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("[warn] Epoll", 0) != 0) kept += line + "\n";
  r.err = kept;
  return r;
}

#define REQUIRE_MPIRUN()                                                             \
  if (access(kMpirun, X_OK) != 0) GTEST_SKIP() << "no mpirun (openmpi-bin) on this machine"

// A .pvtp read back through VTK: every piece's points and triangles with their arrays.
struct ReadBack {
  ById owned, ghost;
  std::map<std::int64_t, std::map<std::string, float>> values;  // owned vertices' scalar arrays
  std::size_t pieces = 0;
};

ReadBack read_pvtp(const std::string& path, const std::vector<std::string>& arrays = {}) {
  ReadBack r;
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdatePiece(0, 1, 1);  // the whole surface, ghost ring included (else VTK drops it)
  r.pieces = std::size_t(reader->GetNumberOfPieces());
  vtkPolyData* poly = reader->GetOutput();
  EXPECT_TRUE(poly) << path;
  if (!poly) return r;
  auto* ids = vtkIdTypeArray::SafeDownCast(poly->GetPointData()->GetArray("vtkGlobalPointIds"));
  vtkDataArray* point_ghost = poly->GetPointData()->GetArray("vtkGhostType");
  vtkDataArray* cell_ghost = poly->GetCellData()->GetArray("vtkGhostType");
  EXPECT_TRUE(ids && point_ghost && cell_ghost)
      << path << ": global ids or ghost arrays missing (" << poly->GetPointData()->GetNumberOfArrays()
      << " point arrays, " << poly->GetNumberOfPoints() << " points)";
  if (!ids || !point_ghost || !cell_ghost) return r;
  EXPECT_EQ(poly->GetPointData()->GetGlobalIds(), ids) << "vtkGlobalPointIds is not the global ids attribute";
  std::multiset<std::int64_t> owned_ids;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    if (point_ghost->GetTuple1(i) != 0) continue;
    double x[3];
    poly->GetPoint(i, x);
    const std::int64_t id = ids->GetValue(i);
    owned_ids.insert(id);
    r.owned.points[id] = {float(x[0]), float(x[1]), float(x[2])};
    for (const std::string& a : arrays)
      if (vtkDataArray* d = poly->GetPointData()->GetArray(a.c_str())) r.values[id][a] = float(d->GetTuple1(i));
  }
  EXPECT_EQ(owned_ids.size(), r.owned.points.size()) << path << ": a vertex owned by two pieces";
  vtkCellArray* polys = poly->GetPolys();
  polys->InitTraversal();
  vtkIdType n = 0;
  const vtkIdType* p = nullptr;
  for (vtkIdType c = 0; polys->GetNextCell(n, p); ++c) {
    EXPECT_EQ(n, 3);
    const IdTri t = canonical(ids->GetValue(p[0]), ids->GetValue(p[1]), ids->GetValue(p[2]));
    (cell_ghost->GetTuple1(c) != 0 ? r.ghost : r.owned).triangles.insert(t);
  }
  return r;
}

// The single process's surface of `path`, by edge key (the device mesher, as the CLI runs it).
ById single_process(const std::string& path, float iso) {
  const volume::Volume v = volume::load(path);
  mc::Options mo;
  mo.keep_edge_keys = true;
  return by_id(mc::extract(v, iso, Device::default_device(), mo));
}

void expect_distributed_extract(const std::string& volume, const std::string& tag) {
  TempDir dir(tag);
  ById whole;
  nlohmann::json j1;  // one rank's summary, which the others' must repeat
  for (int n = 1; n <= 4; ++n) {
    const std::string out = (dir.path() / ("p" + std::to_string(n) + ".pvtp")).string();
    const CliResult r = mpirun(n, {"extract", volume, "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    const nlohmann::json j = test::parse_json(r.out, "extract --json");
    if (n == 1) {
      whole = single_process(volume, j["isovalue"].get<float>());
      j1 = j;
    }
    EXPECT_EQ(j["ranks"].size(), std::size_t(n));
    const ReadBack back = read_pvtp(out);
    EXPECT_EQ(back.pieces, std::size_t(n));
    expect_fit(whole, {back.owned}, {back.ghost}, tag + " at " + std::to_string(n) + " ranks");
    // The totals count each vertex, edge and triangle once.
    EXPECT_EQ(j["vertices"].get<std::size_t>(), whole.points.size());
    EXPECT_EQ(j["triangles"].get<std::size_t>(), whole.triangles.size());
    if (n == 1) continue;
    for (const char* key : {"components", "euler_characteristic", "boundary_edges", "watertight"})
      EXPECT_EQ(j[key], j1[key]) << tag << " at " << n << " ranks: " << key;
    EXPECT_NEAR(j["area"].get<double>(), j1["area"].get<double>(), 1e-9 * j1["area"].get<double>());
    EXPECT_NEAR(j["enclosed_volume"].get<double>(), j1["enclosed_volume"].get<double>(),
                1e-9 * std::abs(j1["enclosed_volume"].get<double>()) + 1e-9);
  }
}

TEST(Mpirun, ExtractAnalyticVolumeAtOneToFourRanks) {
  REQUIRE_MPIRUN();
  expect_distributed_extract(test::dataset("gyroid"), "gyroid");
}

TEST(Mpirun, ExtractRealVolumesAtOneToFourRanks) {
  REQUIRE_MPIRUN();
  expect_distributed_extract(std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol", "lobster");
  expect_distributed_extract(std::string(test_paths::shared_datasets()) + "/headmr/HeadMRVolume.mhd", "headmr");
}

// Raw, NRRD, MetaImage and NIfTI files are read in part (each rank an even share, then its
// slab): the whole volume's statistics are reduced over the ranks, so the default isovalue is the
// single process's to the bit, and the surface is the same.
TEST(Mpirun, UncompressedFilesAreReadInPartWithTheSingleProcessIsovalue) {
  REQUIRE_MPIRUN();
  TempDir dir("in_part");
  const std::string raw = std::string(test_paths::shared_datasets()) + "/lobster/lobster_301x324x56_uint8.raw";
  const std::string nhdr = (dir.path() / "lobster.nhdr").string();
  test::write_file(nhdr, "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 301 324 56\nencoding: raw\n"
                         "spacings: 1 1 1.4\ndata file: " + raw + "\n\n");
  const std::string voxels = test::read_file(raw);
  const std::string mha = (dir.path() / "lobster.mha").string();
  test::write_file(mha, "NDims = 3\nDimSize = 301 324 56\nElementType = MET_UCHAR\nElementSpacing = 1 1 1.4\n"
                        "ElementDataFile = LOCAL\n" + voxels);
  std::string nii(352, '\0');  // NIfTI-1: uint8, pixdim 1 1 1.4, the voxels at 352
  auto put = [&](std::size_t at, auto value) { std::memcpy(&nii[at], &value, sizeof value); };
  put(0, std::int32_t(348));
  const std::int16_t dim[8] = {3, 301, 324, 56, 1, 1, 1, 1};
  std::memcpy(&nii[40], dim, sizeof dim);
  put(70, std::int16_t(2));  // uint8
  put(72, std::int16_t(8));
  const float pixdim[4] = {1, 1, 1, 1.4f};
  std::memcpy(&nii[76], pixdim, sizeof pixdim);
  put(108, 352.0f);  // vox_offset
  std::memcpy(&nii[344], "n+1", 4);
  const std::string nifti = (dir.path() / "lobster.nii").string();
  test::write_file(nifti, nii + voxels);
  for (const std::string& volume : {raw, nhdr, mha, nifti}) {
    const CliResult single = test::run_isocurv({"extract", volume, "-o", (dir.path() / "s.vtp").string(), "--json"});
    ASSERT_TRUE(single.ok()) << single.describe();
    const float iso = test::parse_json(single.out, "extract")["isovalue"].get<float>();
    const ById whole = single_process(volume, iso);
    for (int n : {2, 3}) {
      const std::string out = (dir.path() / ("p" + std::to_string(n) + ".pvtp")).string();
      const CliResult r = mpirun(n, {"extract", volume, "-o", out, "--json"});
      ASSERT_TRUE(r.ok()) << r.describe();
      const nlohmann::json j = test::parse_json(r.out, "extract --json");
      EXPECT_EQ(j["read"].get<std::string>().rfind("in part", 0), 0u) << j["read"];
      EXPECT_EQ(j["isovalue"].get<float>(), iso) << volume << ": the default isovalue from the reduced histogram";
      for (const auto& rank : j["ranks"]) EXPECT_GT(rank["peak_memory_bytes"].get<double>(), 0);
      const ReadBack back = read_pvtp(out);
      expect_fit(whole, {back.owned}, {back.ghost}, volume + " at " + std::to_string(n) + " ranks");
    }
  }
}

// The volume estimator per piece (the default): every array of every vertex bit-identical to the
// single process's (matched by position), at 1-4 ranks, on real volumes (a CT read whole; an MRI
// read in part), a binary mask (its smoothed-surface point, the binary scale) read in part, and
// a float gyroid whose grid coordinates are not whole numbers (.vdb, read whole). Each volume at
// two rank counts, each count on two volumes (every count on every volume took a minute on 2 cores).
TEST(Mpirun, VolumeEstimatorIsTheSingleProcessToTheBit) {
  REQUIRE_MPIRUN();
  TempDir dir("volume_estimator");
  const std::string torus = (dir.path() / "torus_48x48x40_uint8.raw").string();
  {
    std::string mask(48 * 48 * 40, '\0');
    for (int z = 0; z < 40; ++z)
      for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 48; ++x) {
          const double px = x - 23.7, py = y - 23.6, pz = z - 19.8, q = std::hypot(px, py) - 13;
          mask[std::size_t((z * 48 + y) * 48 + x)] = q * q + pz * pz < 5.0 * 5.0 ? 1 : 0;
        }
    test::write_file(torus, mask);
  }
  const std::string shared = test_paths::shared_datasets();
  const std::vector<std::string> arrays = {"H", "K", "k1", "k2", "AO", "Scale", "Unreliable", "Boundary"};
  const std::vector<std::pair<std::string, std::vector<int>>> cases = {
      {shared + "/lobster/lobster.vol", {1, 3}}, {shared + "/headmr/HeadMRVolume.mhd", {2, 4}},
      {torus, {1, 4}}, {test::dataset("gyroid"), {2, 3}}};
  for (const auto& [volume, rank_counts] : cases) {
    const std::string single = (dir.path() / "single.vtp").string();
    const CliResult one = test::run_isocurv({"curvature", volume, "-o", single, "--quiet"});
    ASSERT_TRUE(one.ok()) << one.describe();
    const io::MeshFile s = io::read_mesh(single);
    ASSERT_TRUE(s.field.has_value());
    std::map<std::array<float, 3>, std::size_t> at;
    for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) at[s.mesh.positions[v]] = v;
    const std::map<std::string, const std::vector<float>*> single_arrays = [&] {
      std::map<std::string, const std::vector<float>*> m = {{"H", &s.field->H}, {"K", &s.field->K},
                                                            {"k1", &s.field->k1}, {"k2", &s.field->k2},
                                                            {"AO", &s.field->ao}};
      for (const auto& [name, values] : s.field->extra) m[name] = &values;
      return m;
    }();
    for (int n : rank_counts) {
      const std::string out = (dir.path() / ("v" + std::to_string(n) + ".pvtp")).string();
      const CliResult r = mpirun(n, {"curvature", volume, "-o", out, "--quiet"});
      ASSERT_TRUE(r.ok()) << r.describe();
      const ReadBack back = read_pvtp(out, arrays);
      ASSERT_EQ(back.values.size(), s.mesh.positions.size()) << volume << " at " << n << " ranks";
      std::size_t off = 0, compared = 0;
      for (const auto& [id, values] : back.values) {
        const auto v = at.find(back.owned.points.at(id));
        ASSERT_NE(v, at.end()) << volume << ": a vertex the single process does not have";
        for (const auto& [name, value] : values) {
          const float ref = name == "Unreliable" ? float(s.field->unreliable[v->second])
                            : name == "Boundary" ? float(s.field->boundary[v->second])
                                                 : (*single_arrays.at(name))[v->second];
          off += std::memcmp(&value, &ref, sizeof value) != 0;
          ++compared;
        }
      }
      EXPECT_GE(compared, s.mesh.positions.size() * 7) << volume << ": arrays missing";
      EXPECT_EQ(off, 0u) << volume << " at " << n << " ranks: values differ from the single process's";
    }
  }
}

// A mesh estimator per piece: within 1e-6 of the single process's at every rank count (its
// neighbourhood lies inside the margin).
TEST(Mpirun, MeshEstimatorsMatchAcrossRankCounts) {
  REQUIRE_MPIRUN();
  TempDir dir("curvature");
  const std::string volume = std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol";
  for (const std::string estimator : {"rusinkiewicz", "quadric"}) {
    std::map<std::int64_t, std::map<std::string, float>> one;
    for (int n : {1, 2, 4}) {
      const std::string out = (dir.path() / (estimator + std::to_string(n) + ".pvtp")).string();
      const CliResult r = mpirun(n, {"curvature", volume, "-o", out, "--estimator", estimator, "--quiet"});
      ASSERT_TRUE(r.ok()) << r.describe();
      const ReadBack back = read_pvtp(out, {"H", "K", "k1"});
      ASSERT_FALSE(back.values.empty());
      if (n == 1) {
        one = back.values;
        continue;
      }
      ASSERT_EQ(back.values.size(), one.size());
      std::size_t off = 0;
      double worst = 0;
      for (const auto& [id, arrays] : back.values) {
        for (const auto& [name, value] : arrays) {
          const float ref = one.at(id).at(name);
          worst = std::max(worst, std::abs(double(value) - ref) / std::max(1e-3, std::abs(double(ref))));
          off += !std::isfinite(value);
        }
      }
      EXPECT_EQ(off, 0u) << estimator << " at " << n << " ranks: values not finite";
      EXPECT_LE(worst, 1e-6) << estimator << " at " << n << " ranks";
    }
  }
}

TEST(Mpirun, GatherWritesOneMeshLikeTheSingleProcess) {
  REQUIRE_MPIRUN();
  TempDir dir("gather");
  const std::string volume = test::dataset("gyroid");
  const std::string single = (dir.path() / "single.vtp").string(), gathered = (dir.path() / "gathered.vtp").string();
  ASSERT_TRUE(test::run_isocurv({"curvature", volume, "-o", single, "--estimator", "rusinkiewicz", "--quiet"}).ok());
  const CliResult r = mpirun(3, {"curvature", volume, "-o", gathered, "--gather", "--estimator", "rusinkiewicz", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const io::MeshFile a = io::read_mesh(single), b = io::read_mesh(gathered);
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
  ASSERT_EQ(a.mesh.triangles.size(), b.mesh.triangles.size());
  // The same vertices (the gathered ones ordered by global id) with the same curvature.
  std::map<std::array<float, 3>, float> h;
  for (std::size_t v = 0; v < a.mesh.positions.size(); ++v) h[a.mesh.positions[v]] = a.field->H[v];
  std::size_t off = 0;
  for (std::size_t v = 0; v < b.mesh.positions.size(); ++v) {
    const auto it = h.find(b.mesh.positions[v]);
    off += it == h.end() || std::abs(it->second - b.field->H[v]) > 1e-6f * std::max(1.0f, std::abs(it->second));
  }
  EXPECT_EQ(off, 0u);
  // Without --gather or a .pvtp, several ranks would write one file: refused.
  const CliResult refused = mpirun(2, {"extract", volume, "-o", (dir.path() / "x.vtp").string()});
  test::expect_clean_failure(refused, ".pvtp");
}

// Many files: the inputs go to the ranks as they become free, one summary.json lists every entry
// in input order with the rank that made it, and the counts are the single process's.
TEST(Mpirun, BatchHandsInputsToRanksWithOneSummary) {
  REQUIRE_MPIRUN();
  TempDir dir("batch");
  const std::string bad = (dir.path() / "bad.nrrd").string();
  test::write_file(bad, "NRRD0004\ntype: float\n");  // no sizes: fails to load
  std::vector<std::string> inputs = {test::dataset("gyroid"), test::dataset("sphere"), bad,
                                     test::dataset("torus"), test::dataset("ellipsoid")};
  std::vector<std::string> one = {"extract"}, many = {"extract"};
  one.insert(one.end(), inputs.begin(), inputs.end());
  many.insert(many.end(), inputs.begin(), inputs.end());
  for (const std::string& a : std::vector<std::string>{"-o", (dir.path() / "one").string(), "--quiet"}) one.push_back(a);
  for (const std::string& a : std::vector<std::string>{"-o", (dir.path() / "many").string(), "--quiet"}) many.push_back(a);
  const CliResult single = test::run_isocurv(one, 240);
  const CliResult ranks = mpirun(3, many);
  EXPECT_EQ(single.exit_code, 1) << single.describe();  // the bad input fails, the others are written
  EXPECT_EQ(ranks.exit_code, 1) << ranks.describe();
  const nlohmann::json a = test::parse_json(test::read_file((dir.path() / "one" / "summary.json").string()), "summary");
  const nlohmann::json b = test::parse_json(test::read_file((dir.path() / "many" / "summary.json").string()), "summary");
  ASSERT_EQ(b["entries"].size(), inputs.size());
  EXPECT_EQ(b["ranks"], 3);
  EXPECT_EQ(b["ok"], 4);
  EXPECT_EQ(b["failed"], 1);
  std::set<int> used;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const nlohmann::json& e = b["entries"][i];
    EXPECT_EQ(e["input"], inputs[i]) << "entries out of input order";
    EXPECT_EQ(e["status"], a["entries"][i]["status"]);
    EXPECT_EQ(e.value("vertices", -1), a["entries"][i].value("vertices", -1)) << inputs[i];
    EXPECT_EQ(e.value("triangles", -1), a["entries"][i].value("triangles", -1)) << inputs[i];
    used.insert(e["rank"].get<int>());
  }
  EXPECT_EQ(used.size(), 3u) << "every rank draws an input before working on any";
  for (const char* stem : {"gyroid", "sphere", "torus", "ellipsoid"})
    EXPECT_TRUE(fs::exists(dir.path() / "many" / stem / (std::string(stem) + ".vtp"))) << stem;
  EXPECT_FALSE(fs::exists(dir.path() / "many" / "bad")) << "a failed input's empty folder is removed";
  // One input under several ranks: lines would run once per rank; refused.
  test::expect_clean_failure(mpirun(2, {"lines", test::dataset("sphere"), "-o", (dir.path() / "l.svg").string()}),
                             "several inputs");
  test::expect_clean_failure(mpirun(2, {"info", test::dataset("sphere")}), "mpirun");
}

// One volume, finished on rank 0: check reports what the single process reports, run writes its
// mesh, picture and stats.json from rank 0 with the single process's counts.
TEST(Mpirun, CheckAndRunFinishOnRankZero) {
  REQUIRE_MPIRUN();
  TempDir dir("finish");
  const std::string volume = std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol";
  const CliResult single = test::run_isocurv({"check", volume, "--json"}, 120);
  const CliResult ranks = mpirun(3, {"check", volume, "--json"});
  ASSERT_TRUE(single.ok()) << single.describe();
  ASSERT_TRUE(ranks.ok()) << ranks.describe();
  const nlohmann::json a = test::parse_json(single.out, "check"), b = test::parse_json(ranks.out, "check under mpirun");
  for (const char* key : {"vertices", "triangles", "edges", "boundary_edges", "non_manifold_edges", "misoriented_edges",
                          "duplicate_vertices", "unreferenced_vertices", "degenerate_triangles", "components",
                          "euler_characteristic", "genus", "closed_components", "problems_found"})
    EXPECT_EQ(a[key], b[key]) << key;
  EXPECT_NEAR(a["area"].get<double>(), b["area"].get<double>(), 1e-9 * a["area"].get<double>());

  const std::string gyroid = test::dataset("gyroid");
  const std::string one = (dir.path() / "one").string(), many = (dir.path() / "many").string();
  ASSERT_TRUE(test::run_isocurv({"run", gyroid, "-o", one, "--estimator", "rusinkiewicz", "--quiet"}, 120).ok());
  const CliResult run = mpirun(2, {"run", gyroid, "-o", many, "--estimator", "rusinkiewicz", "--quiet"});
  ASSERT_TRUE(run.ok()) << run.describe();
  for (const char* file : {"gyroid.vtp", "gyroid.png", "stats.json"})
    EXPECT_TRUE(fs::exists(fs::path(many) / file)) << file;
  const nlohmann::json sa = test::parse_json(test::read_file(one + "/stats.json"), "stats");
  const nlohmann::json sb = test::parse_json(test::read_file(many + "/stats.json"), "stats");
  EXPECT_EQ(sa["vertices"], sb["vertices"]);
  EXPECT_EQ(sa["triangles"], sb["triangles"]);
}

// Label surfaces are not divided among ranks: `run --labels` is refused under several ranks like
// extract and curvature (every rank computed and wrote all of them).
TEST(Mpirun, LabelsAreRefusedByEveryCommandThatTakesThem) {
  REQUIRE_MPIRUN();
  TempDir dir("labels_ranks");
  const std::string volume = std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol";
  for (const char* command : {"run", "extract", "curvature"}) {
    const std::string out = (dir.path() / (std::string(command) + "_out")).string();
    const std::string target = std::string(command) == "run" ? out : out + ".pvtp";
    const CliResult r = mpirun(2, {command, volume, "--labels", "-o", target, "--quiet"});
    EXPECT_EQ(r.exit_code, 1) << command << ": " << r.describe();
    EXPECT_NE(r.err.find("do not run distributed"), std::string::npos) << command << ": " << r.err;
    EXPECT_FALSE(fs::exists(target)) << command;
  }
}

// A rank that cannot write its piece stops every rank: one line (from rank 0, naming the rank),
// status 1, no .pvtp and no new piece.
TEST(Mpirun, AFailingRankStopsAllWithOneLineAndNoPvtp) {
  REQUIRE_MPIRUN();
  TempDir dir("failure");
  const std::string out = (dir.path() / "out.pvtp").string();
  fs::create_directories(dir.path() / "out" / "out_2.vtp");  // rank 2's piece cannot be written
  const CliResult r = mpirun(4, {"extract", test::dataset("gyroid"), "-o", out});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  ASSERT_EQ(r.err_lines().size(), 1u) << r.describe();
  EXPECT_NE(r.err.find("rank 2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (int k : {0, 1, 3}) EXPECT_FALSE(fs::exists(dir.path() / "out" / ("out_" + std::to_string(k) + ".vtp")));
  // A failure after the pieces' folder was made (here: no surface to estimate curvature on) takes
  // the new, empty folder away again; it once stayed behind as an empty `fresh/`.
  const std::string fresh = (dir.path() / "fresh.pvtp").string();
  const CliResult f = mpirun(2, {"curvature", test::dataset("sphere"), "--iso", "1e9", "-o", fresh});
  EXPECT_EQ(f.exit_code, 1) << f.describe();
  EXPECT_FALSE(fs::exists(dir.path() / "fresh")) << "an empty pieces folder stayed";
  EXPECT_FALSE(fs::exists(fresh));
}

}  // namespace
}  // namespace isocurv
