// The real volumes of ../shared/datasets (README facts: dimensions, value ranges, grid classes,
// isovalues); skipped when the folder is absent.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "volume/load.h"

using namespace isocurv::volume;

namespace {

struct Expect {
  const char* file;
  int nx, ny, nz;
  double min, max;         ///< exact value range (README), or NaN to check [0, 255] bounds only
  double iso_lo, iso_hi;   ///< the suggested isovalue must fall in [iso_lo, iso_hi]
  const char* grid_class;  ///< "unknown" for dense files
  double sx, sy, sz;       ///< spacing
};

// Shown by GoogleTest (and so in CTest's test names) instead of the struct's bytes.
void PrintTo(const Expect& e, std::ostream* os) { *os << e.file; }

constexpr double kAny = std::numeric_limits<double>::quiet_NaN();

const Expect kFiles[] = {
    {"aa_cubesphere/cubesphere-128-aa-l0_1.vol", 128, 128, 128, 0, 255, 120, 135, "unknown", 1, 1, 1},
    {"aa_cubesphere/cubesphere-256-aa-l0_1.vol", 256, 256, 256, 0, 255, 120, 135, "unknown", 1, 1, 1},
    {"aa_dragon/dragon-128-aa-l0_1.vol", 128, 128, 128, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_dragon/dragon-256-aa-l0_1.vol", 256, 256, 256, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_octaflower/octa-flower17k-128-aa-l0_1.vol", 128, 128, 128, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_octaflower/octa-flower17k-256-aa-l0_1.vol", 256, 256, 256, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_octaflower/octa-flower17k-512-aa-l0_1.vol", 512, 512, 512, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_torusknot/Torus_knot-129.vol", 130, 130, 130, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"aa_torusknot/Torus_knot-129-aa-l0_1.vol", 130, 130, 130, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"aa_torusknot/Torus_knot-257-aa-l0_1.vol", 258, 258, 258, 0, 255, 115, 135, "unknown", 1, 1, 1},
    {"al100/Al.100.vol", 100, 100, 100, 0, 1, 0.5, 0.5, "unknown", 1, 1, 1},
    {"bolt/bolt_70x123x66_uint8.raw", 70, 123, 66, kAny, kAny, 100, 140, "unknown", 1, 1, 1},
    {"bolt/bolt.slc", 70, 123, 66, kAny, kAny, 100, 140, "unknown", 1, 1, 1},
    {"brainweb_t1/t1_icbm_normal_1mm_pn0_rf0_180x216x180_uint8_1x1.bin-gz", 180, 216, 180, kAny, kAny, 66, 70, "unknown", 1, 1, 1},
    {"frogtissue/frogtissue.mhd", 500, 470, 136, 0, 29, 0, 29, "unknown", 1, 1, 1.5},
    {"headmr/HeadMRVolume.mhd", 48, 62, 42, kAny, kAny, 40, 44, "unknown", 4, 4, 4},
    {"headsq/headsq_64x64x93_int16le.raw", 64, 64, 93, 0, 3926, 0, 3926, "unknown", 1, 1, 1},
    {"hydrogen_orbital/hydrogen_orbital_64x64x64_float32le.raw", 64, 64, 64, 0, 1, 0, 1, "unknown", 1, 1, 1},
    {"hydrogen_orbital/hydrogen.vti", 64, 64, 64, 0, 1, 0, 1, "unknown", 1, 1, 1},
    {"ironprot/ironprot_68x68x68_uint8.raw", 68, 68, 68, kAny, kAny, 0, 255, "unknown", 1, 1, 1},
    {"ironprot/ironProt.vtk", 68, 68, 68, kAny, kAny, 0, 255, "unknown", 1, 1, 1},
    {"lidc2_ct/LIDC2_256x256x133_uint8.raw.gz", 256, 256, 133, 0, 255, 58, 62, "unknown", 1, 1, 1},
    {"lobster/lobster_301x324x56_uint8.raw", 301, 324, 56, kAny, kAny, 0, 255, "unknown", 1, 1, 1},
    {"lobster/lobster.vol", 301, 324, 56, kAny, kAny, 0, 255, "unknown", 1, 1, 1},
    {"mni152_t1/avg152T1_91x109x91_uint8.raw", 91, 109, 91, kAny, kAny, 96, 100, "unknown", 1, 1, 1},
    {"mni152_t1/avg152T1_RL_nifti.nii.gz", 91, 109, 91, kAny, kAny, 96, 100, "unknown", 2, 2, 2},
    {"nucleon/nucleon_41x41x41_uint8.raw", 41, 41, 41, kAny, kAny, 78, 82, "unknown", 1, 1, 1},
    {"nut/nut_68x41x59_uint8.raw", 68, 41, 59, kAny, kAny, 100, 140, "unknown", 1, 1, 1},
    {"nut/nut.slc", 68, 41, 59, kAny, kAny, 100, 140, "unknown", 1, 1, 1},
    {"vdb_cube/cube.vdb", 225, 225, 225, kAny, kAny, 0, 0, "level set", 0.05, 0.05, 0.05},
    {"vdb_smoke/smoke.vdb", 111, 222, 112, kAny, kAny, 0, 5.72, "fog volume", 0.47619, 0.47619, 0.47619},
    {"vdb_sphere/sphere.vdb", 125, 125, 125, kAny, kAny, 0, 0, "level set", 0.05, 0.05, 0.05},
    {"vg_buddha/buddha-128.vol", 128, 128, 128, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_buddha/buddha-256.vol", 256, 256, 256, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_bunny/bunny-64.vol", 64, 64, 64, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_bunny/bunny-128.vol", 128, 128, 128, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_bunny/bunny-256.vol", 256, 256, 256, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_dragon/dragon-128.vol", 128, 128, 128, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_dragon/dragon-256.vol", 256, 256, 256, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_dragon/dragon-512.vol", 512, 512, 512, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_octaflower/octa-flower17k-128.vol", 128, 128, 128, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_octaflower/octa-flower17k-256.vol", 256, 256, 256, 0, 255, 127.5, 127.5, "unknown", 1, 1, 1},
    {"vg_spot/spot-128.vol", 129, 129, 129, 0, 128, 64, 64, "unknown", 1, 1, 1},
    {"vg_spot/spot-256.vol", 257, 257, 257, 0, 128, 64, 64, "unknown", 1, 1, 1},
};

std::string dataset(const std::string& rel) { return std::string(isocurv::test_paths::shared_datasets()) + "/" + rel; }

class VolumeRealDataset : public ::testing::TestWithParam<Expect> {};

}  // namespace

TEST_P(VolumeRealDataset, LoadsWithReadmeFacts) {
  const Expect& e = GetParam();
  const std::string path = dataset(e.file);
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const auto t0 = std::chrono::steady_clock::now();
  const Volume v = load(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  RecordProperty("load_seconds", std::to_string(seconds));
  EXPECT_EQ(v.domain.dim(), openvdb::Coord(e.nx, e.ny, e.nz));
  EXPECT_EQ(v.grid_class, e.grid_class);
  EXPECT_EQ(v.inside, std::string(e.grid_class) == "level set" ? Inside::Below : Inside::Above);
  EXPECT_EQ(v.dense, std::string(e.grid_class) == "unknown");
  if (!std::isnan(e.min)) {
    EXPECT_EQ(v.stats.min, e.min);
    EXPECT_EQ(v.stats.max, e.max);
  } else if (v.dense) {
    EXPECT_GE(v.stats.min, 0);
    EXPECT_LE(v.stats.max, 255);
    EXPECT_LT(v.stats.min, v.stats.max);
  }
  EXPECT_GE(v.stats.suggested_isovalue, e.iso_lo);
  EXPECT_LE(v.stats.suggested_isovalue, e.iso_hi);
  EXPECT_EQ(v.stats.nan_count + v.stats.inf_count, 0u);
  EXPECT_NEAR(v.spacing().x(), e.sx, 1e-5);
  EXPECT_NEAR(v.spacing().y(), e.sy, 1e-5);
  EXPECT_NEAR(v.spacing().z(), e.sz, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(All, VolumeRealDataset, ::testing::ValuesIn(kFiles), [](const auto& info) {
  std::string name = info.param.file;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

namespace {

/// Loads two files holding the same voxels and compares them; `index_of` maps a voxel of `a`
/// to the corresponding index of `b`.
void expect_same_voxels(const std::string& a_file, const std::string& b_file,
                        const std::function<openvdb::Coord(const openvdb::Coord&)>& index_of = {}) {
  const std::string a_path = dataset(a_file), b_path = dataset(b_file);
  if (!std::filesystem::exists(a_path) || !std::filesystem::exists(b_path)) GTEST_SKIP() << "datasets not present";
  const Volume a = load(a_path), b = load(b_path);
  ASSERT_EQ(a.domain, b.domain);
  auto ra = a.grid->getConstAccessor();
  auto rb = b.grid->getConstAccessor();
  std::uint64_t differ = 0;
  for (auto it = a.domain.begin(); it; ++it) {
    const openvdb::Coord c = *it;
    differ += ra.getValue(c) != rb.getValue(index_of ? index_of(c) : c);
  }
  EXPECT_EQ(differ, 0u) << a_file << " vs " << b_file;
}

}  // namespace

TEST(VolumeRealDatasetPairs, SameVoxelsInEveryFormat) {
  expect_same_voxels("ironprot/ironprot_68x68x68_uint8.raw", "ironprot/ironProt.vtk");
  expect_same_voxels("hydrogen_orbital/hydrogen_orbital_64x64x64_float32le.raw", "hydrogen_orbital/hydrogen.vti");
  expect_same_voxels("lobster/lobster_301x324x56_uint8.raw", "lobster/lobster.vol");
  expect_same_voxels("bolt/bolt_70x123x66_uint8.raw", "bolt/bolt.slc");
  expect_same_voxels("nut/nut_68x41x59_uint8.raw", "nut/nut.slc");
}

TEST(VolumeRealDatasetPairs, NiftiSformGivesWorldSpace) {
  const std::string nii = dataset("mni152_t1/avg152T1_RL_nifti.nii.gz");
  if (!std::filesystem::exists(nii)) GTEST_SKIP() << "datasets not present";
  // sform (code 4): srow = diag(2, 2, 2) with translation (-90, -126, -72).
  const Volume v = load(nii);
  EXPECT_NEAR(v.origin().x(), -90, 1e-9);
  EXPECT_NEAR(v.origin().y(), -126, 1e-9);
  EXPECT_NEAR(v.origin().z(), -72, 1e-9);
  const openvdb::Vec3d far = v.grid->transform().indexToWorld(openvdb::Vec3d(90, 108, 90));
  EXPECT_NEAR(far.x(), 90, 1e-9);
  EXPECT_NEAR(far.y(), 90, 1e-9);
  EXPECT_NEAR(far.z(), 108, 1e-9);
  expect_same_voxels("mni152_t1/avg152T1_91x109x91_uint8.raw", "mni152_t1/avg152T1_RL_nifti.nii.gz");
}
