#pragma once
// The explorer tests' shared set-up (tests/viz/test_explorer*.cpp): a fresh folder per test for
// screenshots and other files, and the scripted explorer most tests start from, on a synthetic
// torus whose tube radius is the isovalue. Each test file derives its suite from ExplorerTest
// (class VizExplorerTime : public test::ExplorerTest {}; then TEST_F(VizExplorerTime, ...)).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fresh_dir.h"
#include "test_surfaces.h"
#include "viz/explorer.h"

namespace isocurv::test {

/// The torus of major radius 1 and tube radius `tube` (nu x nv vertices) as an explorer surface.
inline viz::Surface torus_surface(float tube, int nu = 64, int nv = 32,
                                  std::string detail = "torus") {
  TestSurface t = torus(1.f, tube, nu, nv);
  return viz::Surface{std::move(t.mesh), std::move(t.field), 0, std::move(detail)};
}

/// The whole text of the file `path` (a script's status line, say); empty when it is missing.
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class ExplorerTest : public ::testing::Test {
 protected:
  /// <tmp>/isocurv_explorer_<pid>_<suite>_<test>, empty (test::fresh_dir).
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fresh_dir("isocurv_explorer",
                    std::string(info->test_suite_name()) + "_" + info->name());
  }
  /// A passing test's folder is removed; a failing one's stays for a look at its screenshots.
  void TearDown() override {
    if (!HasFailure()) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  }

  /// `name` in the test's folder, as a string (a screenshot's path, say).
  std::string file(const std::string& name) const { return (dir / name).string(); }

  /// A scripted explorer on isovalues 0.1 .. 0.6 starting at `iso`, in a width x height window,
  /// whose surface is torus_surface(iso, nu, nv); every isovalue asked for is appended to
  /// `extracted`. Tests add their script, keys' callbacks and checks.
  viz::ExplorerSetup torus_setup(float iso, int width, int height, int nu = 64, int nv = 32) {
    viz::ExplorerSetup setup;
    setup.isovalue = iso;
    setup.min_value = 0.1f;
    setup.max_value = 0.6f;
    setup.view.width = width;
    setup.view.height = height;
    setup.surface = [this, nu, nv](float value) {
      extracted.push_back(value);
      return torus_surface(value, nu, nv);
    };
    return setup;
  }

  std::filesystem::path dir;    ///< the test's own folder
  std::vector<float> extracted;  ///< the isovalues torus_setup's callback was asked for
};

}  // namespace isocurv::test
