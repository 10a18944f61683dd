// LoadOptions::z_slab: raw, NRRD (raw encoding), MetaImage (raw binary data) and plain NIfTI
// files read in part, as the ranks of a distributed run read them: the same voxels and world
// positions as the whole read inside the slab (rounded out to whole 8-slice blocks), the whole
// file's domain, the slab's statistics, and LoadOptions::outside for non-finite voxels and the
// background. Formats and encodings that cannot seek (compressed, ASCII) read everything.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include "tests/volume/test_files.h"
#include "volume/load.h"

namespace isocurv {
namespace {

constexpr int kX = 20, kY = 17, kZ = 37;

float voxel(int x, int y, int z) { return float(x * 3 + y * 5 + z * 7 % 11) + 0.25f * float(z); }

std::vector<float> voxels() {
  std::vector<float> v(std::size_t(kX) * kY * kZ);
  for (int z = 0; z < kZ; ++z)
    for (int y = 0; y < kY; ++y)
      for (int x = 0; x < kX; ++x) v[(std::size_t(z) * kY + y) * kX + x] = voxel(x, y, z);
  v[(std::size_t(12) * kY + 3) * kX + 4] = std::numeric_limits<float>::quiet_NaN();  // in the slab
  return v;
}

// `nan_x`: where the NaN voxel lands in index space (kX - 1 - 4 when a left-handed frame made the
// loader reverse X).
void expect_slab_of(const volume::Volume& whole, const volume::Volume& part, int first, int last, int nan_x = 4) {
  ASSERT_TRUE(part.slab.has_value());
  EXPECT_EQ(part.slab->min().z(), first);
  EXPECT_EQ(part.slab->max().z(), last);
  EXPECT_EQ(part.domain, whole.domain) << "the domain stays the whole file's";
  // World positions: the slab's voxels sit where the whole read puts them.
  EXPECT_EQ(part.grid->transform(), whole.grid->transform());
  for (const openvdb::Coord& c : {openvdb::Coord(0, 0, first), openvdb::Coord(kX - 1, kY - 1, last),
                                  openvdb::Coord(kX - 1, 0, (first + last) / 2)})
    EXPECT_EQ(part.grid->indexToWorld(c), whole.grid->indexToWorld(c)) << c;
  auto a = whole.grid->getConstAccessor(), b = part.grid->getConstAccessor();
  std::size_t off = 0;
  for (int z = first; z <= last; ++z)
    for (int y = 0; y < kY; ++y)
      for (int x = 0; x < kX; ++x) {
        const openvdb::Coord c(x, y, z);
        if (x == nan_x && y == 3 && z == 12) continue;  // the NaN: each read's own outside value
        off += a.getValue(c) != b.getValue(c);
      }
  EXPECT_EQ(off, 0u);
  EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * (last - first + 1)) << "statistics of the slab read";
  EXPECT_EQ(part.stats.nan_count, first <= 12 && 12 <= last ? 1u : 0u) << "the NaN at z = 12";
}

TEST(Slab, RawReadsOnlyTheBlocksAskedFor) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::string path = dir.file("part_20x17x37_float32.raw");
  voltest::write_file(path, v.data(), v.size() * sizeof(float));
  const volume::Volume whole = volume::load(path);
  EXPECT_FALSE(whole.slab.has_value());
  volume::LoadOptions o;
  o.z_slab = {{9, 20}};  // rounded out to the blocks [8, 23]
  const volume::Volume part = volume::load(path, o);
  expect_slab_of(whole, part, 8, 23);
  // Outside the slab: the background, here the slab's own finite minimum...
  EXPECT_EQ(part.grid->getConstAccessor().getValue(openvdb::Coord(0, 0, 30)), float(part.stats.min));
  // ... or the value the caller gives (a rank: the whole volume's), for the NaN voxel too.
  o.outside = -5.0f;
  const volume::Volume given = volume::load(path, o);
  EXPECT_EQ(given.grid->background(), -5.0f);
  EXPECT_EQ(given.grid->getConstAccessor().getValue(openvdb::Coord(4, 3, 12)), -5.0f);
  // The last block is clamped to the file; a slab past the end reads the last block.
  o.z_slab = {{30, 99}};
  const volume::Volume tail = volume::load(path, o);
  expect_slab_of(whole, tail, 24, kZ - 1);
}

TEST(Slab, NrrdWithDetachedRawDataReadsInPart) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  voltest::write_file(dir.file("data.raw"), v.data(), v.size() * sizeof(float));
  const std::string nhdr = dir.file("part.nhdr");
  voltest::write_file(nhdr, "NRRD0004\ntype: float\ndimension: 3\nsizes: 20 17 37\nencoding: raw\nendian: little\n"
                            "spacings: 1 1 2.5\ndata file: data.raw\n\n");
  const volume::Volume whole = volume::load(nhdr);
  volume::LoadOptions o;
  o.z_slab = {{0, 15}};
  expect_slab_of(whole, volume::load(nhdr, o), 0, 15);
}

TEST(Slab, CompressedFilesAreReadWhole) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::vector<std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(v.data()),
                                        reinterpret_cast<const std::uint8_t*>(v.data() + v.size()));
  const std::string path = dir.file("part_20x17x37_float32.raw.gz");
  voltest::write_file(path, voltest::gzip_compress(bytes));
  volume::LoadOptions o;
  o.z_slab = {{8, 15}};
  const volume::Volume part = volume::load(path, o);
  EXPECT_FALSE(part.slab.has_value());
  EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * kZ);
}

std::vector<std::uint8_t> float_bytes(const std::vector<float>& v) {
  return {reinterpret_cast<const std::uint8_t*>(v.data()), reinterpret_cast<const std::uint8_t*>(v.data() + v.size())};
}

/// A MetaImage header for the test volume (float32, little endian) with `extra` lines before
/// ElementDataFile.
std::string mhd_header(const std::string& extra, const std::string& data_file) {
  return "ObjectType = Image\nNDims = 3\nDimSize = 20 17 37\nElementType = MET_FLOAT\nElementByteOrderMSB = False\n"
         "ElementSpacing = 0.5 0.75 1.25\nOffset = 1 -2 3\nTransformMatrix = 0 1 0 -1 0 0 0 0 1\n" +
         extra + "ElementDataFile = " + data_file + "\n";
}

TEST(Slab, MetaImageLocalReadsInPart) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::vector<std::uint8_t> bytes = float_bytes(v);
  std::string mha = mhd_header("", "LOCAL");
  mha.append(bytes.begin(), bytes.end());
  const std::string path = dir.file("part.mha");
  voltest::write_file(path, mha);
  const volume::Volume whole = volume::load(path);
  EXPECT_FALSE(whole.slab.has_value());
  volume::LoadOptions o;
  o.z_slab = {{9, 20}};
  expect_slab_of(whole, volume::load(path, o), 8, 23);
  o.z_slab = {{30, 99}};
  expect_slab_of(whole, volume::load(path, o), 24, kZ - 1);
}

TEST(Slab, MetaImageDataFileReadsInPart) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::vector<std::uint8_t> bytes = float_bytes(v);
  voltest::write_file(dir.file("part.raw"), bytes);
  const std::string mhd = dir.file("part.mhd");
  voltest::write_file(mhd, mhd_header("", "part.raw"));
  volume::LoadOptions o;
  o.z_slab = {{16, 16}};
  expect_slab_of(volume::load(mhd), volume::load(mhd, o), 16, 23);
  // HeaderSize -1: the voxels end the file, after bytes to skip; and HeaderSize n skips n bytes.
  std::vector<std::uint8_t> skipped(100, 0xee);
  skipped.insert(skipped.end(), bytes.begin(), bytes.end());
  voltest::write_file(dir.file("skip.raw"), skipped);
  for (const char* header_size : {"-1", "100"}) {
    const std::string skip = dir.file("skip.mhd");
    voltest::write_file(skip, mhd_header(std::string("HeaderSize = ") + header_size + "\n", "skip.raw"));
    const volume::Volume whole = volume::load(skip);
    o.z_slab = {{0, 7}};
    expect_slab_of(whole, volume::load(skip, o), 0, 7);
    o.z_slab = {{25, 36}};
    expect_slab_of(whole, volume::load(skip, o), 24, kZ - 1);
  }
  // Data too short for the header: one clear error, slab or not.
  voltest::write_file(dir.file("short.raw"), bytes.data(), bytes.size() - 4);
  voltest::write_file(dir.file("short.mhd"), mhd_header("", "short.raw"));
  o.z_slab = {{0, 7}};
  voltest::expect_error([&] { volume::load(dir.file("short.mhd"), o); }, "short.mhd", "holds");
}

TEST(Slab, MetaImageCompressedOrAsciiIsReadWhole) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  std::string mha = mhd_header("CompressedData = True\n", "LOCAL");
  const std::vector<std::uint8_t> z = voltest::zlib_compress(float_bytes(v));
  mha.append(z.begin(), z.end());
  voltest::write_file(dir.file("z.mha"), mha);
  std::string text = mhd_header("BinaryData = False\n", "LOCAL");
  for (float f : v) text += (std::isnan(f) ? std::string("0") : std::to_string(f)) + " ";
  voltest::write_file(dir.file("text.mha"), text);
  volume::LoadOptions o;
  o.z_slab = {{8, 15}};
  for (const char* name : {"z.mha", "text.mha"}) {
    const volume::Volume part = volume::load(dir.file(name), o);
    EXPECT_FALSE(part.slab.has_value()) << name;
    EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * kZ) << name;
  }
}

/// A NIfTI-1 single file of the test volume (float32, vox_offset 352, little endian); `header`
/// edits the 348-byte header (geometry, scaling).
std::vector<std::uint8_t> nifti_file(const std::vector<float>& v,
                                     const std::function<void(std::vector<std::uint8_t>&)>& header = {}) {
  std::vector<std::uint8_t> h(352, 0);
  auto put = [&](std::size_t off, auto value) { std::memcpy(&h[off], &value, sizeof(value)); };
  put(0, std::int32_t(348));
  put(40, std::int16_t(3));
  put(42, std::int16_t(kX));
  put(44, std::int16_t(kY));
  put(46, std::int16_t(kZ));
  for (int i = 4; i < 8; ++i) put(40 + 2 * std::size_t(i), std::int16_t(1));
  put(70, std::int16_t(16));  // float32
  put(72, std::int16_t(32));
  put(76, 1.0f);
  put(80, 0.5f);
  put(84, 0.75f);
  put(88, 1.25f);
  put(108, 352.0f);
  std::memcpy(&h[344], "n+1", 4);
  if (header) header(h);
  const std::vector<std::uint8_t> data = float_bytes(v);
  h.insert(h.end(), data.begin(), data.end());
  return h;
}

void put_f32(std::vector<std::uint8_t>& h, std::size_t off, float value) { std::memcpy(&h[off], &value, 4); }
void put_i16(std::vector<std::uint8_t>& h, std::size_t off, std::int16_t value) { std::memcpy(&h[off], &value, 2); }

TEST(Slab, NiftiReadsInPartWhateverItsOrientation) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  auto sform = [](std::vector<std::uint8_t>& h, float sx, float sz) {
    put_i16(h, 254, 2);  // sform_code
    const float srow[3][4] = {{sx, 0, 0, 10}, {0, 0.75f, 0, 20}, {0, 0, sz, 30}};
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t c = 0; c < 4; ++c) put_f32(h, 280 + 16 * r + 4 * c, srow[r][c]);
  };
  // File slice k is index z k for every geometry (the orientation lives in the transform, and
  // finish_dense reverses X alone): pixdim only; an sform with X flipped (left-handed: X is
  // reversed) and scl_slope/scl_inter; an sform with X and Z flipped (right-handed, Z pointing
  // down); a qform with qfac -1 (Z flipped, left-handed).
  const bool left_handed[] = {false, true, false, true};
  const std::vector<std::function<void(std::vector<std::uint8_t>&)>> headers{
      {},
      [&](std::vector<std::uint8_t>& h) {
        sform(h, -0.5f, 1.25f);
        put_f32(h, 112, 2.0f);   // scl_slope
        put_f32(h, 116, -3.0f);  // scl_inter
      },
      [&](std::vector<std::uint8_t>& h) { sform(h, -0.5f, -1.25f); },
      [](std::vector<std::uint8_t>& h) {
        put_f32(h, 76, -1.0f);  // qfac
        put_i16(h, 252, 1);     // qform_code, a quarter turn about Z
        put_f32(h, 264, std::sqrt(0.5f));
        put_f32(h, 268, 1.0f);
        put_f32(h, 272, 2.0f);
        put_f32(h, 276, 3.0f);
      }};
  for (std::size_t i = 0; i < headers.size(); ++i) {
    SCOPED_TRACE("header " + std::to_string(i));
    const std::string path = dir.file("part" + std::to_string(i) + ".nii");
    voltest::write_file(path, nifti_file(v, headers[i]));
    const volume::Volume whole = volume::load(path);
    EXPECT_FALSE(whole.slab.has_value());
    volume::LoadOptions o;
    const int nan_x = left_handed[i] ? kX - 1 - 4 : 4;
    o.z_slab = {{9, 20}};
    expect_slab_of(whole, volume::load(path, o), 8, 23, nan_x);
    o.z_slab = {{36, 36}};
    expect_slab_of(whole, volume::load(path, o), 32, kZ - 1, nan_x);
  }
  // A payload shorter than the header's dimensions: one clear error, slab or not.
  std::vector<std::uint8_t> cut = nifti_file(v);
  cut.resize(cut.size() - 4);
  voltest::write_file(dir.file("cut.nii"), cut);
  volume::LoadOptions o;
  o.z_slab = {{0, 7}};
  voltest::expect_error([&] { volume::load(dir.file("cut.nii"), o); }, "cut.nii", "holds");
}

TEST(Slab, NiftiGzipIsReadWhole) {
  voltest::TempDir dir;
  const std::string path = dir.file("part.nii.gz");
  voltest::write_file(path, voltest::gzip_compress(nifti_file(voxels())));
  volume::LoadOptions o;
  o.z_slab = {{8, 15}};
  const volume::Volume part = volume::load(path, o);
  EXPECT_FALSE(part.slab.has_value());
  EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * kZ);
}

}  // namespace
}  // namespace isocurv
