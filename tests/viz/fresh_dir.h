#pragma once
// An empty folder of the system's temporary folder for one test's files (screenshots, cameras),
// named after the process so that parallel test runs do not collide.
#include <unistd.h>

#include <filesystem>
#include <string>

namespace isocurv::test {

/// <tmp>/<prefix>_<pid>_<name>, emptied and created.
inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    (prefix + "_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace isocurv::test
