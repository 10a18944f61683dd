// Each loader on a small file written here: values, dimensions, spacing, origin, inside side.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cmath>
#include <functional>

#include "core/progress.h"
#include "test_files.h"
#include "volume/load.h"

using namespace isocurv::volume;
using namespace voltest;

namespace {

using WorldOf = std::function<openvdb::Vec3d(int, int, int)>;

/// World position of voxel (x, y, z) for an axis-aligned image.
WorldOf axis_aligned(openvdb::Vec3d spacing, openvdb::Vec3d origin) {
  return [=](int x, int y, int z) { return origin + openvdb::Vec3d(x * spacing[0], y * spacing[1], z * spacing[2]); };
}

/// Checks that the 5x4x3 ramp voxel (x, y, z) of the file sits at world(x, y, z) in the grid,
/// and the bookkeeping fields.
void expect_ramp(const Volume& v, const WorldOf& world, const std::string& format, const std::string& type,
                 float scale = 1, float offset = 0) {
  ASSERT_TRUE(v.grid);
  EXPECT_EQ(v.format, format);
  EXPECT_EQ(v.voxel_type, type);
  EXPECT_TRUE(v.dense);
  EXPECT_EQ(v.domain.dim(), openvdb::Coord(5, 4, 3));
  EXPECT_EQ(v.inside, Inside::Above);
  EXPECT_EQ(v.stats.voxels, 60u);
  EXPECT_FLOAT_EQ(float(v.stats.min), offset);
  EXPECT_FLOAT_EQ(float(v.stats.max), scale * 234 + offset);
  auto acc = v.grid->getConstAccessor();
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) {
        const openvdb::Vec3d idx = v.grid->transform().worldToIndex(world(x, y, z));
        const openvdb::Coord c(int(std::lround(idx.x())), int(std::lround(idx.y())), int(std::lround(idx.z())));
        ASSERT_NEAR(idx.x(), c.x(), 1e-6);
        ASSERT_NEAR(idx.y(), c.y(), 1e-6);
        ASSERT_NEAR(idx.z(), c.z(), 1e-6);
        ASSERT_TRUE(v.domain.isInside(c)) << c;
        ASSERT_FLOAT_EQ(acc.getValue(c), scale * ramp(x, y, z) + offset) << x << " " << y << " " << z;
      }
}

}  // namespace

/// Writes the 5x4x3 big-endian uint16 ramp as dir/ramp.raw; `o` gets its layout.
std::string big_endian_ramp(TempDir& dir, LoadOptions& o) {
  const std::string path = dir.file("ramp.raw");
  write_file(path, to_bytes(ramp_values<std::uint16_t>(), /*big_endian=*/true));
  o.raw.dims = {5, 4, 3};
  o.raw.type = "uint16";
  o.raw.big_endian = true;
  return path;
}

TEST(VolumeLoadRaw, OptionsGiveTheLayout) {
  TempDir dir;
  LoadOptions o;
  const std::string path = big_endian_ramp(dir, o);
  o.raw.spacing = {0.5, 0.25, 2};
  o.raw.origin = {1, 2, 3};
  expect_ramp(load(path, o), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "raw", "uint16");
}

TEST(VolumeLoadRaw, BuildingTheGridReportsProgressToTheLoadStage) {
  TempDir dir;
  LoadOptions o;
  const std::string path = big_endian_ramp(dir, o);
  isocurv::StageBar bar("load");
  ASSERT_EQ(isocurv::stage_progress(), -1.0);
  load(path, o);
  EXPECT_EQ(isocurv::stage_progress(), 1.0) << "every block counted";
}

TEST(VolumeLoadRaw, FileNameGivesTheLayout) {
  TempDir dir;
  const std::string le = dir.file("ramp_5x4x3_int16le.raw");
  write_file(le, to_bytes(ramp_values<std::int16_t>()));
  expect_ramp(load(le), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "int16");
  const std::string be = dir.file("ramp_5x4x3_float32be.raw");
  write_file(be, to_bytes(ramp_values<float>(), true));
  expect_ramp(load(be), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "float");
  const std::string dbl = dir.file("Ramp_5x4x3_double_extra.raw");
  write_file(dbl, to_bytes(ramp_values<double>()));
  expect_ramp(load(dbl), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "double");
}

TEST(VolumeLoadRaw, GzipRawAndBinGz) {
  TempDir dir;
  const auto gz = gzip_compress(to_bytes(ramp_values<std::uint8_t>()));
  const std::string a = dir.file("ramp_5x4x3_uint8.raw.gz");
  write_file(a, gz);
  expect_ramp(load(a), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "uint8");
  const std::string b = dir.file("t1_5x4x3_uint8_1x1.bin-gz");
  write_file(b, gz);
  expect_ramp(load(b), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "uint8");
}

TEST(VolumeLoadRaw, InsideOverride) {
  TempDir dir;
  const std::string path = dir.file("ramp_5x4x3_int8.raw");
  write_file(path, to_bytes(ramp_values<std::int8_t>(5, 4, 1)) /* 5x4x1 has max 34 */);
  LoadOptions o;
  o.raw.dims = {5, 4, 1};
  o.raw.type = "int8";
  o.inside = Inside::Below;
  const Volume v = load(path, o);
  EXPECT_EQ(v.inside, Inside::Below);
  EXPECT_EQ(v.grid->background(), 34.0f);  // outside value: the maximum
}

TEST(VolumeLoadNrrd, AttachedRawWithSpaceDirections) {
  TempDir dir;
  const std::string path = dir.file("ramp.nrrd");
  std::string header =
      "NRRD0004\n# a comment\ntype: short\ndimension: 3\nsizes: 5 4 3\nendian: little\nencoding: raw\n"
      "space: right-anterior-superior\nspace directions: (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (1,2,3)\n"
      "my key:=my value\n\n";
  auto bytes = to_bytes(ramp_values<std::int16_t>());
  header.append(bytes.begin(), bytes.end());
  write_file(path, header);
  expect_ramp(load(path), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "nrrd", "int16");
}

TEST(VolumeLoadNrrd, SpaceNamesTheWorldAxesAndDirectionsFlipThem) {
  TempDir dir;
  auto bytes = to_bytes(ramp_values<std::int16_t>());
  auto write = [&](const std::string& name, const std::string& space, const std::string& dirs) {
    std::string header =
        "NRRD0004\ntype: short\ndimension: 3\nsizes: 5 4 3\nendian: little\n"
        "encoding: raw\n" +
        (space.empty() ? "" : "space: " + space + "\n") + "space directions: " + dirs +
        "\nspace origin: (10,20,30)\n\n";
    header.append(bytes.begin(), bytes.end());
    write_file(dir.file(name), header);
    return dir.file(name);
  };
  // LPS, as ITK/Slicer write it: index x runs towards -x (the patient's right), y towards -y
  const Volume lps =
      load(write("lps.nrrd", "left-posterior-superior", "(-0.5,0,0) (0,-0.25,0) (0,0,2)"));
  EXPECT_EQ(lps.world_space, "LPS");
  expect_ramp(
      lps,
      [](int x, int y, int z) { return openvdb::Vec3d(10 - 0.5 * x, 20 - 0.25 * y, 30 + 2.0 * z); },
      "nrrd", "int16");
  EXPECT_EQ(load(write("ras.nrrd", "RAS", "(0.5,0,0) (0,0.25,0) (0,0,2)")).world_space, "RAS");
  EXPECT_EQ(
      load(write("las.nrrd", "Left-Anterior-Superior", "(0.5,0,0) (0,0.25,0) (0,0,2)")).world_space,
      "LAS");
  EXPECT_EQ(load(write("xyz.nrrd", "scanner-xyz", "(0.5,0,0) (0,0.25,0) (0,0,2)")).world_space, "");
  EXPECT_EQ(load(write("none.nrrd", "", "(0.5,0,0) (0,0.25,0) (0,0,2)")).world_space, "");
  EXPECT_THROW(
      load(write("time.nrrd", "right-anterior-superior-time", "(0.5,0,0) (0,0.25,0) (0,0,2)")),
      isocurv::Error);
  try {
    load(write("bad.nrrd", "upside-down", "(0.5,0,0) (0,0.25,0) (0,0,2)"));
    ADD_FAILURE() << "an unknown space must fail";
  } catch (const isocurv::Error& e) {
    EXPECT_NE(std::string(e.what()).find("upside-down"), std::string::npos) << e.what();
  }
}

TEST(VolumeLoadNrrd, AttachedGzipBigEndianFloatWithSpacings) {
  TempDir dir;
  const std::string path = dir.file("ramp.nrrd");
  std::string header = "NRRD0004\ntype: float\ndimension: 3\nsizes: 5 4 3\nendian: big\nencoding: gzip\nspacings: 0.5 0.25 2\n\n";
  auto gz = gzip_compress(to_bytes(ramp_values<float>(), true));
  header.append(gz.begin(), gz.end());
  write_file(path, header);
  expect_ramp(load(path), axis_aligned({0.5, 0.25, 2}, {0, 0, 0}), "nrrd", "float");
}

TEST(VolumeLoadNrrd, DetachedHeaderAndAsciiData) {
  TempDir dir;
  write_file(dir.file("ramp.data"), to_bytes(ramp_values<std::uint16_t>(), true));
  write_file(dir.file("ramp.nhdr"),
             "NRRD0005\ntype: unsigned short\ndimension: 3\nsizes: 5 4 3\nendian: big\nencoding: raw\n"
             "space directions: (0,0.25,0) (0.5,0,0) (0,0,2)\nspace origin: (1,2,3)\ndata file: ramp.data\n");
  // Axes swapped: index x runs along world y, index y along world x; det < 0, so the loader
  // reverses X; world positions must still match.
  const Volume v = load(dir.file("ramp.nhdr"));
  expect_ramp(v, [](int x, int y, int z) { return openvdb::Vec3d(1 + 0.5 * y, 2 + 0.25 * x, 3 + 2.0 * z); }, "nrrd",
              "uint16");

  std::string ascii = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: ascii\n\n";
  for (float f : ramp_values<float>(5, 4, 3)) ascii += std::to_string(int(f) % 256) + (int(f) % 7 ? " " : "\n");
  write_file(dir.file("ascii.nrrd"), ascii);
  const Volume a = load(dir.file("ascii.nrrd"));
  EXPECT_EQ(a.grid->tree().getValue(openvdb::Coord(4, 3, 2)), float(234));
}

TEST(VolumeLoadMetaImage, MhdWithRawBigEndian) {
  TempDir dir;
  write_file(dir.file("ramp.raw"), to_bytes(ramp_values<std::int16_t>(), true));
  write_file(dir.file("ramp.mhd"),
             "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\nElementSpacing = 0.5 0.25 2\n"
             "Offset = 1 2 3\nElementByteOrderMSB = True\nElementDataFile = ramp.raw\n");
  expect_ramp(load(dir.file("ramp.mhd")), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "metaimage", "int16");
}

TEST(VolumeLoadMetaImage, MhaLocalAndCompressedWithRotation) {
  TempDir dir;
  std::string mha =
      "NDims = 3\nDimSize = 5 4 3\nElementType = MET_FLOAT\nElementSpacing = 0.5 0.25 2\nOrigin = 1 2 3\n"
      "ElementDataFile = LOCAL\n";
  const auto bytes = to_bytes(ramp_values<float>());
  mha.append(bytes.begin(), bytes.end());
  write_file(dir.file("ramp.mha"), mha);
  expect_ramp(load(dir.file("ramp.mha")), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "metaimage", "float");

  // Compressed data, and a 90-degree rotation about z: index x -> world +y, index y -> world -x.
  // CompressedDataSize must be the compressed bytes' count (tests/volume/test_header_integrity.cpp).
  const auto z = zlib_compress(to_bytes(ramp_values<std::uint8_t>()));
  write_file(dir.file("rot.zraw"), z);
  write_file(dir.file("rot.mhd"),
             "NDims = 3\nDimSize = 5 4 3\nElementType = MET_UCHAR\nElementSpacing = 0.5 0.25 2\nOffset = 1 2 3\n"
             "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nCompressedData = True\nCompressedDataSize = " +
                 std::to_string(z.size()) + "\nElementDataFile = rot.zraw\n");
  expect_ramp(load(dir.file("rot.mhd")),
              [](int x, int y, int z) { return openvdb::Vec3d(1 - 0.25 * y, 2 + 0.5 * x, 3 + 2.0 * z); }, "metaimage",
              "uint8");
}

namespace {

/// A NIfTI-1 single file (header, 4-byte extension flag, data) in either byte order.
std::vector<std::uint8_t> nifti_file(const std::vector<std::uint8_t>& data, short datatype, short bitpix, bool big_endian,
                                     const std::function<void(std::uint8_t*, bool)>& extra = {}) {
  std::vector<std::uint8_t> h(352, 0);
  auto put = [&](std::size_t off, auto value) {
    std::memcpy(&h[off], &value, sizeof(value));
    if (big_endian) std::reverse(h.begin() + long(off), h.begin() + long(off + sizeof(value)));
  };
  put(0, std::int32_t(348));
  put(40, std::int16_t(3));
  put(42, std::int16_t(5));
  put(44, std::int16_t(4));
  put(46, std::int16_t(3));
  for (int i = 4; i < 8; ++i) put(40 + 2 * std::size_t(i), std::int16_t(1));
  put(70, datatype);
  put(72, bitpix);
  put(76, 1.0f);
  put(80, 0.5f);
  put(84, 0.25f);
  put(88, 2.0f);
  put(108, 352.0f);
  std::memcpy(&h[344], "n+1", 4);
  if (extra) {
    // The callback writes through `put` semantics by itself.
  }
  std::vector<std::uint8_t> out = h;
  if (extra) extra(out.data(), big_endian);
  out.insert(out.end(), data.begin(), data.end());
  return out;
}

void put_field(std::uint8_t* h, std::size_t off, float value, bool big_endian) {
  std::memcpy(h + off, &value, 4);
  if (big_endian) std::reverse(h + off, h + off + 4);
}
void put_field(std::uint8_t* h, std::size_t off, std::int16_t value, bool big_endian) {
  std::memcpy(h + off, &value, 2);
  if (big_endian) std::reverse(h + off, h + off + 2);
}

}  // namespace

TEST(VolumeLoadNifti, LittleEndianPixdimOnly) {
  TempDir dir;
  write_file(dir.file("ramp.nii"), nifti_file(to_bytes(ramp_values<std::uint8_t>()), 2, 8, false));
  expect_ramp(load(dir.file("ramp.nii")), axis_aligned({0.5, 0.25, 2}, {0, 0, 0}), "nifti", "uint8");
}

TEST(VolumeLoadNifti, BigEndianGzipWithSformAndScaling) {
  TempDir dir;
  // sform: x axis flipped (radiological), so the loader reverses X to stay right-handed.
  auto file = nifti_file(to_bytes(ramp_values<std::int16_t>(), true), 4, 16, true, [](std::uint8_t* h, bool be) {
    put_field(h, 112, 2.0f, be);   // scl_slope
    put_field(h, 116, 1.0f, be);   // scl_inter
    put_field(h, 254, std::int16_t(2), be);  // sform_code
    const float srow[3][4] = {{-0.5f, 0, 0, 10}, {0, 0.25f, 0, 20}, {0, 0, 2, 30}};
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t c = 0; c < 4; ++c) put_field(h, 280 + 16 * r + 4 * c, srow[r][c], be);
  });
  write_file(dir.file("ramp.nii.gz"), gzip_compress(file));
  expect_ramp(load(dir.file("ramp.nii.gz")),
              [](int x, int y, int z) { return openvdb::Vec3d(10 - 0.5 * x, 20 + 0.25 * y, 30 + 2.0 * z); }, "nifti",
              "int16", 2.0f, 1.0f);
}

TEST(VolumeLoadNifti, QformOffset) {
  TempDir dir;
  auto file = nifti_file(to_bytes(ramp_values<float>()), 16, 32, false, [](std::uint8_t* h, bool be) {
    put_field(h, 252, std::int16_t(1), be);  // qform_code, identity quaternion
    put_field(h, 268, 1.0f, be);
    put_field(h, 272, 2.0f, be);
    put_field(h, 276, 3.0f, be);
  });
  write_file(dir.file("q.nii"), file);
  expect_ramp(load(dir.file("q.nii")), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "nifti", "float");
}

TEST(VolumeLoadVtk, XmlImageData) {
  TempDir dir;
  std::string values;
  for (float f : ramp_values<float>()) values += std::to_string(f) + " ";
  // Extent starting at 1 in x: the first voxel sits one spacing past the origin.
  write_file(dir.file("ramp.vti"),
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
             "<ImageData WholeExtent=\"1 5 0 3 0 2\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 2\">\n"
             "<Piece Extent=\"1 5 0 3 0 2\"><PointData Scalars=\"density\">\n"
             "<DataArray type=\"Float32\" Name=\"density\" format=\"ascii\">" + values +
                 "</DataArray>\n</PointData><CellData></CellData></Piece></ImageData></VTKFile>\n");
  const Volume v = load(dir.file("ramp.vti"));
  expect_ramp(v, axis_aligned({0.5, 0.25, 2}, {1.5, 2, 3}), "vti", "float");
  EXPECT_EQ(v.grid_name, "density");
}

TEST(VolumeLoadVtk, LegacyStructuredPoints) {
  TempDir dir;
  std::string text =
      "# vtk DataFile Version 3.0\nramp\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 5 4 3\nSPACING 0.5 0.25 2\n"
      "ORIGIN 1 2 3\nPOINT_DATA 60\nSCALARS density short 1\nLOOKUP_TABLE default\n";
  for (float f : ramp_values<float>()) text += std::to_string(int(f)) + "\n";
  write_file(dir.file("ramp.vtk"), text);
  expect_ramp(load(dir.file("ramp.vtk")), axis_aligned({0.5, 0.25, 2}, {1, 2, 3}), "vtk", "int16");
}

TEST(VolumeLoadDgtalVol, Version3ZlibAndVersion2Raw) {
  TempDir dir;
  const std::string header = "Center-X: 2\nCenter-Y: 2\nCenter-Z: 1\nX: 5\nY: 4\nZ: 3\nVoxel-Size: 1\nAlpha-Color: 0\n"
                             "Voxel-Endian: 0\nInt-Endian: 0123\n";
  std::string v3 = header + "Version: 3\n.\n";
  const auto z = zlib_compress(to_bytes(ramp_values<std::uint8_t>()));
  v3.append(z.begin(), z.end());
  write_file(dir.file("ramp3.vol"), v3);
  expect_ramp(load(dir.file("ramp3.vol")), axis_aligned({1, 1, 1}, {0, 0, 0}), "dgtal-vol", "uint8");

  std::string v2 = header + "Version: 2\n.\n";
  const auto raw = to_bytes(ramp_values<std::uint8_t>());
  v2.append(raw.begin(), raw.end());
  write_file(dir.file("ramp2.vol"), v2);
  expect_ramp(load(dir.file("ramp2.vol")), axis_aligned({1, 1, 1}, {0, 0, 0}), "dgtal-vol", "uint8");
}

TEST(VolumeLoadVdb, LevelSetFogAndDoubleGrids) {
  openvdb::initialize();
  TempDir dir;
  auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, openvdb::Vec3f(0.5f, 0, 0), 0.1f);
  sphere->setName("level_set");
  auto fog = openvdb::FloatGrid::create(0.0f);
  fog->setName("smoke");
  fog->setGridClass(openvdb::GRID_FOG_VOLUME);
  fog->tree().setValue(openvdb::Coord(1, 2, 3), 0.75f);
  fog->tree().setValue(openvdb::Coord(4, 2, 3), 0.25f);
  auto dbl = openvdb::DoubleGrid::create(0.0);
  dbl->setName("values_d");
  dbl->tree().setValue(openvdb::Coord(-3, 0, 0), 1.5);
  dbl->tree().fill(openvdb::CoordBBox(openvdb::Coord(16), openvdb::Coord(31)), 2.5, true);
  auto vec = openvdb::Vec3SGrid::create();
  vec->setName("a_velocity");
  vec->tree().setValue(openvdb::Coord(0), openvdb::Vec3s(1, 0, 0));
  const std::string path = dir.file("grids.vdb");
  openvdb::GridPtrVec grids{vec, sphere, fog, dbl};
  openvdb::io::File(path).write(grids);

  // First float grid in the file's listing (OpenVDB lists grids by name): the level set.
  const Volume ls = load(path);
  EXPECT_EQ(ls.grid_name, "level_set");
  EXPECT_EQ(ls.grid_class, "level set");
  EXPECT_EQ(ls.inside, Inside::Below);
  EXPECT_FALSE(ls.dense);
  EXPECT_EQ(ls.stats.suggested_isovalue, 0.0);
  EXPECT_EQ(ls.domain, sphere->evalActiveVoxelBoundingBox());
  EXPECT_EQ(ls.stats.voxels, sphere->activeVoxelCount());
  EXPECT_NEAR(ls.spacing().x(), 0.1, 1e-7);  // float voxel size
  EXPECT_LT(ls.stats.min, 0);

  LoadOptions o;
  o.grid = "smoke";
  const Volume f = load(path, o);
  EXPECT_EQ(f.grid_class, "fog volume");
  EXPECT_EQ(f.inside, Inside::Above);
  EXPECT_EQ(f.stats.voxels, 2u);
  EXPECT_EQ(f.stats.min, 0.25);
  EXPECT_EQ(f.stats.max, 0.75);
  EXPECT_EQ(f.domain, openvdb::CoordBBox(openvdb::Coord(1, 2, 3), openvdb::Coord(4, 2, 3)));

  o.grid = "values_d";
  o.inside = Inside::Below;
  const Volume d = load(path, o);
  EXPECT_EQ(d.voxel_type, "double");
  EXPECT_EQ(d.inside, Inside::Below);
  EXPECT_EQ(d.grid->tree().getValue(openvdb::Coord(-3, 0, 0)), 1.5f);
  EXPECT_EQ(d.grid->tree().getValue(openvdb::Coord(20, 20, 20)), 2.5f);
  EXPECT_EQ(d.stats.voxels, 1u + 16 * 16 * 16);
}

TEST(VolumeLoadOverrides, SpacingAndOriginReplaceTheHeaderAlongTheFilesAxes) {
  TempDir dir;
  write_file(dir.file("ramp.data"), to_bytes(ramp_values<std::uint16_t>(), true));
  write_file(
      dir.file("ramp.nhdr"),
      "NRRD0005\ntype: unsigned short\ndimension: 3\nsizes: 5 4 3\nendian: big\nencoding: raw\n"
      "space directions: (0,0.25,0) (0.5,0,0) (0,0,2)\nspace origin: (1,2,3)\n"
      "data file: ramp.data\n");
  LoadOptions o;
  o.spacing = std::array<double, 3>{1, 2, 3};
  o.origin = std::array<double, 3>{10, 20, 30};
  // The header's axes stay (index x along world y, a left-handed frame the loader reorders), the
  // spacing is along them and the origin is where the file's first voxel goes.
  const Volume v = load(dir.file("ramp.nhdr"), o);
  expect_ramp(
      v,
      [](int x, int y, int z) { return openvdb::Vec3d(10 + 2.0 * y, 20 + 1.0 * x, 30 + 3.0 * z); },
      "nrrd", "uint16");
  ASSERT_TRUE(v.file_spacing && v.file_origin);
  EXPECT_EQ(*v.file_spacing, openvdb::Vec3d(0.25, 0.5, 2));
  EXPECT_EQ(*v.file_origin, openvdb::Vec3d(1, 2, 3));
  EXPECT_FALSE(load(dir.file("ramp.nhdr")).file_spacing) << "no override, nothing recorded";

  write_file(dir.file("r.raw"), to_bytes(ramp_values<std::int16_t>(), true));
  write_file(dir.file("r.mhd"),
             "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
             "ElementSpacing = 0.5 0.25 2\nOffset = 1 2 3\nElementByteOrderMSB = True\n"
             "ElementDataFile = r.raw\n");
  LoadOptions s;
  s.spacing = std::array<double, 3>{1, 1, 1.4};
  expect_ramp(load(dir.file("r.mhd"), s), axis_aligned({1, 1, 1.4}, {1, 2, 3}), "metaimage",
              "int16");
}

TEST(VolumeLoadOverrides, SpacingAndOriginReplaceAVdbTransform) {
  TempDir dir;
  openvdb::initialize();
  auto grid =
      openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(4.0f, openvdb::Vec3f(0, 0, 0), 0.5f);
  openvdb::io::File file(dir.file("ball.vdb"));
  file.write(openvdb::GridPtrVec{grid});
  file.close();
  LoadOptions o;
  o.spacing = std::array<double, 3>{1, 2, 3};
  o.origin = std::array<double, 3>{5, 6, 7};
  const Volume v = load(dir.file("ball.vdb"), o);
  EXPECT_EQ(v.spacing(), openvdb::Vec3d(1, 2, 3));
  EXPECT_EQ(v.origin(), openvdb::Vec3d(5, 6, 7));
  EXPECT_EQ(v.grid->transform().indexToWorld(openvdb::Vec3d(1, 1, 1)), openvdb::Vec3d(6, 8, 10));
  ASSERT_TRUE(v.file_spacing);
  EXPECT_EQ(*v.file_spacing, openvdb::Vec3d(0.5, 0.5, 0.5));
}

TEST(VolumeLoadOverrides, AnExplicitByteOrderWinsOverTheFileName) {
  TempDir dir;
  const std::string path = dir.file("ramp_5x4x3_uint16le.raw");
  write_file(path, to_bytes(ramp_values<std::uint16_t>(), /*big_endian=*/true));
  LoadOptions o;
  o.raw.big_endian = true;
  expect_ramp(load(path, o), axis_aligned({1, 1, 1}, {0, 0, 0}), "raw", "uint16");
}

TEST(VolumeLoadOverrides, OptionsForAnotherFormatAreErrors) {
  TempDir dir;
  const std::string path = dir.file("ramp.nrrd");
  std::string nrrd = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n\n";
  const auto bytes = to_bytes(ramp_values<std::uint8_t>());
  nrrd.append(bytes.begin(), bytes.end());
  write_file(path, nrrd);
  LoadOptions dims;
  dims.raw.dims = {5, 4, 3};
  expect_error([&] { load(path, dims); }, path, "--dims");
  LoadOptions type;
  type.raw.type = "uint8";
  expect_error([&] { load(path, type); }, path, "--type");
  LoadOptions endian;
  endian.raw.big_endian = false;
  expect_error([&] { load(path, endian); }, path, "--endian");
  LoadOptions grid;
  grid.grid = "density";
  expect_error([&] { load(path, grid); }, path, "--grid");
  LoadOptions spacing;
  spacing.spacing = std::array<double, 3>{1, -1, 1};
  expect_error([&] { load(path, spacing); }, path, "--spacing");
}
