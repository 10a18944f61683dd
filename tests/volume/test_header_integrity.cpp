// Header integrity: the readers' findings of an outside fuzzing campaign (issue 55). Each test
// writes small files of its own: NIfTI scl_slope / scl_inter on integer voxels (applied: they are
// real values), a qform quaternion with b^2 + c^2 + d^2 > 1 (normalised as nifti1_io.c does, so
// the spacing stays pixdim), gzip streams whose trailer is cut by 1 to 8 bytes (refused at every
// size, in .nii.gz, .raw.gz and NRRD gzip), and lenient NRRD / MetaImage headers (refused, each
// with one Error line naming the file and the field).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "test_files.h"
#include "volume/load.h"

using namespace isocurv::volume;
using namespace voltest;

namespace header_files {

/// A little-endian NIfTI-1 single file: 352-byte header (pixdim 0.5 0.25 2, vox_offset 352) then
/// `data`; `edit` sets more header fields through put.
struct Nifti {
  std::vector<std::uint8_t> h = std::vector<std::uint8_t>(352, 0);
  template <class T>
  void put(std::size_t off, T value) {
    std::memcpy(&h[off], &value, sizeof(T));
  }
  Nifti(int nx, int ny, int nz, std::int16_t datatype, std::int16_t bitpix) {
    put(0, std::int32_t(348));
    put(40, std::int16_t(3));
    put(42, std::int16_t(nx));
    put(44, std::int16_t(ny));
    put(46, std::int16_t(nz));
    for (std::size_t i = 4; i < 8; ++i) put(40 + 2 * i, std::int16_t(1));
    put(70, datatype);
    put(72, bitpix);
    put(76, 1.0f);  // qfac
    put(80, 0.5f);
    put(84, 0.25f);
    put(88, 2.0f);
    put(108, 352.0f);
    std::memcpy(&h[344], "n+1", 4);
  }
  std::vector<std::uint8_t> with(const std::vector<std::uint8_t>& data) const {
    std::vector<std::uint8_t> out = h;
    out.insert(out.end(), data.begin(), data.end());
    return out;
  }
};

/// n^3 uint8 voxels that compress only partly (a ramp with pseudo-random low bits), so that the
/// compressed stream of a large volume spans many of the reader's input buffers.
std::vector<std::uint8_t> mixed_bytes(int n) {
  std::vector<std::uint8_t> out(std::size_t(n) * std::size_t(n) * std::size_t(n));
  std::uint32_t s = 12345;
  for (std::size_t i = 0; i < out.size(); ++i) {
    s = s * 1664525u + 1013904223u;
    out[i] = std::uint8_t(((i / 97) & 0xf0) | (s >> 28));
  }
  return out;
}

/// The value of voxel index (x, y, z).
float voxel(const Volume& v, int x, int y, int z) {
  return v.grid->getConstAccessor().getValue(openvdb::Coord(x, y, z));
}

}  // namespace header_files

// 4.1 scl_slope / scl_inter on integer voxels are real values: applied, whatever they make of
// the integers (the label-map refusal is in tests/labels/test_label_map.cpp).
TEST(VolumeHeaderIntegrity, NiftiScalingOfIntegerVoxelsIsApplied) {
  TempDir dir;
  const std::vector<std::int16_t> labels = {0, 1, 2, 1, 0, 2, 2, 1};  // 2x2x2
  for (const auto& [slope, inter] : std::vector<std::pair<float, float>>{{0.5f, 0}, {1, 0.25f}, {2, -1}}) {
    header_files::Nifti n(2, 2, 2, 4, 16);
    n.put(112, slope);
    n.put(116, inter);
    write_file(dir.file("s.nii"), n.with(to_bytes(labels)));
    const Volume v = load(dir.file("s.nii"));
    EXPECT_EQ(v.voxel_type, "int16");  // the type on disk
    for (int i = 0; i < 8; ++i)
      EXPECT_FLOAT_EQ(header_files::voxel(v, i & 1, (i >> 1) & 1, i >> 2), slope * float(labels[std::size_t(i)]) + inter)
          << "slope " << slope << " inter " << inter << " voxel " << i;
  }
}

// 4.2 A qform quaternion with b^2 + c^2 + d^2 > 1 scaled the spacing (pixdim 1 read as 3):
// nifti1_io.c's nifti_quatern_to_mat44 normalises (b, c, d) and takes a = 0 (a half turn).
TEST(VolumeHeaderIntegrity, QformQuaternionBeyondUnitLengthIsNormalised) {
  TempDir dir;
  const auto data = to_bytes(ramp_values<std::uint8_t>());
  struct Case {
    float b, c, d;
  };
  for (const Case q : {Case{1, 1, 1}, Case{0.8f, 0.8f, 0}, Case{0, 0, 1.5f}}) {
    SCOPED_TRACE(std::to_string(q.b) + " " + std::to_string(q.c) + " " + std::to_string(q.d));
    header_files::Nifti n(5, 4, 3, 2, 8);
    n.put(252, std::int16_t(1));  // qform_code
    n.put(256, q.b);
    n.put(260, q.c);
    n.put(264, q.d);
    n.put(268, 10.0f);
    write_file(dir.file("q.nii"), n.with(data));
    const Volume v = load(dir.file("q.nii"));
    // A half turn about u = (b, c, d) / |(b, c, d)|: R = 2 u u^T - I, a rotation (right-handed, so
    // nothing is flipped); index axis i goes pixdim[i] along column i of R.
    const double len = std::sqrt(double(q.b) * q.b + double(q.c) * q.c + double(q.d) * q.d);
    const double u[3] = {q.b / len, q.c / len, q.d / len};
    const double pixdim[3] = {0.5, 0.25, 2};
    const openvdb::Vec3d origin = v.grid->transform().indexToWorld(openvdb::Vec3d(0, 0, 0));
    EXPECT_NEAR(origin[0], 10, 1e-9);
    for (int i = 0; i < 3; ++i) {
      openvdb::Vec3d step(0, 0, 0);
      step[i] = 1;
      const openvdb::Vec3d axis = v.grid->transform().indexToWorld(step) - origin;
      EXPECT_NEAR(axis.length(), pixdim[i], 1e-6) << "axis " << i;
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR(axis[r], pixdim[i] * (2 * u[r] * u[i] - (r == i ? 1 : 0)), 1e-6) << "axis " << i << " row " << r;
    }
  }
  // A quaternion that is not a number is one error line, not a NaN transform.
  header_files::Nifti n(5, 4, 3, 2, 8);
  n.put(252, std::int16_t(1));
  n.put(256, std::nanf(""));
  write_file(dir.file("nan.nii"), n.with(data));
  expect_error([&] { load(dir.file("nan.nii")); }, "nan.nii", "qform quaternion");
}

// 4.3 A gzip stream whose trailer (CRC-32 and length) was cut by 1 to 8 bytes was accepted above
// about 80^3 voxels and refused below: whether zlib's gzread saw the cut depended on where its
// buffers ended. Every size and every cut is refused now, by every reader of gzip files.
TEST(VolumeHeaderIntegrity, GzipTrailerCutIsRefusedAtEverySize) {
  TempDir dir;
  for (const int size : {5, 40, 80, 96, 128}) {
    const auto bytes = header_files::mixed_bytes(size);
    const std::string dims = std::to_string(size) + " " + std::to_string(size) + " " + std::to_string(size);
    const std::string raw_name = "v_" + std::to_string(size) + "x" + std::to_string(size) + "x" +
                                 std::to_string(size) + "_uint8.raw.gz";
    const auto nii = gzip_compress(header_files::Nifti(size, size, size, 2, 8).with(bytes));
    const auto raw = gzip_compress(bytes);
    const std::string nrrd_head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: " + dims + "\nencoding: gzip\n\n";
    for (int cut = 0; cut <= 8; ++cut) {
      SCOPED_TRACE("size " + std::to_string(size) + "^3, trailer cut by " + std::to_string(cut));
      auto a = nii, b = raw;
      a.resize(a.size() - std::size_t(cut));
      b.resize(b.size() - std::size_t(cut));
      std::string c = nrrd_head;
      c.append(b.begin(), b.end());
      write_file(dir.file("v.nii.gz"), a);
      write_file(dir.file(raw_name), b);
      write_file(dir.file("v.nrrd"), c);
      if (cut == 0) {
        EXPECT_EQ(load(dir.file("v.nii.gz")).stats.voxels, bytes.size());
        EXPECT_EQ(load(dir.file(raw_name)).stats.voxels, bytes.size());
        EXPECT_EQ(load(dir.file("v.nrrd")).stats.voxels, bytes.size());
      } else {
        expect_error([&] { load(dir.file("v.nii.gz")); }, "v.nii.gz", "truncated");
        expect_error([&] { load(dir.file(raw_name)); }, raw_name, "truncated");
        expect_error([&] { load(dir.file("v.nrrd")); }, "v.nrrd", "truncated");
      }
    }
  }
}

// Two gzip members one after the other (pigz, bgzip, `cat a.gz b.gz`) are one stream, as gzip
// reads them; bytes after the last member that are not a gzip member are ignored, as before.
TEST(VolumeHeaderIntegrity, GzipMembersInSequenceAndTrailingBytes) {
  TempDir dir;
  const auto bytes = header_files::mixed_bytes(40);
  const auto file = header_files::Nifti(40, 40, 40, 2, 8).with(bytes);
  const std::size_t half = file.size() / 2;
  auto two = gzip_compress(std::vector<std::uint8_t>(file.begin(), file.begin() + long(half)));
  const auto second = gzip_compress(std::vector<std::uint8_t>(file.begin() + long(half), file.end()));
  two.insert(two.end(), second.begin(), second.end());
  write_file(dir.file("two.nii.gz"), two);
  const Volume v = load(dir.file("two.nii.gz"));
  EXPECT_EQ(v.stats.voxels, bytes.size());
  EXPECT_EQ(header_files::voxel(v, 39, 39, 39), float(bytes.back()));
  auto padded = gzip_compress(file);
  padded.insert(padded.end(), 100, 0);
  write_file(dir.file("padded.nii.gz"), padded);
  EXPECT_EQ(load(dir.file("padded.nii.gz")).stats.voxels, bytes.size());
  // The second member cut inside its trailer.
  two.resize(two.size() - 3);
  write_file(dir.file("cut.nii.gz"), two);
  expect_error([&] { load(dir.file("cut.nii.gz")); }, "cut.nii.gz", "truncated");
}

// 4.4 NRRD `spacings` and `space directions` both given: NRRD (teem) forbids the pair, and when
// they disagree nothing says which one is right, so the file is refused naming both; when they
// agree (as some writers repeat them) the file is read.
TEST(VolumeHeaderIntegrity, NrrdSpacingsThatDisagreeWithSpaceDirections) {
  TempDir dir;
  const std::string data(60, '\1');
  const std::string head = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n"
                           "space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\n";
  write_file(dir.file("agree.nrrd"), head + "spacings: 0.5 0.25 2\n\n" + data);
  EXPECT_NEAR(load(dir.file("agree.nrrd")).spacing()[2], 2, 1e-12);
  write_file(dir.file("nan.nrrd"), head + "spacings: nan nan nan\n\n" + data);  // teem's "not set"
  EXPECT_NEAR(load(dir.file("nan.nrrd")).spacing()[1], 0.25, 1e-12);
  write_file(dir.file("differ.nrrd"), head + "spacings: 0.5 0.25 3\n\n" + data);
  expect_error([&] { load(dir.file("differ.nrrd")); }, "differ.nrrd", "spacings");
  expect_error([&] { load(dir.file("differ.nrrd")); }, "differ.nrrd", "space directions");
  write_file(dir.file("flip.nrrd"), head + "spacings: -0.5 0.25 2\n\n" + data);
  expect_error([&] { load(dir.file("flip.nrrd")); }, "flip.nrrd", "disagree");
}

// `line skip: -1` was read as 0. Only `byte skip` has a -1 (the data end the file); a negative
// line count means nothing, so it is refused.
TEST(VolumeHeaderIntegrity, NrrdNegativeLineSkip) {
  TempDir dir;
  write_file(dir.file("l.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: raw\nline skip: -1\n\n" +
                                     std::string(60, '\1'));
  expect_error([&] { load(dir.file("l.nrrd")); }, "l.nrrd", "line skip");
}

// `sizes: 41 41.0 41` was read as 41 41 41: a size (and every other integer field) is written as
// an integer, so "41.0", "4e1" or "0x29" are refused as bad values.
TEST(VolumeHeaderIntegrity, IntegerFieldsMustBeWrittenAsIntegers) {
  TempDir dir;
  const std::string data(60, '\1');
  for (const std::string sizes : {"5 4.0 3", "5 4 3.", "5e0 4 3", "0x5 4 3"}) {
    SCOPED_TRACE(sizes);
    write_file(dir.file("s.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: " + sizes + "\nencoding: raw\n\n" + data);
    expect_error([&] { load(dir.file("s.nrrd")); }, "s.nrrd", "bad sizes '" + sizes + "'");
    write_file(dir.file("s.mha"), "NDims = 3\nDimSize = " + sizes + "\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + data);
    expect_error([&] { load(dir.file("s.mha")); }, "s.mha", "bad DimSize '" + sizes + "'");
  }
  write_file(dir.file("ok.nrrd"), "NRRD0004\ntype: uchar\ndimension: 3\nsizes: +5 4 3\nencoding: raw\n\n" + data);
  EXPECT_EQ(load(dir.file("ok.nrrd")).stats.voxels, 60u);
}

// MetaImage CompressedDataSize was ignored. It is checked against the compressed bytes present:
// fewer means a cut file, refused naming the field. More is read (no warning): the zlib stream
// decides where the data end, its Adler-32 and exact size vouch for them, and real files carry a
// stale count (VTK's frogtissue.mhd: 260020 for a 262087-byte stream, test_real_datasets.cpp).
TEST(VolumeHeaderIntegrity, MetaImageCompressedDataSizeIsChecked) {
  TempDir dir;
  const auto z = zlib_compress(to_bytes(ramp_values<std::uint8_t>()));
  const std::string head = "NDims = 3\nDimSize = 5 4 3\nElementType = MET_UCHAR\nCompressedData = True\n";
  auto mha = [&](const std::string& size_line, std::size_t keep) {
    std::string s = head + size_line + "ElementDataFile = LOCAL\n";
    s.append(z.begin(), z.begin() + long(keep));
    return s;
  };
  const std::string n = std::to_string(z.size());
  write_file(dir.file("ok.mha"), mha("CompressedDataSize = " + n + "\n", z.size()));
  EXPECT_EQ(load(dir.file("ok.mha")).stats.voxels, 60u);
  write_file(dir.file("none.mha"), mha("", z.size()));  // the field is optional
  EXPECT_EQ(load(dir.file("none.mha")).stats.voxels, 60u);
  write_file(dir.file("more.mha"), mha("CompressedDataSize = " + std::to_string(z.size() + 10) + "\n", z.size()));
  expect_error([&] { load(dir.file("more.mha")); }, "more.mha", "CompressedDataSize " + std::to_string(z.size() + 10));
  expect_error([&] { load(dir.file("more.mha")); }, "more.mha", "truncated");
  // A file cut by a few bytes under an intact count: refused naming the count.
  write_file(dir.file("cut.mha"), mha("CompressedDataSize = " + n + "\n", z.size() - 3));
  expect_error([&] { load(dir.file("cut.mha")); }, "cut.mha", "CompressedDataSize " + n);
  write_file(dir.file("stale.mha"), mha("CompressedDataSize = " + std::to_string(z.size() - 10) + "\n", z.size()));
  EXPECT_EQ(load(dir.file("stale.mha")).stats.voxels, 60u);
  write_file(dir.file("bad.mha"), mha("CompressedDataSize = -4\n", z.size()));
  expect_error([&] { load(dir.file("bad.mha")); }, "bad.mha", "CompressedDataSize");
  // A detached data file likewise.
  write_file(dir.file("d.zraw"), std::string(z.begin(), z.end()));
  write_file(dir.file("d.mhd"), head + "CompressedDataSize = " + std::to_string(z.size() + 1) + "\nElementDataFile = d.zraw\n");
  expect_error([&] { load(dir.file("d.mhd")); }, "d.zraw", "CompressedDataSize");
}
