// Issue 41: volume files that are wrong give one clear Error, never a crash and never values the
// file does not hold. Each class the mutation campaign found is written here as a small file:
// VTK XML images (extents near 2^31, string arrays, header_type, declared types and short
// appended data), NRRD sizes and repeated fields, spacings, and compressed streams or ASCII data
// cut short.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "tests/le_bytes.h"
#include "test_files.h"
#include "volume/load.h"

using namespace isocurv::volume;
using namespace voltest;

namespace {

using isocurv::test::le;

/// The 2x2x2 values 0 .. 7 as Float32 bytes.
std::string eight_floats() {
  std::string out;
  for (int i = 0; i < 8; ++i) out += le(float(i));
  return out;
}

/// A 2x2x2 .vti with one raw appended array: `root` attributes on VTKFile, the Piece extent,
/// the array's type, and the appended bytes after '_' (header and data).
std::string vti(const std::string& root, const std::string& extent, const std::string& type, const std::string& data,
                const std::string& image = "Origin=\"0 0 0\" Spacing=\"1 1 1\"") {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" " + root +
         ">\n<ImageData WholeExtent=\"0 1 0 1 0 1\" " + image + ">\n<Piece Extent=\"" + extent +
         "\">\n<PointData Scalars=\"s\">\n<DataArray type=\"" + type +
         "\" Name=\"s\" format=\"appended\" offset=\"0\"/>\n</PointData>\n</Piece>\n</ImageData>\n"
         "<AppendedData encoding=\"raw\">\n_" + data + "\n</AppendedData>\n</VTKFile>\n";
}

const std::string kLittle32 = "byte_order=\"LittleEndian\" header_type=\"UInt32\"";

}  // namespace

TEST(VolumeReaderHonesty, RawAppendedVtiLoadsWhenConsistent) {
  TempDir dir;
  write_file(dir.file("ok.vti"), vti(kLittle32, "0 1 0 1 0 1", "Float32", le(std::uint32_t(32)) + eight_floats()));
  const Volume v = load(dir.file("ok.vti"));
  EXPECT_EQ(v.stats.voxels, 8u);
  EXPECT_EQ(v.stats.min, 0.0);
  EXPECT_EQ(v.stats.max, 7.0);
}

// Crashes (SIGSEGV) in VTK: a Piece Extent reaching 2147483647 with binary or base64 data, and a
// String array as the image's values.
TEST(VolumeReaderHonesty, VtiExtentNear2Pow31AndStringArraysRefused) {
  TempDir dir;
  const std::string data = le(std::uint32_t(32)) + eight_floats();
  write_file(dir.file("ext.vti"), vti(kLittle32, "0 2147483647 0 1 0 1", "Float32", data));
  expect_error([&] { load(dir.file("ext.vti")); }, "ext.vti", "Extent");
  std::string far = vti(kLittle32, "2147483646 2147483647 0 1 0 1", "Float32", data);
  far.replace(far.find("WholeExtent=\"0 1"), 16, "WholeExtent=\"2147483646 2147483647");
  write_file(dir.file("far.vti"), far);
  expect_error([&] { load(dir.file("far.vti")); }, "far.vti", "below 2^31");
  // Inline base64 (format="binary"), the piece's extent larger than the whole.
  std::string b64 = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" " + kLittle32 +
                    ">\n<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
                    "<Piece Extent=\"0 1 0 1 0 2147483647\"><PointData Scalars=\"s\"><DataArray type=\"UInt8\" "
                    "Name=\"s\" format=\"binary\">CAAAAAABAgMEBQYH</DataArray></PointData></Piece></ImageData>"
                    "</VTKFile>\n";
  write_file(dir.file("b64.vti"), b64);
  expect_error([&] { load(dir.file("b64.vti")); }, "b64.vti", "Extent");
  write_file(dir.file("string.vti"), vti(kLittle32, "0 1 0 1 0 1", "String", le(std::uint32_t(16)) +
                                                                           std::string("a\0b\0c\0d\0e\0f\0g\0h\0", 16)));
  expect_error([&] { load(dir.file("string.vti")); }, "string.vti", "String array");
  // The same string array in ASCII.
  std::string ascii = b64;
  ascii.replace(ascii.find("0 1 0 1 0 2147483647"), 20, "0 1 0 1 0 1");
  ascii.replace(ascii.find("type=\"UInt8\""), 12, "type=\"String\"");
  ascii.replace(ascii.find("format=\"binary\">CAAAAAABAgMEBQYH"), 32, "format=\"ascii\">97 0 98 0 99 0 100 0 101 0 102 0 103 0 104 0");
  write_file(dir.file("string_ascii.vti"), ascii);
  expect_error([&] { load(dir.file("string_ascii.vti")); }, "string_ascii.vti", "String array");
}

// Silent wrong data: header_type UInt64 on a file of UInt32 headers read the byte count from the
// first value and values from outside the file; a declared type other than the stored one; raw
// appended data shorter than the array.
TEST(VolumeReaderHonesty, VtiHeadersTypesAndLengthsMustMatchTheBytes) {
  TempDir dir;
  const std::string data = le(std::uint32_t(32)) + eight_floats();
  write_file(dir.file("u64.vti"), vti("byte_order=\"LittleEndian\" header_type=\"UInt64\"", "0 1 0 1 0 1", "Float32", data));
  expect_error([&] { load(dir.file("u64.vti")); }, "u64.vti", "array 's' in PointData of piece 0 claims");
  write_file(dir.file("int8.vti"), vti(kLittle32, "0 1 0 1 0 1", "Int8", data));
  expect_error([&] { load(dir.file("int8.vti")); }, "int8.vti",
               "holds 32 bytes, its declaration 8 x 1 Int8 values (8 bytes)");
  write_file(dir.file("short.vti"), vti(kLittle32, "0 1 0 1 0 1", "Float32", data.substr(0, 20)));
  expect_error([&] { load(dir.file("short.vti")); }, "short.vti", "claims 32 bytes but its data holds at most");
  write_file(dir.file("header_type.vti"), vti("byte_order=\"LittleEndian\" header_type=\"UInt16\"", "0 1 0 1 0 1", "Float32", data));
  expect_error([&] { load(dir.file("header_type.vti")); }, "header_type.vti", "header_type 'UInt16'");
  write_file(dir.file("bits.vti"), vti(kLittle32, "0 1 0 1 0 1", "Bit", data));
  expect_error([&] { load(dir.file("bits.vti")); }, "bits.vti", "has type 'Bit'");
  // ASCII arrays must hold exactly the extent's values.
  const std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
                           "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
                           "<Piece Extent=\"0 1 0 1 0 1\"><PointData Scalars=\"s\"><DataArray type=\"UInt8\" "
                           "Name=\"s\" format=\"ascii\">";
  const std::string tail = "</DataArray></PointData></Piece></ImageData></VTKFile>\n";
  write_file(dir.file("nine.vti"), head + "0 1 2 3 4 5 6 7 8" + tail);
  expect_error([&] { load(dir.file("nine.vti")); }, "nine.vti", "holds 9 ASCII values");
  write_file(dir.file("eight.vti"), head + "0 1 2 3 4 5 6 7" + tail);
  EXPECT_EQ(load(dir.file("eight.vti")).stats.max, 7.0);
}

// A zlib block without its Adler-32 trailer: VTK's uncompress refuses it, and the error is one line.
TEST(VolumeReaderHonesty, VtiZlibBlockWithoutTrailerRefused) {
  TempDir dir;
  std::vector<std::uint8_t> raw(32);
  std::memcpy(raw.data(), eight_floats().data(), 32);
  std::vector<std::uint8_t> z = zlib_compress(raw);
  z.resize(z.size() - 4);  // the Adler-32 trailer
  const std::string block(z.begin(), z.end());
  const std::string header = le(std::uint32_t(1)) + le(std::uint32_t(32)) + le(std::uint32_t(32)) +
                             le(std::uint32_t(block.size()));
  write_file(dir.file("z.vti"), vti(kLittle32 + " compressor=\"vtkZLibDataCompressor\"", "0 1 0 1 0 1", "Float32",
                                    header + block));
  expect_error([&] { load(dir.file("z.vti")); }, "z.vti");
}

// NRRD: data longer than the sizes need (attached and detached) was accepted, a smaller grid than
// the file holds; a second `sizes:` silently won.
TEST(VolumeReaderHonesty, NrrdSizesMustMatchTheData) {
  TempDir dir;
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n";
  const auto bytes = to_bytes(ramp_values<std::uint8_t>());
  const std::string data(bytes.begin(), bytes.end());
  write_file(dir.file("exact.nrrd"), head + "\n" + data);
  EXPECT_EQ(load(dir.file("exact.nrrd")).stats.voxels, 60u);
  write_file(dir.file("long.nrrd"), head + "\n" + data + data);
  expect_error([&] { load(dir.file("long.nrrd")); }, "long.nrrd", "voxel data has 120 bytes, the header's 5x4x3 uint8 needs 60");
  write_file(dir.file("long.raw"), data + "x");
  write_file(dir.file("long.nhdr"), head + "data file: long.raw\n");
  expect_error([&] { load(dir.file("long.nhdr")); }, "long.raw", "voxel data has 61 bytes");
  write_file(dir.file("skip.nrrd"), head + "byte skip: -1\n\n" + std::string(7, 'h') + data);  // -1: the data ends the file
  EXPECT_EQ(load(dir.file("skip.nrrd")).stats.voxels, 60u);
  write_file(dir.file("twice.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nsizes: 5 4 1\nencoding: raw\n\n" +
                                         data.substr(0, 20));
  expect_error([&] { load(dir.file("twice.nrrd")); }, "twice.nrrd", "NRRD field 'sizes' is given twice");
}

// Spacing: NaN, 0 and inf became 1 (NRRD spacings, NIfTI pixdim, VTI); now one error line in
// every format, and a negative spacing is a flip, the same in every format.
TEST(VolumeReaderHonesty, BadSpacingIsAnErrorInEveryFormat) {
  TempDir dir;
  const auto bytes = to_bytes(ramp_values<std::uint8_t>());
  const std::string data(bytes.begin(), bytes.end());
  for (const std::string s : {"NaN", "0", "inf", "-inf"}) {
    SCOPED_TRACE(s);
    write_file(dir.file("s.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nspacings: " + s +
                                       " 1 1\nencoding: raw\n\n" + data);
    expect_error([&] { load(dir.file("s.nrrd")); }, "s.nrrd", "invalid voxel spacing");
    write_file(dir.file("s.mha"), "NDims = 3\nDimSize = 5 4 3\nElementType = MET_UCHAR\nElementSpacing = 1 " + s +
                                      " 1\nElementDataFile = LOCAL\n" + data);
    expect_error([&] { load(dir.file("s.mha")); }, "s.mha", "spacing");
    std::string image = vti(kLittle32, "0 1 0 1 0 1", "Float32", le(std::uint32_t(32)) + eight_floats(),
                            "Origin=\"0 0 0\" Spacing=\"1 1 " + s + "\"");
    write_file(dir.file("s.vti"), image);
    expect_error([&] { load(dir.file("s.vti")); }, "s.vti", "Spacing");
    write_file(dir.file("s.vtk"), "# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
                                  "SPACING 1 " + s + " 1\nORIGIN 0 0 0\nPOINT_DATA 8\nSCALARS s float 1\n"
                                  "LOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n");
    expect_error([&] { load(dir.file("s.vtk")); }, "s.vtk", "SPACING");
    // NIfTI pixdim (no qform or sform: pixdim is the spacing).
    std::vector<std::uint8_t> h(352, 0);
    const std::int32_t sizeof_hdr = 348;
    std::memcpy(h.data(), &sizeof_hdr, 4);
    const std::int16_t dims[4] = {3, 5, 4, 3};
    std::memcpy(&h[40], dims, sizeof dims);
    const std::int16_t u8 = 2, bitpix = 8;
    std::memcpy(&h[70], &u8, 2);
    std::memcpy(&h[72], &bitpix, 2);
    const float pixdim[4] = {1, 1, s == "NaN" ? std::numeric_limits<float>::quiet_NaN()
                                  : s == "0" ? 0.0f
                                  : s == "inf" ? std::numeric_limits<float>::infinity()
                                               : -std::numeric_limits<float>::infinity(), 1};
    std::memcpy(&h[76], pixdim, sizeof pixdim);
    const float offset = 352;
    std::memcpy(&h[108], &offset, 4);
    std::memcpy(&h[344], "n+1", 4);
    h.insert(h.end(), bytes.begin(), bytes.end());
    write_file(dir.file("s.nii"), h);
    expect_error([&] { load(dir.file("s.nii")); }, "s.nii", "invalid voxel spacing");
  }
  // NaN origin and direction too.
  write_file(dir.file("o.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nspace: RAS\n"
                                 "space origin: (0,nan,0)\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n\n" + data);
  expect_error([&] { load(dir.file("o.nrrd")); }, "o.nrrd", "origin");
  write_file(dir.file("o.vti"), vti(kLittle32, "0 1 0 1 0 1", "Float32", le(std::uint32_t(32)) + eight_floats(),
                                    "Origin=\"0 0 nan\" Spacing=\"1 1 1\""));
  expect_error([&] { load(dir.file("o.vti")); }, "o.vti", "Origin");
  write_file(dir.file("d.vti"), vti(kLittle32, "0 1 0 1 0 1", "Float32", le(std::uint32_t(32)) + eight_floats(),
                                    "Origin=\"0 0 0\" Spacing=\"1 1 1\" Direction=\"1 0 0 0 1 0 0 0 nan\""));
  expect_error([&] { load(dir.file("d.vti")); }, "d.vti", "Direction");
}

TEST(VolumeReaderHonesty, NegativeSpacingIsTheSameFlipInEveryFormat) {
  TempDir dir;
  const auto bytes = to_bytes(ramp_values<std::uint8_t>(2, 2, 2));
  const std::string data(bytes.begin(), bytes.end());
  write_file(dir.file("f.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nspacings: 1 -2 1\nencoding: raw\n\n" + data);
  write_file(dir.file("f.mha"), "NDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementSpacing = 1 -2 1\n"
                                "ElementDataFile = LOCAL\n" + data);
  std::string vals;
  for (unsigned char b : data) vals += std::to_string(int(b)) + " ";
  write_file(dir.file("f.vti"), "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
                                "<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 -2 1\">\n"
                                "<Piece Extent=\"0 1 0 1 0 1\"><PointData Scalars=\"s\"><DataArray type=\"UInt8\" "
                                "Name=\"s\" format=\"ascii\">" + vals +
                                    "</DataArray></PointData></Piece></ImageData></VTKFile>\n");
  write_file(dir.file("f.vtk"), "# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
                                "SPACING 1 -2 1\nORIGIN 0 0 0\nPOINT_DATA 8\nSCALARS s unsigned_char 1\n"
                                "LOOKUP_TABLE default\n" + vals + "\n");
  // Value v(x, y, z) = x + 10 y + 100 z sits at world (x, -2 y, z) in every one of them.
  for (const char* name : {"f.nrrd", "f.mha", "f.vti", "f.vtk"}) {
    SCOPED_TRACE(name);
    const Volume v = load(dir.file(name));
    EXPECT_NEAR(v.spacing()[1], 2.0, 1e-12);
    int checked = 0;
    for (auto c = v.domain.begin(); c; ++c) {
      const openvdb::Vec3d p = v.grid->transform().indexToWorld(*c);
      const double x = std::round(p[0]), y = std::round(-p[1] / 2), z = std::round(p[2]);
      EXPECT_NEAR(p[1], -2 * y, 1e-9);
      EXPECT_FLOAT_EQ(v.grid->tree().getValue(*c), float(x + 10 * y + 100 * z)) << p;
      ++checked;
    }
    EXPECT_EQ(checked, 8);
  }
}

// Compressed streams without their checksum trailer (zlib Adler-32, gzip CRC-32 and length) were
// accepted: the bytes then come with nothing that vouches for them.
TEST(VolumeReaderHonesty, CompressedStreamsNeedTheirTrailer) {
  TempDir dir;
  const auto bytes = to_bytes(ramp_values<std::uint8_t>());
  auto gz = gzip_compress(bytes);
  gz.resize(gz.size() - 8);  // CRC-32 and length
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: gzip\n\n";
  std::string nrrd = head;
  nrrd.append(gz.begin(), gz.end());
  write_file(dir.file("gz.nrrd"), nrrd);
  expect_error([&] { load(dir.file("gz.nrrd")); }, "gz.nrrd", "checksum trailer");
  auto z = zlib_compress(bytes);
  z.resize(z.size() - 4);  // Adler-32
  std::string mha = "NDims = 3\nDimSize = 5 4 3\nElementType = MET_UCHAR\nCompressedData = True\nElementDataFile = LOCAL\n";
  mha.append(z.begin(), z.end());
  write_file(dir.file("z.mha"), mha);
  expect_error([&] { load(dir.file("z.mha")); }, "z.mha", "checksum trailer");
  // A .nii.gz cut inside its trailer.
  std::vector<std::uint8_t> h(352, 0);
  const std::int32_t sizeof_hdr = 348;
  std::memcpy(h.data(), &sizeof_hdr, 4);
  const std::int16_t dims[4] = {3, 5, 4, 3};
  std::memcpy(&h[40], dims, sizeof dims);
  const std::int16_t u8 = 2;
  std::memcpy(&h[70], &u8, 2);
  const float pixdim[4] = {1, 1, 1, 1};
  std::memcpy(&h[76], pixdim, sizeof pixdim);
  const float offset = 352;
  std::memcpy(&h[108], &offset, 4);
  std::memcpy(&h[344], "n+1", 4);
  h.insert(h.end(), bytes.begin(), bytes.end());
  auto nii = gzip_compress(h);
  write_file(dir.file("ok.nii.gz"), nii);
  EXPECT_EQ(load(dir.file("ok.nii.gz")).stats.voxels, 60u);
  nii.resize(nii.size() - 3);
  write_file(dir.file("cut.nii.gz"), nii);
  expect_error([&] { load(dir.file("cut.nii.gz")); }, "cut.nii.gz", "truncated");
}

// ASCII data cut inside its last number read as a shorter number; more numbers than the sizes
// need were ignored.
TEST(VolumeReaderHonesty, AsciiDataCutOrTooLong) {
  TempDir dir;
  std::string values;
  for (float f : ramp_values<float>()) values += std::to_string(int(f) % 256) + " ";
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: ascii\n\n";
  write_file(dir.file("ok.nrrd"), head + values + "\n");
  EXPECT_EQ(load(dir.file("ok.nrrd")).stats.voxels, 60u);
  std::string cut = values;
  while (cut.back() == ' ') cut.pop_back();
  cut.pop_back();  // "234" -> "23"
  write_file(dir.file("cut.nrrd"), head + cut);
  expect_error([&] { load(dir.file("cut.nrrd")); }, "cut.nrrd", "ends inside its last value");
  write_file(dir.file("more.nrrd"), head + values + "7\n");
  expect_error([&] { load(dir.file("more.nrrd")); }, "more.nrrd", "more than the header's 60 values");
  write_file(dir.file("cut.mha"), "NDims = 3\nDimSize = 5 4 3\nElementType = MET_UCHAR\nBinaryData = False\n"
                                  "ElementDataFile = LOCAL\n" + cut);
  expect_error([&] { load(dir.file("cut.mha")); }, "cut.mha", "ends inside its last value");
}
