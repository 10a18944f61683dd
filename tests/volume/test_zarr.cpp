// The Zarr reader (volume/zarr.h, volume/load_zarr.cpp, volume/detail/zarr_*.cpp): small stores
// written here (v2 and v3, every codec, sharded and not, nested keys, F order, missing chunks,
// OME-NGFF 0.4 and 0.5 with scale and translation, a 5-D t/c/z/y/x store), each compared voxel
// for voxel with the same data written as NRRD and read by the NRRD loader; and bad stores, one
// Error each.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <limits>

#include "tests/volume/test_files.h"
#include "tests/volume/zarr_store_writer.h"
#include "volume/load.h"
#include "volume/zarr.h"

using namespace isocurv::volume;
using zarrtest::Array;
using zarrtest::Index;

namespace {

constexpr int kZx = 7, kZy = 6, kZz = 5;  // the test volume: x fastest

/// The 3-D test array (z, y, x), values x + 10 y + 100 z (+ `bias`).
Array zarr_test_array(const std::string& type = "u2", bool big = false, double bias = 0) {
  Array a;
  a.shape = {kZz, kZy, kZx};
  a.type = type;
  a.big = big;
  for (int z = 0; z < kZz; ++z)
    for (int y = 0; y < kZy; ++y)
      for (int x = 0; x < kZx; ++x) a.values.push_back(x + 10 * y + 100 * z + bias);
  return a;
}

/// The same voxels (x fastest, nx ny nz) as a float NRRD, read by the NRRD loader with the given
/// spacing and origin.
Volume zarr_reference(const voltest::TempDir& dir, const std::vector<double>& values, std::array<int, 3> dims,
                      std::array<double, 3> spacing = {1, 1, 1}, std::array<double, 3> origin = {0, 0, 0}) {
  std::vector<float> f(values.begin(), values.end());
  std::string text = "NRRD0004\ntype: float\ndimension: 3\nsizes: " + std::to_string(dims[0]) + " " +
                     std::to_string(dims[1]) + " " + std::to_string(dims[2]) + "\nencoding: raw\nendian: little\n\n";
  const std::string path = dir.file("reference.nrrd");
  text.append(reinterpret_cast<const char*>(f.data()), f.size() * sizeof(float));
  voltest::write_file(path, text);
  LoadOptions o;
  o.spacing = spacing;
  o.origin = origin;
  return load(path, o);
}

void expect_same_volume(const Volume& zarr, const Volume& ref, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(zarr.grid && ref.grid);
  EXPECT_EQ(zarr.format, "zarr");
  EXPECT_EQ(zarr.domain, ref.domain);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(zarr.spacing()[i], ref.spacing()[i]) << "axis " << i;
    EXPECT_DOUBLE_EQ(zarr.origin()[i], ref.origin()[i]) << "axis " << i;
  }
  const auto za = zarr.grid->getConstAccessor(), ra = ref.grid->getConstAccessor();
  int bad = 0;
  for (auto it = ref.domain.begin(); it; ++it) {
    const float a = za.getValue(*it), b = ra.getValue(*it);
    if (!(a == b) && bad++ < 5) ADD_FAILURE() << "voxel " << *it << ": zarr " << a << ", reference " << b;
  }
  EXPECT_EQ(bad, 0);
}

std::vector<std::uint8_t> zarr_identity(const std::vector<std::uint8_t>& b) { return b; }

}  // namespace

TEST(Zarr, Crc32cKnownAnswer) {
  const std::string s = "123456789";
  EXPECT_EQ(zarr_detail::crc32c(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()), 0xE3069283u);
}

TEST(Zarr, V2EveryCompressorFlatKeys) {
  const Array a = zarr_test_array();
  const Index chunks{2, 4, 3};
  struct Case {
    const char* name;
    std::string compressor;
    zarrtest::Encode encode;
  };
  const std::vector<Case> cases{
      {"none", "null", zarr_identity},
      {"zlib", "{\"id\": \"zlib\", \"level\": 5}", voltest::zlib_compress},
      {"gzip", "{\"id\": \"gzip\", \"level\": 5}", voltest::gzip_compress},
      {"zstd", "{\"id\": \"zstd\", \"level\": 3}", zarrtest::zstd_compress},
      {"blosc", "{\"id\": \"blosc\", \"cname\": \"zstd\", \"clevel\": 5, \"shuffle\": 1}",
       [](const std::vector<std::uint8_t>& b) { return zarrtest::blosc_compress(b, 2); }},
  };
  voltest::TempDir dir;
  const Volume ref = zarr_reference(dir, a.values, {kZx, kZy, kZz});
  for (const Case& c : cases) {
    const std::string store = dir.file(std::string(c.name) + ".zarr");
    std::filesystem::create_directories(store);
    voltest::write_file(store + "/.zarray", zarrtest::zarray(a, chunks, c.compressor));
    zarrtest::write_chunks(store, a, chunks, c.encode, ".", false);
    const Volume v = load(store);
    expect_same_volume(v, ref, c.name);
    EXPECT_EQ(v.voxel_type, "uint16");
  }
}

TEST(Zarr, V2NestedKeysFOrderBigEndianAndTypes) {
  voltest::TempDir dir;
  for (const std::string type : {"u1", "i1", "i2", "u4", "i4", "f4", "f8"}) {
    const bool big = type != "u1" && type != "i1";
    const Array a = zarr_test_array(type, big, type[0] == 'i' ? -250 : 0.5 * (type[0] == 'f'));
    const std::string store = dir.file(type + ".zarr");
    std::filesystem::create_directories(store);
    voltest::write_file(store + "/.zarray", zarrtest::zarray(a, {3, 2, 4}, "{\"id\": \"zlib\"}", "0", "F", "/"));
    zarrtest::write_chunks(store, a, {3, 2, 4}, voltest::zlib_compress, "/", false, true);
    std::vector<double> expected = a.values;
    for (double& e : expected) {  // the type's own range
      if (type == "u1") e = double(std::uint8_t(int(e)));
      if (type == "i1") e = double(std::int8_t(int(e)));
    }
    expect_same_volume(load(store), zarr_reference(dir, expected, {kZx, kZy, kZz}), type);
  }
}

TEST(Zarr, MissingChunksAreTheFillValue) {
  voltest::TempDir dir;
  const Array a = zarr_test_array("f4");
  const Index chunks{2, 4, 3};
  for (const std::string fill : {"7", "\"NaN\""}) {
    const std::string store = dir.file("fill" + std::to_string(fill.size()) + ".zarr");
    std::filesystem::create_directories(store);
    voltest::write_file(store + "/.zarray", zarrtest::zarray(a, chunks, "{\"id\": \"zstd\"}", fill));
    // Chunk (1, 0, 2): z 2-3, y 0-3, x 6 (an edge chunk); chunk (2, 1, 0): z 4, y 4-5, x 0-2.
    zarrtest::write_chunks(store, a, chunks, zarrtest::zstd_compress, ".", false, false, {{1, 0, 2}, {2, 1, 0}});
    std::vector<double> expected = a.values;
    const double f = fill == "7" ? 7.0 : std::numeric_limits<double>::quiet_NaN();
    for (int z = 0; z < kZz; ++z)
      for (int y = 0; y < kZy; ++y)
        for (int x = 0; x < kZx; ++x)
          if ((z / 2 == 1 && y / 4 == 0 && x / 3 == 2) || (z / 2 == 2 && y / 4 == 1 && x / 3 == 0))
            expected[std::size_t(x + kZx * (y + kZy * z))] = f;
    const Volume v = load(store);
    expect_same_volume(v, zarr_reference(dir, expected, {kZx, kZy, kZz}), "fill " + fill);
    if (fill != "7") {
      EXPECT_EQ(v.stats.nan_count, 2u * 4 * 1 + 1u * 2 * 3);
    }
  }
}

TEST(Zarr, V3EveryCodecAndKeyEncoding) {
  voltest::TempDir dir;
  const Array a = zarr_test_array("u2", false);
  const Array big = zarr_test_array("i2", true, -300);
  const Index chunks{2, 4, 3};
  const Volume ref = zarr_reference(dir, a.values, {kZx, kZy, kZz});
  struct Case {
    const char* name;
    const Array* array;
    std::string codecs;
    zarrtest::Encode encode;
    std::string keys = "{\"name\": \"default\"}";
    std::string sep = "/";
    bool c_prefix = true;
  };
  const std::string bytes = "{\"name\": \"bytes\", \"configuration\": {\"endian\": \"little\"}}";
  const std::vector<Case> cases{
      {"bytes", &a, "[" + bytes + "]", zarr_identity},
      {"gzip", &a, "[" + bytes + ", {\"name\": \"gzip\", \"configuration\": {\"level\": 5}}]", voltest::gzip_compress},
      {"zstd", &a, "[" + bytes + ", {\"name\": \"zstd\", \"configuration\": {\"level\": 3, \"checksum\": false}}]",
       zarrtest::zstd_compress},
      {"blosc", &a,
       "[" + bytes + ", {\"name\": \"blosc\", \"configuration\": {\"cname\": \"zstd\", \"clevel\": 5, \"shuffle\": "
                     "\"shuffle\", \"typesize\": 2, \"blocksize\": 0}}]",
       [](const std::vector<std::uint8_t>& b) { return zarrtest::blosc_compress(b, 2); }},
      {"v2 keys", &a, "[" + bytes + "]", zarr_identity, "{\"name\": \"v2\", \"configuration\": {\"separator\": \".\"}}",
       ".", false},
      {"dot keys", &a, "[" + bytes + ", {\"name\": \"crc32c\"}]",
       [](const std::vector<std::uint8_t>& b) {
         std::vector<std::uint8_t> out = b;
         const std::uint32_t crc = zarr_detail::crc32c(b.data(), b.size());
         for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(crc >> (8 * k)));
         return out;
       },
       "{\"name\": \"default\", \"configuration\": {\"separator\": \".\"}}", ".", true},
  };
  for (const Case& c : cases) {
    const std::string store = dir.file(std::string("v3_") + c.name + ".zarr");
    std::filesystem::create_directories(store);
    voltest::write_file(store + "/zarr.json", zarrtest::zarr_json_array(*c.array, chunks, c.codecs, "0", c.keys));
    zarrtest::write_chunks(store, *c.array, chunks, c.encode, c.sep, c.c_prefix);
    expect_same_volume(load(store), ref, c.name);
  }
  // transpose + big-endian bytes: the chunks are stored in F order (the transpose [2, 1, 0]).
  const std::string store = dir.file("v3_transpose.zarr");
  std::filesystem::create_directories(store);
  voltest::write_file(store + "/zarr.json",
                      zarrtest::zarr_json_array(big, chunks,
                                                "[{\"name\": \"transpose\", \"configuration\": {\"order\": [2, 1, 0]}}, "
                                                "{\"name\": \"bytes\", \"configuration\": {\"endian\": \"big\"}}, "
                                                "{\"name\": \"zstd\", \"configuration\": {\"level\": 1}}]"));
  zarrtest::write_chunks(store, big, chunks, zarrtest::zstd_compress, "/", true, true);
  expect_same_volume(load(store), zarr_reference(dir, big.values, {kZx, kZy, kZz}), "transpose");
}

TEST(Zarr, V3ShardedIndexAtEitherEndAndMissingInnerChunks) {
  voltest::TempDir dir;
  const Array a = zarr_test_array("u2");
  const Index shard{4, 4, 4}, inner{2, 2, 2};
  for (const bool at_end : {true, false}) {
    const std::string store = dir.file(at_end ? "end.zarr" : "start.zarr");
    std::filesystem::create_directories(store);
    const std::string codecs =
        "[{\"name\": \"sharding_indexed\", \"configuration\": {\"chunk_shape\": [2, 2, 2], \"codecs\": "
        "[{\"name\": \"bytes\", \"configuration\": {\"endian\": \"little\"}}, {\"name\": \"gzip\", "
        "\"configuration\": {\"level\": 1}}], \"index_codecs\": [{\"name\": \"bytes\", \"configuration\": "
        "{\"endian\": \"little\"}}, {\"name\": \"crc32c\"}], \"index_location\": \"" +
        std::string(at_end ? "end" : "start") + "\"}}]";
    voltest::write_file(store + "/zarr.json", zarrtest::zarr_json_array(a, shard, codecs, "3"));
    // Inner chunk (1, 2, 3): z 2-3, y 4-5, x 6 (at the edge) left out: the fill value 3.
    zarrtest::write_shards(store, a, shard, inner, voltest::gzip_compress, at_end, {{1, 2, 3}});
    std::vector<double> expected = a.values;
    for (int z = 2; z < 4; ++z)
      for (int y = 4; y < 6; ++y) expected[std::size_t(6 + kZx * (y + kZy * z))] = 3;
    const Volume v = load(store);
    expect_same_volume(v, zarr_reference(dir, expected, {kZx, kZy, kZz}), at_end ? "index at end" : "index at start");
    const ZarrInfo info = describe_zarr(store);
    EXPECT_EQ(info.levels.at(0).inner_chunks, (std::vector<long long>{2, 2, 2}));
    EXPECT_NE(info.codecs.find("sharding_indexed"), std::string::npos) << info.codecs;
  }
}

namespace {

/// An OME-NGFF 0.4 store with two levels: "0" the array, "1" every second voxel.
std::string write_ome04(const voltest::TempDir& dir, const Array& a, Array& half) {
  const std::string store = dir.file("image.ome.zarr");
  std::filesystem::create_directories(store + "/0");
  std::filesystem::create_directories(store + "/1");
  half.shape = {(a.shape[0] + 1) / 2, (a.shape[1] + 1) / 2, (a.shape[2] + 1) / 2};
  half.type = a.type;
  half.values.clear();
  for (long long z = 0; z < a.shape[0]; z += 2)
    for (long long y = 0; y < a.shape[1]; y += 2)
      for (long long x = 0; x < a.shape[2]; x += 2)
        half.values.push_back(a.values[std::size_t(x + a.shape[2] * (y + a.shape[1] * z))]);
  voltest::write_file(store + "/.zgroup", "{\"zarr_format\": 2}");
  voltest::write_file(
      store + "/.zattrs",
      R"({"multiscales": [{"version": "0.4", "name": "test",
          "axes": [{"name": "z", "type": "space", "unit": "micrometer"},
                   {"name": "y", "type": "space", "unit": "micrometer"},
                   {"name": "x", "type": "space", "unit": "micrometer"}],
          "datasets": [
            {"path": "0", "coordinateTransformations": [{"type": "scale", "scale": [1.5, 0.5, 0.25]},
                                                        {"type": "translation", "translation": [3, 2, 1]}]},
            {"path": "1", "coordinateTransformations": [{"type": "scale", "scale": [3, 1, 0.5]},
                                                        {"type": "translation", "translation": [3.75, 2.25, 1.125]}]}],
          "coordinateTransformations": [{"type": "scale", "scale": [2, 2, 2]}]}]})");
  voltest::write_file(store + "/0/.zarray", zarrtest::zarray(a, {2, 4, 3}, "{\"id\": \"blosc\", \"cname\": \"lz4\"}"));
  zarrtest::write_chunks(store + "/0", a, {2, 4, 3}, [](const std::vector<std::uint8_t>& b) { return zarrtest::blosc_compress(b, 2); },
                         ".", false);
  voltest::write_file(store + "/1/.zarray", zarrtest::zarray(half, {2, 2, 2}, "null"));
  zarrtest::write_chunks(store + "/1", half, {2, 2, 2}, zarr_identity, ".", false);
  return store;
}

}  // namespace

TEST(Zarr, OmeNgff04LevelsScaleTranslationAndUnit) {
  voltest::TempDir dir;
  const Array a = zarr_test_array();
  Array half;
  const std::string store = write_ome04(dir, a, half);
  // Level 0: spacing (x y z) = 2 * (0.25, 0.5, 1.5), origin 2 * (1, 2, 3): the dataset's
  // transformations, then the multiscale's.
  const Volume v0 = load(store);
  expect_same_volume(v0, zarr_reference(dir, a.values, {kZx, kZy, kZz}, {0.5, 1, 3}, {2, 4, 6}), "level 0");
  EXPECT_EQ(v0.length_unit, "um");
  LoadOptions o;
  o.level = 1;
  const Volume v1 = load(store, o);
  expect_same_volume(v1, zarr_reference(dir, half.values, {4, 3, 3}, {1, 2, 6}, {2.25, 4.5, 7.5}), "level 1");
  const ZarrInfo info = describe_zarr(store);
  EXPECT_EQ(info.ome_version, "0.4");
  ASSERT_EQ(info.levels.size(), 2u);
  EXPECT_EQ(info.default_level, 0);
  EXPECT_EQ(info.levels[1].dims, (std::array<long long, 3>{4, 3, 3}));
  const std::string text = zarr_summary_text(info, 1);
  EXPECT_NE(text.find("OME-NGFF 0.4"), std::string::npos) << text;
  EXPECT_NE(text.find("blosc(lz4)"), std::string::npos) << text;
  EXPECT_NE(text.find("<- read"), std::string::npos) << text;
  const auto j = zarr_summary_json(info, 1);
  EXPECT_EQ(j["levels"][1]["shape"], nlohmann::json::parse("[3, 3, 4]"));
  EXPECT_EQ(j["length_unit"], "um");
}

TEST(Zarr, OmeNgff05FiveDimensionsPicksTimePointAndChannel) {
  voltest::TempDir dir;
  // t = 2, c = 3, then z y x; value = x + 10 y + 100 z + 1000 c + 5000 t.
  Array a;
  a.shape = {2, 3, kZz, kZy, kZx};
  a.type = "u2";
  for (int t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c)
      for (int z = 0; z < kZz; ++z)
        for (int y = 0; y < kZy; ++y)
          for (int x = 0; x < kZx; ++x) a.values.push_back(x + 10 * y + 100 * z + 1000 * c + 5000 * t);
  const std::string store = dir.file("cells.ome.zarr");
  std::filesystem::create_directories(store + "/0");
  voltest::write_file(store + "/zarr.json", R"({"zarr_format": 3, "node_type": "group", "attributes": {"ome": {
      "version": "0.5", "multiscales": [{"name": "cells",
        "axes": [{"name": "t", "type": "time", "unit": "second"}, {"name": "c", "type": "channel"},
                 {"name": "z", "type": "space", "unit": "millimeter"}, {"name": "y", "type": "space", "unit": "millimeter"},
                 {"name": "x", "type": "space", "unit": "millimeter"}],
        "datasets": [{"path": "0", "coordinateTransformations": [{"type": "scale", "scale": [1, 1, 2, 1, 1]}]}]}]}}})");
  voltest::write_file(store + "/0/zarr.json",
                      zarrtest::zarr_json_array(a, {1, 2, 2, 4, 3},
                                                "[{\"name\": \"bytes\", \"configuration\": {\"endian\": \"little\"}}, "
                                                "{\"name\": \"zstd\", \"configuration\": {\"level\": 3}}]"));
  zarrtest::write_chunks(store + "/0", a, {1, 2, 2, 4, 3}, zarrtest::zstd_compress, "/", true);
  auto slice = [&](int t, int c) {
    std::vector<double> v;
    const std::size_t n = std::size_t(kZx * kZy * kZz);
    const std::size_t first = std::size_t(t * 3 + c) * n;
    v.assign(a.values.begin() + long(first), a.values.begin() + long(first + n));
    return v;
  };
  LoadOptions o;
  o.channel = 1;
  const Volume v = load(store, o);
  expect_same_volume(v, zarr_reference(dir, slice(0, 1), {kZx, kZy, kZz}, {1, 1, 2}), "t 0 c 1");
  EXPECT_EQ(v.length_unit, "mm");
  o.time_point = 1;
  o.channel = 2;
  expect_same_volume(load(store, o), zarr_reference(dir, slice(1, 2), {kZx, kZy, kZz}, {1, 1, 2}), "t 1 c 2");
  o.channel = 3;
  voltest::expect_error([&] { load(store, o); }, store, "--channel 3 is outside axis 'c' (0 to 2)");
}

TEST(Zarr, DimensionNamesPutXFastest) {
  // A v3 array stored x slowest (dimension_names x y z): the volume still has x fastest.
  voltest::TempDir dir;
  Array a;
  a.shape = {kZx, kZy, kZz};
  a.type = "i4";
  for (int x = 0; x < kZx; ++x)
    for (int y = 0; y < kZy; ++y)
      for (int z = 0; z < kZz; ++z) a.values.push_back(x + 10 * y + 100 * z);
  const std::string store = dir.file("xyz.zarr");
  std::filesystem::create_directories(store);
  std::string meta = zarrtest::zarr_json_array(a, {3, 4, 2}, "[{\"name\": \"bytes\"}]");
  meta.insert(meta.size() - 1, ", \"dimension_names\": [\"x\", \"y\", \"z\"]");
  voltest::write_file(store + "/zarr.json", meta);
  zarrtest::write_chunks(store, a, {3, 4, 2}, zarr_identity, "/", true);
  const Volume v = load(store);
  expect_same_volume(v, zarr_reference(dir, zarr_test_array().values, {kZx, kZy, kZz}), "x y z");
  EXPECT_EQ(v.voxel_type, "int32");
}

TEST(Zarr, ResultDoesNotDependOnTheThreadCount) {
  voltest::TempDir dir;
  Array a;
  a.shape = {24, 20, 22};
  a.type = "f4";
  for (int i = 0; i < 24 * 20 * 22; ++i) a.values.push_back(std::sin(0.01 * i) * 100);
  const std::string store = dir.file("threads.zarr");
  std::filesystem::create_directories(store);
  voltest::write_file(store + "/.zarray", zarrtest::zarray(a, {5, 6, 7}, "{\"id\": \"zstd\"}"));
  zarrtest::write_chunks(store, a, {5, 6, 7}, zarrtest::zstd_compress, ".", false);
  const Volume many = load(store);
  Volume one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = load(store);
  }
  expect_same_volume(many, one, "1 thread against all");
  expect_same_volume(many, zarr_reference(dir, a.values, {22, 20, 24}), "reference");
}

TEST(Zarr, BadStoresAreOneError) {
  voltest::TempDir dir;
  const Array a = zarr_test_array();
  auto store_with = [&](const std::string& name, const std::string& zarray) {
    const std::string store = dir.file(name);
    std::filesystem::create_directories(store);
    if (!zarray.empty()) voltest::write_file(store + "/.zarray", zarray);
    return store;
  };
  const std::string good = zarrtest::zarray(a, {2, 4, 3}, "null");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  using voltest::expect_error;
  // Missing or malformed metadata.
  const std::string empty = store_with("empty.zarr", "");
  expect_error([&] { load(empty); }, empty, "not a Zarr store");
  expect_error([&] { load(dir.file("absent.zarr")); }, "absent.zarr", "not one (or does not exist)");
  const std::string broken = store_with("broken.zarr", "{\"zarr_format\": 2, \"shape\": [5, ");
  expect_error([&] { load(broken); }, broken + "/.zarray", "malformed JSON");
  const std::string noshape = store_with("noshape.zarr", with("\"shape\"", "\"shapes\""));
  expect_error([&] { load(noshape); }, noshape + "/.zarray", "no \"shape\"");
  const std::string wrongtype = store_with("wrongtype.zarr", with("\"shape\": [5, 6, 7]", "\"shape\": \"5 6 7\""));
  expect_error([&] { load(wrongtype); }, wrongtype + "/.zarray", "not a list of integers");
  // Unknown codec, unsupported dtype.
  const std::string lz = store_with("lzma.zarr", with("\"compressor\": null", "\"compressor\": {\"id\": \"lzma\"}"));
  expect_error([&] { load(lz); }, lz + "/.zarray", "unknown Zarr compressor 'lzma'");
  const std::string v3 = dir.file("v3codec.zarr");
  std::filesystem::create_directories(v3);
  voltest::write_file(v3 + "/zarr.json", zarrtest::zarr_json_array(a, {2, 4, 3}, "[{\"name\": \"bytes\"}, {\"name\": \"lz5\"}]"));
  expect_error([&] { load(v3); }, v3 + "/zarr.json", "unknown Zarr codec 'lz5'");
  const std::string i8 = store_with("i8.zarr", with("\"<u2\"", "\"<i8\""));
  expect_error([&] { load(i8); }, i8 + "/.zarray", "dtype '<i8' is not supported");
  // Shapes that overflow, or exceed the memory budget; a chunk too large to decode.
  const std::string huge = store_with("huge.zarr", with("[5, 6, 7]", "[4611686018427387904, 4611686018427387904, 7]"));
  expect_error([&] { load(huge); }, huge + "/.zarray", "overflows");
  const std::string big = store_with("big.zarr", with("[5, 6, 7]", "[100000, 100000, 10000]"));
  expect_error([&] { load(big); }, big, "exceeds the memory budget");
  const std::string bigchunk = store_with("bigchunk.zarr", with("[2, 4, 3]", "[100000, 100000, 3]"));
  expect_error([&] { load(bigchunk); }, bigchunk + "/.zarray", "chunk shape is too large");
  // A chunk of the wrong size, a corrupt compressed chunk: named by its path.
  const std::string shortc = store_with("short.zarr", good);
  zarrtest::write_chunks(shortc, a, {2, 4, 3}, zarr_identity, ".", false);
  voltest::write_file(shortc + "/1.1.1", std::string(10, '\0'));
  expect_error([&] { load(shortc); }, shortc + "/1.1.1", "decoded chunk has 10 bytes, expected 48 bytes");
  voltest::write_file(shortc + "/1.1.1", std::string(3 << 20, '\0'));
  expect_error([&] { load(shortc); }, shortc + "/1.1.1", "more than a chunk of 48 bytes can take");
  const std::string corrupt = store_with("corrupt.zarr", with("\"compressor\": null", "\"compressor\": {\"id\": \"zstd\"}"));
  zarrtest::write_chunks(corrupt, a, {2, 4, 3}, zarrtest::zstd_compress, ".", false);
  voltest::write_file(corrupt + "/0.0.0", std::string("garbage, not zstd"));
  expect_error([&] { load(corrupt); }, corrupt + "/0.0.0", "zstd");
  // Options that do not apply.
  const std::string ok = store_with("ok.zarr", good);
  LoadOptions o;
  o.level = 2;
  expect_error([&] { load(ok, o); }, ok, "--level 2: the store has 1 level (0)");
  o = {};
  o.channel = 1;
  expect_error([&] { load(ok, o); }, ok, "the store has no channel axis");
  o = {};
  o.raw.type = "uint8";
  expect_error([&] { load(ok, o); }, ok, "--type applies to headerless .raw files only");
  zarr_reference(dir, a.values, {kZx, kZy, kZz});  // writes reference.nrrd
  o = {};
  o.level = 0;
  expect_error([&] { load(dir.file("reference.nrrd"), o); }, "reference.nrrd", "--level applies to Zarr stores only");
  // A group without multiscales.
  const std::string group = store_with("group.zarr", "");
  voltest::write_file(group + "/.zgroup", "{\"zarr_format\": 2}");
  expect_error([&] { load(group); }, group, "without OME-NGFF multiscales");
}
