#pragma once
// Helpers for the volume tests: a per-test temporary directory, little writers for binary,
// zlib and gzip files, and an assertion that a call throws isocurv::Error naming a file.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace voltest {

/// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("isocurv_volume_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// The whole file as bytes (empty when it cannot be read).
inline std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const std::string& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), std::streamsize(size));
}
inline void write_file(const std::string& path, const std::string& text) { write_file(path, text.data(), text.size()); }
inline void write_file(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file(path, bytes.data(), bytes.size());
}

inline std::vector<std::uint8_t> zlib_compress(const std::vector<std::uint8_t>& in) {
  uLongf size = compressBound(uLong(in.size()));
  std::vector<std::uint8_t> out(size);
  compress2(out.data(), &size, in.data(), uLong(in.size()), 6);
  out.resize(size);
  return out;
}

inline std::vector<std::uint8_t> gzip_compress(const std::vector<std::uint8_t>& in) {
  z_stream zs{};
  deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  std::vector<std::uint8_t> out(deflateBound(&zs, uLong(in.size())) + 64);
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = uInt(in.size());
  zs.next_out = out.data();
  zs.avail_out = uInt(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

template <class T>
std::vector<std::uint8_t> to_bytes(const std::vector<T>& v, bool big_endian = false) {
  std::vector<std::uint8_t> out(v.size() * sizeof(T));
  std::memcpy(out.data(), v.data(), out.size());
  if (big_endian)
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(out[i * sizeof(T) + k], out[i * sizeof(T) + sizeof(T) - 1 - k]);
  return out;
}

/// The 5x4x3 test ramp value at (x, y, z): x + 10 y + 100 z.
inline float ramp(int x, int y, int z) { return float(x + 10 * y + 100 * z); }

template <class T>
std::vector<T> ramp_values(int nx = 5, int ny = 4, int nz = 3) {
  std::vector<T> v;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) v.push_back(T(ramp(x, y, z)));
  return v;
}

/// Expects `f` to throw isocurv::Error whose message contains `file` and `problem`.
inline void expect_error(const std::function<void()>& f, const std::string& file, const std::string& problem = "") {
  try {
    f();
    ADD_FAILURE() << "expected isocurv::Error for " << file;
  } catch (const isocurv::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    if (!problem.empty()) {
      EXPECT_NE(what.find(problem), std::string::npos) << what;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "unexpected exception type: " << e.what();
  }
}

}  // namespace voltest
