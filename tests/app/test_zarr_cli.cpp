// isocurv on a Zarr store (docs/big-volumes.md): extract gives the same mesh as the same voxels
// in NRRD, info shows the store's levels, chunks and codecs, a bad store is one error line.
#include <gtest/gtest.h>
#include <zlib.h>

#include "cli.h"
#include "io/mesh_file.h"
#include "mesh_compare.h"

using namespace isocurv;
using namespace isocurv::test;

namespace {

/// The CT ball of write_ct_ball (n^3 uint8) as a Zarr v2 store, zlib chunks of 16^3, under an
/// OME-NGFF 0.4 group with unit spacing, and as an attached NRRD; returns {store, nrrd}.
std::pair<std::string, std::string> write_ball_as_zarr_and_nrrd(const TempDir& dir, int n) {
  const std::string raw = read_file(write_ct_ball(dir.path().string(), n, n * 0.3, 20, 7));
  const std::string nrrd = dir / "ball.nrrd";
  write_file(nrrd, "NRRD0004\ntype: uchar\ndimension: 3\nsizes: " + std::to_string(n) + " " + std::to_string(n) + " " +
                       std::to_string(n) + "\nencoding: raw\n\n" + raw);
  const std::string store = dir / "ball.ome.zarr";
  fs::create_directories(store + "/0");
  write_file(store + "/.zgroup", "{\"zarr_format\": 2}");
  write_file(store + "/.zattrs",
             R"({"multiscales": [{"version": "0.4", "axes": [{"name": "z", "type": "space", "unit": "millimeter"},
                {"name": "y", "type": "space", "unit": "millimeter"}, {"name": "x", "type": "space", "unit": "millimeter"}],
                "datasets": [{"path": "0", "coordinateTransformations": [{"type": "scale", "scale": [1, 1, 1]}]}]}]})");
  const std::string s = std::to_string(n);
  write_file(store + "/0/.zarray", "{\"zarr_format\": 2, \"shape\": [" + s + ", " + s + ", " + s +
                                       "], \"chunks\": [16, 16, 16], \"dtype\": \"|u1\", \"compressor\": {\"id\": "
                                       "\"zlib\", \"level\": 1}, \"fill_value\": 0, \"order\": \"C\", \"filters\": null}");
  const int c = (n + 15) / 16;
  for (int cz = 0; cz < c; ++cz)
    for (int cy = 0; cy < c; ++cy)
      for (int cx = 0; cx < c; ++cx) {
        std::string chunk(16 * 16 * 16, '\0');
        for (int z = 0; z < 16; ++z)
          for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
              const int X = cx * 16 + x, Y = cy * 16 + y, Z = cz * 16 + z;
              if (X < n && Y < n && Z < n) chunk[std::size_t(x + 16 * (y + 16 * z))] = raw[std::size_t(X + n * (Y + n * Z))];
            }
        uLongf size = compressBound(uLong(chunk.size()));
        std::string packed(size, '\0');
        compress2(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(chunk.data()),
                  uLong(chunk.size()), 1);
        packed.resize(size);
        write_file(store + "/0/" + std::to_string(cz) + "." + std::to_string(cy) + "." + std::to_string(cx), packed);
      }
  return {store, nrrd};
}

}  // namespace

TEST(CliZarr, ExtractGivesTheSameMeshAsNrrd) {
  TempDir dir("zarr_extract");
  const auto [store, nrrd] = write_ball_as_zarr_and_nrrd(dir, 40);
  const auto a = run_isocurv({"extract", store, "-o", dir / "zarr.vtp", "--quiet"});
  ASSERT_TRUE(a.ok()) << a.describe();
  const auto b = run_isocurv({"extract", nrrd, "-o", dir / "nrrd.vtp", "--quiet"});
  ASSERT_TRUE(b.ok()) << b.describe();
  const Mesh za = io::read_mesh(dir / "zarr.vtp").mesh, nb = io::read_mesh(dir / "nrrd.vtp").mesh;
  EXPECT_GT(za.triangles.size(), 100u);
  expect_same_mesh(za, nb, "zarr against nrrd");
}

TEST(CliZarr, InfoShowsLevelsChunksCodecsAndUnit) {
  TempDir dir("zarr_info");
  const auto paths = write_ball_as_zarr_and_nrrd(dir, 24);
  const auto r = run_isocurv({"info", paths.first});
  ASSERT_TRUE(r.ok()) << r.describe();
  for (const char* want : {"OME-NGFF 0.4", "chunks 16x16x16", "zlib", "length unit       mm", "<- read", "uint8"})
    EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
  const auto j = run_isocurv({"info", paths.first, "--json"});
  ASSERT_TRUE(j.ok()) << j.describe();
  const auto doc = parse_json(j.out, "info --json");
  EXPECT_EQ(doc["format"], "zarr");
  EXPECT_EQ(doc["zarr"]["levels"][0]["chunks"], nlohmann::json::parse("[16, 16, 16]"));
  EXPECT_EQ(doc["zarr"]["level_read"], 0);
}

TEST(CliZarr, BadStoreIsOneErrorLine) {
  TempDir dir("zarr_bad");
  const std::string store = dir / "bad.zarr";
  fs::create_directories(store);
  write_file(store + "/.zarray", "{\"zarr_format\": 2, \"shape\": [4, 4, 4], \"chunks\": [2, 2, 2], \"dtype\": \"<u2\", "
                                 "\"compressor\": {\"id\": \"lzma\"}, \"fill_value\": 0, \"order\": \"C\"}");
  const auto r = run_isocurv({"extract", store, "-o", dir / "out.vtp"});
  expect_clean_failure(r, "unknown Zarr compressor 'lzma'");
  EXPECT_FALSE(fs::exists(dir / "out.vtp"));
  const auto l = run_isocurv({"info", store, "--level", "3"});
  expect_clean_failure(l, "bad.zarr");
}

// Segmentations are the common Zarr label map: --labels reads one as it reads the NRRD of the
// same voxels (issue 56 item 4), label by label.
TEST(CliZarr, ALabelMapStoreMeasuresPerLabelAsItsNrrd) {
  TempDir dir("zarr_labels");
  const int n = 32;
  std::string raw(std::size_t(n) * n * n, '\0');
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        auto in = [&](double cx, double cy, double cz, double r) {
          return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) < r * r;
        };
        raw[std::size_t(x + n * (y + n * z))] = in(11, 16, 16, 7) ? 3 : in(21, 16, 16, 7) ? 9 : 0;
      }
  const std::string nrrd = dir / "map.nrrd";
  write_file(nrrd, "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 32 32 32\nencoding: raw\n\n" + raw);
  const std::string store = dir / "map.zarr";
  fs::create_directories(store);
  write_file(store + "/.zarray",
             "{\"zarr_format\": 2, \"shape\": [32, 32, 32], \"chunks\": [32, 32, 32], \"dtype\": \"|u1\", "
             "\"compressor\": null, \"fill_value\": 0, \"order\": \"C\", \"filters\": null}");
  write_file(store + "/0.0.0", raw);
  auto measure = [&](const std::string& path) {
    const auto r = run_isocurv({"measure", path, "--labels", "--json"});
    EXPECT_TRUE(r.ok()) << r.describe();
    return parse_json(r.out, "measure --labels --json");
  };
  const nlohmann::json z = measure(store), r = measure(nrrd);
  ASSERT_EQ(z["labels"].size(), 2u) << z.dump();
  ASSERT_EQ(r["labels"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(z["labels"][i]["label"], r["labels"][i]["label"]);
    for (const char* q : {"area", "volume", "integral_H", "integral_K"})
      EXPECT_EQ(z["labels"][i][q].get<double>(), r["labels"][i][q].get<double>()) << q;
  }
}
