// Where the tests find their data and the built programs. The paths are compiled into one
// generated source per build (tests/CMakeLists.txt), not into every test as defines, so that test
// objects are identical across checkouts and build folders and a compiler cache can share them.
#pragma once

namespace isocurv::test_paths {

/// ../shared/datasets beside the source tree (the real volumes); may not exist.
const char* shared_datasets();
/// The CMake build folder (holds app/isocurv and the generated datasets/).
const char* build_dir();
/// The source tree's root (holds tests/data/).
const char* source_dir();

}  // namespace isocurv::test_paths
