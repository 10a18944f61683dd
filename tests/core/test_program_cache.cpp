// The on-disk OpenCL program cache (core/program_cache.h): a second build loads the stored
// binary, a corrupt, truncated or foreign entry is rebuilt (never trusted), an unwritable folder
// only turns the cache off, and programs from the cache compute what freshly compiled ones do.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/program_cache.h"

namespace isocurv {
namespace {

namespace fs = std::filesystem;

// Work-group size 4 on purpose: the kernel's result must not depend on how items are grouped.
constexpr std::size_t kLocal = 4;
constexpr std::size_t kItems = 64;

const char* kSource = R"CL(
#define SCALE 3.0f
kernel void affine(global const float* in, global float* out) {
  const size_t i = get_global_id(0);
  out[i] = SCALE * in[i] + (float)get_local_id(0) * 0.0f + 1.0f;
}
)CL";

/// Runs `affine` from a program built by `dev`, on 0..kItems-1.
std::vector<float> run_affine(Device& dev, const std::string& options = "") {
  cl::Program& p = dev.program("cache_test", kSource, options);
  cl::Kernel k(p, "affine");
  std::vector<float> in(kItems), out(kItems, -1.0f);
  for (std::size_t i = 0; i < kItems; ++i) in[i] = float(i) * 0.25f;
  cl::Buffer a(dev.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, kItems * sizeof(float),
               in.data());
  cl::Buffer b(dev.context(), CL_MEM_WRITE_ONLY, kItems * sizeof(float));
  k.setArg(0, a);
  k.setArg(1, b);
  dev.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(kItems), cl::NDRange(kLocal));
  dev.queue().enqueueReadBuffer(b, CL_TRUE, 0, kItems * sizeof(float), out.data());
  return out;
}

/// The C++ reference of `affine`.
std::vector<float> reference_affine() {
  std::vector<float> out(kItems);
  for (std::size_t i = 0; i < kItems; ++i) out[i] = 3.0f * (float(i) * 0.25f) + 1.0f;
  return out;
}

class ProgramCache : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isocurv_program_cache_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    setenv("ISOCURV_CACHE_DIR", dir_.c_str(), 1);
    set_program_cache_warnings(false);
  }
  void TearDown() override {
    unsetenv("ISOCURV_CACHE_DIR");
    fs::remove_all(dir_);
  }
  /// The cache_test entries in the folder.
  std::vector<fs::path> entries() const {
    std::vector<fs::path> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir_, ec))
      if (e.path().filename().string().rfind("cache_test-", 0) == 0) out.push_back(e.path());
    return out;
  }
  fs::path dir_;
};

TEST_F(ProgramCache, SecondBuildLoadsTheStoredBinary) {
  const ProgramBuildStats s0 = program_build_stats();
  const std::vector<float> fresh = run_affine(*Device::open());
  const ProgramBuildStats s1 = program_build_stats();
  EXPECT_EQ(s1.compiled, s0.compiled + 1);
  EXPECT_EQ(s1.from_cache, s0.from_cache);
  ASSERT_EQ(entries().size(), 1u);
  const std::vector<float> cached =
      run_affine(*Device::open());  // a new device: a new process's view
  const ProgramBuildStats s2 = program_build_stats();
  EXPECT_EQ(s2.compiled, s1.compiled);
  EXPECT_EQ(s2.from_cache, s1.from_cache + 1);
  EXPECT_EQ(fresh, reference_affine());
  EXPECT_EQ(cached, fresh);
}

TEST_F(ProgramCache, OtherBuildOptionsAreAnotherEntry) {
  run_affine(*Device::open());
  run_affine(*Device::open(), "-DUNUSED_OPTION=1");
  EXPECT_EQ(entries().size(), 2u);
}

TEST_F(ProgramCache, CorruptOrTruncatedEntryIsRebuilt) {
  run_affine(*Device::open());
  ASSERT_EQ(entries().size(), 1u);
  const fs::path entry = entries()[0];
  const auto size = fs::file_size(entry);
  for (int damage = 0; damage < 3; ++damage) {
    if (damage == 0) {  // one byte of the binary flipped
      std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
      f.seekg(std::streamoff(size / 2));
      char c = 0;
      f.read(&c, 1);
      f.seekp(std::streamoff(size / 2));
      c = char(c ^ 0x5a);
      f.write(&c, 1);
    } else if (damage == 1) {  // cut short
      fs::resize_file(entry, size / 3);
    } else {  // not an entry at all
      std::ofstream(entry, std::ios::binary | std::ios::trunc) << "garbage";
    }
    const ProgramBuildStats before = program_build_stats();
    EXPECT_EQ(run_affine(*Device::open()), reference_affine()) << "damage " << damage;
    const ProgramBuildStats after = program_build_stats();
    EXPECT_EQ(after.rejected, before.rejected + 1) << "damage " << damage;
    EXPECT_EQ(after.compiled, before.compiled + 1) << "damage " << damage;
    EXPECT_EQ(fs::file_size(entry), size) << "the rebuilt entry is written again";
    run_affine(*Device::open());
    EXPECT_EQ(program_build_stats().from_cache, after.from_cache + 1) << "damage " << damage;
  }
}

TEST_F(ProgramCache, EntryForAnotherKeyIsNotTrusted) {
  detail::ProgramKey a{"cache_test", detail::hash_hex("source a"), "-O", "p", "d", "1.0"};
  detail::ProgramKey b = a;
  b.driver = "2.0";
  const std::vector<unsigned char> bin = {1, 2, 3, 4, 5};
  ASSERT_TRUE(detail::store_program_binary(dir_.string(), a, bin));
  bool rejected = false;
  EXPECT_EQ(detail::load_program_binary(dir_.string(), a, &rejected), bin);
  EXPECT_FALSE(rejected);
  // b names another file; copied over it, a's entry must still not pass as b's.
  fs::copy_file(dir_ / a.file_name(), dir_ / b.file_name());
  EXPECT_FALSE(detail::load_program_binary(dir_.string(), b, &rejected).has_value());
  EXPECT_TRUE(rejected);
}

TEST_F(ProgramCache, UnwritableFolderOnlyTurnsTheCacheOff) {
  fs::create_directories(dir_);
  const fs::path file = dir_ / "a_file";
  std::ofstream(file) << "x";
  setenv("ISOCURV_CACHE_DIR", (file / "cache").c_str(), 1);  // below a regular file: cannot exist
  const ProgramBuildStats before = program_build_stats();
  EXPECT_EQ(run_affine(*Device::open()), reference_affine());
  EXPECT_EQ(run_affine(*Device::open()), reference_affine());
  const ProgramBuildStats after = program_build_stats();
  EXPECT_EQ(after.compiled, before.compiled + 2);
  EXPECT_EQ(after.from_cache, before.from_cache);
}

TEST_F(ProgramCache, EmptyVariableTurnsTheCacheOff) {
  setenv("ISOCURV_CACHE_DIR", "", 1);
  EXPECT_EQ(program_cache_dir(), "");
  run_affine(*Device::open());
  EXPECT_FALSE(fs::exists(dir_));
}

TEST(ProgramCacheDir, FollowsXdgThenHome) {
  unsetenv("ISOCURV_CACHE_DIR");
  const char* old_xdg = std::getenv("XDG_CACHE_HOME");
  const std::string saved = old_xdg ? old_xdg : "";
  setenv("XDG_CACHE_HOME", "/somewhere/xdg", 1);
  EXPECT_EQ(program_cache_dir(), "/somewhere/xdg/isocurv");
  unsetenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  if (home && *home) {
    EXPECT_EQ(program_cache_dir(), std::string(home) + "/.cache/isocurv");
  }
  if (old_xdg) setenv("XDG_CACHE_HOME", saved.c_str(), 1);
}

}  // namespace
}  // namespace isocurv
