// Every volume file the fuzzers found a problem with (tests/data/fuzz/volume, fuzz/README.md)
// loads or fails with isocurv::Error, never anything else; one named *_refused.* must fail.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "volume/load.h"

namespace fs = std::filesystem;

TEST(VolumeFuzzRegressions, EveryFileLoadsOrFailsWithError) {
  const fs::path dir = fs::path(isocurv::test_paths::source_dir()) / "tests/data/fuzz/volume";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() == "README.md" || entry.path().extension() == ".data") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    // A "_refused" file once loaded with values it does not hold (issue 41): it must fail.
    const bool must_fail = entry.path().filename().string().find("_refused.") != std::string::npos;
    try {
      const auto v = isocurv::volume::load(entry.path().string());
      EXPECT_TRUE(std::isfinite(v.stats.min) && std::isfinite(v.stats.max));
      EXPECT_FALSE(must_fail) << "loaded";
    } catch (const isocurv::Error&) {
    }
  }
  RecordProperty("files", files);
}
