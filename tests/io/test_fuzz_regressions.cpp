// Every mesh file the fuzzers found a problem with (tests/data/fuzz/mesh, fuzz/README.md) reads
// or fails with isocurv::Error, and a mesh read from one has its indices in range.
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
    try {
      const auto file = isocurv::io::read_mesh(entry.path().string());
      for (const auto& t : file.mesh.triangles)
        for (auto v : t) ASSERT_LT(v, file.mesh.positions.size());
    } catch (const isocurv::Error&) {
    }
  }
  RecordProperty("files", files);
}
