// Every mesh file the fuzzers found a problem with (tests/data/fuzz/mesh, fuzz/README.md) reads
// or fails with isocurv::Error, and a mesh read from one has its indices in range; one named
// *_refused.* must fail.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/mesh_file.h"

namespace fs = std::filesystem;

TEST(IoFuzzRegressions, EveryFileReadsOrFailsWithError) {
  const fs::path dir = fs::path(isocurv::test_paths::source_dir()) / "tests/data/fuzz/mesh";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() == "README.md") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    // A "_refused" file once read as a mesh the file does not describe (issue 41): it must fail.
    const bool must_fail = entry.path().filename().string().find("_refused.") != std::string::npos;
    try {
      const auto file = isocurv::io::read_mesh(entry.path().string());
      for (const auto& t : file.mesh.triangles)
        for (auto v : t) ASSERT_LT(v, file.mesh.positions.size());
      EXPECT_FALSE(must_fail) << "read";
    } catch (const isocurv::Error&) {
    }
  }
  RecordProperty("files", files);
}
