// Mesh headers claiming more elements than their file can hold are refused before anything is
// allocated, with what the claim would need.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "io/mesh_file.h"

namespace fs = std::filesystem;

namespace {

class IoBadSizes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("isocurv_io_sizes_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  /// Writes `text` to `name` and expects read_mesh to throw Error naming it and saying `problem`.
  void expect_refused(const std::string& name, const std::string& text, const std::string& problem) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    try {
      isocurv::io::read_mesh(path);
      ADD_FAILURE() << name << " was read";
    } catch (const isocurv::Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

const std::string kVertex = "property float x\nproperty float y\nproperty float z\n";

}  // namespace

TEST_F(IoBadSizes, PlyClaimingBillionsOfVertices) {
  expect_refused("huge.ply",
                 "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + kVertex +
                     "end_header\n" + std::string(24, '\0'),
                 "header claims 4000000000 vertex records (at least 4.8e+10 bytes) but the file holds 24 "
                 "bytes after its header");
  expect_refused("huge_ascii.ply",
                 "ply\nformat ascii 1.0\nelement vertex 4000000000\n" + kVertex + "end_header\n0 0 0\n",
                 "(at least 2.4e+10 bytes) but the file holds 6 bytes");
  expect_refused("faces.ply",
                 "ply\nformat binary_little_endian 1.0\nelement vertex 1\n" + kVertex +
                     "element face 3000000000\nproperty list uchar int vertex_indices\nend_header\n" +
                     std::string(12, '\0'),
                 "1 vertex, 3000000000 face records (at least 3e+09 bytes)");
}

// An element without properties holds no data however many records it claims: it is skipped,
// not looped over (a claim of 10^18 records hung the reader).
TEST_F(IoBadSizes, PlyElementWithoutPropertiesIsNotLoopedOver) {
  const std::string path = (dir_ / "empty_element.ply").string();
  std::ofstream(path, std::ios::binary)
      << "ply\nformat ascii 1.0\nelement junk 1000000000000000000\nelement vertex 3\n" << kVertex
      << "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const auto file = isocurv::io::read_mesh(path);
  EXPECT_EQ(file.mesh.positions.size(), 3u);
  EXPECT_EQ(file.mesh.triangles.size(), 1u);
}

TEST_F(IoBadSizes, VtpClaimingBillionsOfPoints) {
  expect_refused("huge.vtp",
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\">\n<PolyData>\n"
                 "<Piece NumberOfPoints=\"4000000000\" NumberOfPolys=\"1\">\n<Points>\n"
                 "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray>\n"
                 "</Points>\n</Piece>\n</PolyData>\n</VTKFile>\n",
                 "header claims NumberOfPoints=4000000000");
}

// A compressed array's block header claiming more than the file holds is refused before VTK
// allocates for it (the VTP fuzzer: a 4 KB file whose header asked for a 4 GB block). The file is
// one our writer made (raw appended zlib, UInt64 headers), with the first array's (only) block size,
// and then its block count, patched.
TEST_F(IoBadSizes, VtpCompressedBlockClaimingGigabytes) {
  isocurv::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::string good = (dir_ / "good.vtp").string();
  isocurv::io::write_mesh(good, m);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t data = bytes.find('_', bytes.find("<AppendedData")) + 1;
  ASSERT_NE(data, std::string::npos);
  ASSERT_NE(bytes.find("header_type=\"UInt64\""), std::string::npos);
  ASSERT_NE(bytes.find("offset=\"0\""), std::string::npos);  // the first array's header is at `data`
  auto patched = [&](std::size_t word, unsigned long long value) {
    std::string b = bytes;
    for (int k = 0; k < 8; ++k) b[data + 8 * word + k] = char((value >> (8 * k)) & 0xff);  // little-endian
    return b;
  };
  expect_refused("huge.vtp", patched(2, 4000000000ULL), "claims blocks of 4000000000 bytes");
  // Within what the whole file could inflate to, but not its block: 2 MB from a few dozen bytes.
  expect_refused("block.vtp", patched(2, 2000000), "claims a block of 2000000 bytes from");
  expect_refused("blocks.vtp", patched(0, 1ULL << 40), "claims 1099511627776 blocks");
  expect_refused("zero.vtp", patched(1, 0), "claims a block size of 0");  // VTK divided by it
  std::string none = patched(0, 0);  // no blocks, but VTK still allocates one of the block size
  for (int k = 0; k < 8; ++k) none[data + 8 + k] = char(k == 7 ? 0x60 : 0);
  expect_refused("none.vtp", none, "claims blocks of 6917529027641081856 bytes");
  EXPECT_EQ(isocurv::io::read_mesh(good).mesh.triangles.size(), 4u);
}

// Values are converted without undefined behaviour (found by the PLY fuzzer under UBSan): a list
// length of 1e32 in a float count is an error, a double beyond float's range becomes infinity.
TEST_F(IoBadSizes, PlyValuesOutOfTheirTargetsRange) {
  expect_refused("list.ply",
                 "ply\nformat ascii 1.0\nelement vertex 3\n" + kVertex +
                     "element face 1\nproperty list float int vertex_indices\nend_header\n"
                     "0 0 0\n1 0 0\n0 1 0\n1e32 0 1 2\n",
                 "bad PLY list length");
  const std::string path = (dir_ / "big.ply").string();
  std::ofstream(path, std::ios::binary)
      << "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
         "property double Boundary\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "1e300 0 0 7\n1 0 0 0\n0 1 0 -1e300\n3 0 1 2\n";
  const auto file = isocurv::io::read_mesh(path);
  EXPECT_TRUE(std::isinf(file.mesh.positions[0][0]));
  ASSERT_TRUE(file.field.has_value());
  EXPECT_EQ(file.field->boundary, (std::vector<std::uint8_t>{1, 0, 1}));
}

// "solid" followed by binary bytes: VTK reads it as binary STL and allocated for the triangle
// count at byte 80 (16 GB here) although the size does not match it (found by the STL fuzzer).
TEST_F(IoBadSizes, StlSolidThenBinary) {
  expect_refused("mixed.stl", "solid t\n" + std::string(100, '\xff'), "not an STL file");
  expect_refused("feeds.stl", "solid t\nfacet normal\n" + std::string(200, '\f'), "not an STL file");
}
