// Issue 41: a .vtp that is wrong gives one Error, never a mesh made of what the file does not say.
// The mutation campaign read points declared Int8 while Float32 was stored (area 12.2e6 instead of
// 784.5), a header_type that did not match the headers (Euler characteristic -1026), and
// NumberOfPolys 1 while 2,352 were stored (the rest dropped), all with exit status 0. Each is
// written here as a small raw-appended file next to the consistent one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/le_bytes.h"
#include "core/error.h"
#include "io/mesh_file.h"
#include "tests/io/test_meshes.h"

namespace fs = std::filesystem;

namespace {

using isocurv::test::le;

/// One array of a raw-appended .vtp: where it sits, its attributes and its appended bytes.
struct Array {
  std::string section, type, name;
  int components = 1;
  std::string bytes;  ///< data only: the header is added with the file's header_type
};

/// A one-piece raw-appended .vtp of `arrays`, with `piece` attributes and `header` (UInt32 or
/// UInt64) words, each header saying `header_says(i)` bytes (default: the array's true length).
std::string vtp(const std::string& piece, const std::vector<Array>& arrays, const std::string& header = "UInt32",
                const std::string& declared_header = "") {
  const std::size_t word = header == "UInt64" ? 8 : 4;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                    "header_type=\"" + (declared_header.empty() ? header : declared_header) +
                    "\">\n<PolyData>\n<Piece " + piece + ">\n";
  std::string data;
  std::string open;
  for (const Array& a : arrays) {
    if (a.section != open) {
      if (!open.empty()) xml += "</" + open + ">\n";
      xml += "<" + a.section + ">\n";
      open = a.section;
    }
    xml += "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\" NumberOfComponents=\"" +
           std::to_string(a.components) + "\" format=\"appended\" offset=\"" + std::to_string(data.size()) + "\"/>\n";
    data += word == 8 ? le(std::uint64_t(a.bytes.size())) : le(std::uint32_t(a.bytes.size()));
    data += a.bytes;
  }
  if (!open.empty()) xml += "</" + open + ">\n";
  return xml + "</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_" + data + "\n</AppendedData>\n</VTKFile>\n";
}

std::string floats(const std::vector<float>& v) {
  std::string out;
  for (float f : v) out += le(f);
  return out;
}
std::string ints(const std::vector<std::int32_t>& v) {
  std::string out;
  for (auto i : v) out += le(i);
  return out;
}

/// A unit square of two triangles: 4 points, 2 polys.
std::vector<Array> square(const std::string& point_type = "Float32") {
  return {{"Points", point_type, "Points", 3, floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0})},
          {"Polys", "Int32", "connectivity", 1, ints({0, 1, 2, 0, 2, 3})},
          {"Polys", "Int32", "offsets", 1, ints({3, 6})}};
}
const std::string kPiece = "NumberOfPoints=\"4\" NumberOfPolys=\"2\"";

class IoVtpHonesty : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("isocurv_io_vtp_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  void expect_refused(const std::string& name, const std::string& text, const std::string& problem) {
    const std::string path = write(name, text);
    try {
      const auto m = isocurv::io::read_mesh(path);
      ADD_FAILURE() << name << " was read: " << m.mesh.positions.size() << " points, " << m.mesh.triangles.size()
                    << " triangles";
    } catch (const isocurv::Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

}  // namespace

TEST_F(IoVtpHonesty, ConsistentFileReads) {
  for (const char* header : {"UInt32", "UInt64"}) {
    const auto m = isocurv::io::read_mesh(write("ok.vtp", vtp(kPiece, square(), header)));
    EXPECT_EQ(m.mesh.positions.size(), 4u);
    EXPECT_EQ(m.mesh.triangles.size(), 2u);
  }
}

TEST_F(IoVtpHonesty, DeclaredTypeMustMatchTheStoredBytes) {
  expect_refused("int8.vtp", vtp(kPiece, square("Int8")),
                 "array 'Points' in Points of piece 0 holds 48 bytes, its declaration 4 x 3 Int8 values (12 bytes)");
}

TEST_F(IoVtpHonesty, HeaderTypeMustMatchTheHeaders) {
  // Each header alone can look right (48 bytes of points either way): the arrays then overlap,
  // or leave gaps, in the appended data.
  expect_refused("u64.vtp", vtp(kPiece, square(), "UInt32", "UInt64"), "in Polys of piece 0");
  expect_refused("u32.vtp", vtp(kPiece, square(), "UInt64", "UInt32"),
                 "array 'connectivity' in Polys of piece 0 starts 4 bytes after the previous array's data ends");
}

TEST_F(IoVtpHonesty, CountsMustCoverWhatIsStored) {
  // NumberOfPolys 1 while 2 are stored: VTK read one and dropped the other.
  expect_refused("polys.vtp", vtp("NumberOfPoints=\"4\" NumberOfPolys=\"1\"", square()),
                 "array 'offsets' in Polys of piece 0 holds 8 bytes, its declaration 1 x 1 Int32 values (4 bytes)");
  // Offsets that stop short of the connectivity stored: the rest was ignored.
  auto extra = square();
  extra[1].bytes = ints({0, 1, 2, 0, 2, 3, 1, 2, 3});
  expect_refused("connectivity.vtp", vtp(kPiece, extra), "Polys connectivity holds 9 point ids but the offsets use 6");
  // More points stored than declared.
  auto points = square();
  points[0].bytes += floats({5, 5, 5});
  expect_refused("points.vtp", vtp(kPiece, points), "holds 60 bytes, its declaration 4 x 3 Float32 values (48 bytes)");
  // Strips declared but none stored.
  expect_refused("strips.vtp", vtp(kPiece + " NumberOfStrips=\"1\"", square()),
                 "piece 0 declares 1 Strips but holds no 'offsets' array for them");
  // Bytes after the last array that no array accounts for.
  std::string tail = vtp(kPiece, square());
  tail.insert(tail.find("\n</AppendedData>"), "junk");
  expect_refused("tail.vtp", tail, "the appended data holds");
}

TEST_F(IoVtpHonesty, ShortAppendedDataAndStringArraysRefused) {
  std::string cut = vtp(kPiece, square());
  cut.erase(cut.find("\n</AppendedData>") - 6, 6);  // the last offset loses 6 of its bytes
  expect_refused("short.vtp", cut, "claims 8 bytes but its data holds at most");
  auto text = square();
  text.push_back({"PointData", "String", "label", 1, std::string("a\0b\0c\0d\0", 8)});
  expect_refused("string.vtp", vtp(kPiece, text), "is a String array");
  auto bits = square();
  bits.push_back({"PointData", "Bit", "flags", 1, std::string(1, '\x0f')});
  expect_refused("bit.vtp", vtp(kPiece, bits), "has type 'Bit'");
}

// What isocurv writes (every compressor, strings in FieldData) still reads.
TEST_F(IoVtpHonesty, OwnFilesStillRead) {
  const isocurv::Mesh mesh = isocurv::test::grid_mesh();
  auto field = isocurv::test::random_field(mesh.positions.size());
  field.metadata.emplace_back("estimator", "rusinkiewicz");  // written as a String array in FieldData
  for (const char* c : {"none", "lz4", "zlib"}) {
    SCOPED_TRACE(c);
    const std::string path = (dir_ / (std::string(c) + ".vtp")).string();
    isocurv::io::Compression compression;
    compression.compressor = std::string(c) == "none"  ? isocurv::io::Compressor::none
                             : std::string(c) == "lz4" ? isocurv::io::Compressor::lz4
                                                       : isocurv::io::Compressor::zlib;
    isocurv::io::write_mesh(path, mesh, &field, compression);
    const auto back = isocurv::io::read_mesh(path);
    EXPECT_EQ(back.mesh.triangles.size(), mesh.triangles.size());
    ASSERT_TRUE(back.field.has_value());
  }
}
