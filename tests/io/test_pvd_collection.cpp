// io::PvdCollection / io::read_pvd: round trip, relative names, escaping, order, bad files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "io/pvd_collection.h"

namespace fs = std::filesystem;
using namespace isocurv;

namespace {

class PvdTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isocurv_pvd_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "frames");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
  }
  fs::path dir_;
};

TEST_F(PvdTest, RoundTripsTimesExactlyAndResolvesFilesAgainstTheCollection) {
  io::PvdCollection pvd(path("series.pvd"));
  EXPECT_FALSE(fs::exists(path("series.pvd")));  // nothing before the first frame
  const double times[] = {0.0, 1.0 / 3.0, 0.7, 2.5e-17 + 1.0};
  for (int i = 0; i < 4; ++i) {
    const std::string frame = path("frames/f & <" + std::to_string(i) + ">.vtp");
    std::ofstream(frame) << "x";
    pvd.add(times[i], frame);
    // After every add the file on disk lists exactly the frames so far.
    EXPECT_EQ(io::read_pvd(path("series.pvd")).size(), static_cast<size_t>(i + 1));
  }
  EXPECT_EQ(pvd.frames()[2].file, "frames/f & <2>.vtp");  // stored relative to the .pvd
  const auto frames = io::read_pvd(path("series.pvd"));
  ASSERT_EQ(frames.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(frames[i].time, times[i]);
    EXPECT_TRUE(fs::exists(frames[i].file)) << frames[i].file;
  }
}

TEST_F(PvdTest, RejectsTimesThatDoNotIncreaseAndKeepsTheFileAsItWas) {
  io::PvdCollection pvd(path("s.pvd"));
  pvd.add(1.0, path("frames/a.vtp"));
  EXPECT_THROW(pvd.add(1.0, path("frames/b.vtp")), Error);
  EXPECT_THROW(pvd.add(0.5, path("frames/b.vtp")), Error);
  EXPECT_THROW(pvd.add(std::nan(""), path("frames/b.vtp")), Error);
  EXPECT_EQ(io::read_pvd(path("s.pvd")).size(), 1u);
  EXPECT_EQ(pvd.frames().size(), 1u);
}

TEST_F(PvdTest, FailsWhenTheFolderIsMissingWithoutRecordingTheFrame) {
  io::PvdCollection pvd(path("missing/s.pvd"));
  EXPECT_THROW(pvd.add(0.0, path("frames/a.vtp")), Error);
  EXPECT_TRUE(pvd.frames().empty());
}

TEST_F(PvdTest, BadCollectionsAreOneLineErrors) {
  EXPECT_THROW(io::read_pvd(path("none.pvd")), Error);
  write("junk.pvd", "this is not xml <<<");
  EXPECT_THROW(io::read_pvd(path("junk.pvd")), Error);
  write("poly.pvd", "<VTKFile type=\"PolyData\"><PolyData/></VTKFile>");
  EXPECT_THROW(io::read_pvd(path("poly.pvd")), Error);
  write(
      "notime.pvd",
      "<VTKFile type=\"Collection\"><Collection><DataSet file=\"a.vtp\"/></Collection></VTKFile>");
  try {
    io::read_pvd(path("notime.pvd"));
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("timestep"), std::string::npos) << e.what();
  }
}

}  // namespace
