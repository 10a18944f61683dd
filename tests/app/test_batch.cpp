// Batches, sweeps, --compress and the program cache, end to end through the executable: several
// inputs (and globs) in one call, per-input folders and summary.json, a bad input reported while
// the others still run, --iso V1,V2 sweeps, --jobs 2 giving the same files as --jobs 1 (extract,
// curvature, run, features, lines).
#include <gtest/gtest.h>

#include "io/mesh_file.h"
#include "tests/app/cli.h"
#include "tests/app/mesh_compare.h"
#include "tests/viz/png_stats.h"
#include "viz/curvature_scene.h"

namespace isocurv::test {
namespace {

/// The mesh and k1 of a mesh file, for comparisons.
struct Read {
  std::vector<Vec3f> positions;
  std::vector<Tri> triangles;
  std::vector<float> k1;
};

Read read(const std::string& path) {
  io::MeshFile f = io::read_mesh(path);
  Read r;
  r.positions.assign(f.mesh.positions.begin(), f.mesh.positions.end());
  r.triangles.assign(f.mesh.triangles.begin(), f.mesh.triangles.end());
  if (f.field) r.k1.assign(f.field->k1.begin(), f.field->k1.end());
  return r;
}

void expect_same(const std::string& a, const std::string& b) {
  const Read x = read(a), y = read(b);
  EXPECT_EQ(x.positions, y.positions) << a << " vs " << b;
  EXPECT_EQ(x.triangles, y.triangles) << a << " vs " << b;
  EXPECT_EQ(x.k1, y.k1) << a << " vs " << b;
}

// A pattern that matches nothing is one error line and no output: not a folder named like the
// mesh file holding a summary of one failure.
TEST(Batch, APatternMatchingNothingIsOneErrorAndNoOutput) {
  TempDir dir("batch-none");
  const auto r = run_isocurv({"curvature", dir / "in/*.nhdr", "-o", dir / "out.vtp"});
  EXPECT_NE(r.exit_code, 0) << r.describe();
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << r.describe();
  EXPECT_NE(lines[0].find("no file matches this pattern"), std::string::npos) << r.describe();
  EXPECT_FALSE(fs::exists(dir / "out.vtp"));
}

TEST(Batch, EachInputInItsFolderOneBadInputReportedOthersRun) {
  TempDir dir("batch");
  fs::create_directories(dir / "in/other");
  fs::copy_file(dataset("sphere"), dir / "in/sphere.vdb");
  fs::copy_file(dataset("torus"), dir / "in/torus.vdb");
  fs::copy_file(dataset("gyroid"), dir / "in/other/sphere.vdb");  // same stem: gets sphere_2
  write_file(dir / "in/broken.vdb", "not a vdb file");
  const auto r = run_isocurv({"curvature", dir / "in/*.vdb", dir / "in/other/sphere.vdb",
                              dir / "in/none*.nrrd", "-o", dir / "out"},
                             120);
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 3u) << r.describe();  // broken.vdb, the empty glob, then the count
  EXPECT_NE(lines[0].find("broken.vdb"), std::string::npos) << r.describe();
  EXPECT_NE(lines[1].find("none*.nrrd"), std::string::npos) << r.describe();
  EXPECT_NE(lines[2].find("2 of 5 entries failed"), std::string::npos) << r.describe();
  for (const char* f : {"out/sphere/sphere.vtp", "out/sphere/stats.json", "out/torus/torus.vtp",
                        "out/sphere_2/sphere.vtp", "out/summary.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  EXPECT_FALSE(fs::exists(dir / "out/broken")) << "a failed input leaves no folder";
  const nlohmann::json s = parse_json(read_file(dir / "out/summary.json"), "summary.json");
  EXPECT_EQ(s["inputs"], 5);
  EXPECT_EQ(s["failed"], 2);
  EXPECT_EQ(s["ok"], 3);
  ASSERT_EQ(s["entries"].size(), 5u);
  int failed = 0;
  for (const auto& e : s["entries"]) {
    if (e["status"] == "failed") {
      ++failed;
      EXPECT_FALSE(e.value("error", "").empty());
    } else {
      EXPECT_EQ(e["mesh_bytes"], fs::file_size(e["mesh"].get<std::string>()));
      EXPECT_GT(e["triangles"].get<int>(), 0);
      // Each input's curvature statistics, as its stats.json has them.
      const nlohmann::json own = parse_json(read_file(e["stats"].get<std::string>()), "stats.json");
      ASSERT_TRUE(e.contains("curvature")) << e.dump(2);
      EXPECT_EQ(e["curvature"], own["curvature"]);
      EXPECT_TRUE(e["curvature"]["H"]["p50"].is_number()) << e.dump(2);
      EXPECT_EQ(e["estimator"], "volume") << e.dump(2);
    }
  }
  EXPECT_EQ(failed, 2);
  // The batch's output is what a single call writes.
  const auto single =
      run_isocurv({"curvature", dataset("torus"), "-o", dir / "torus.vtp", "--quiet"});
  ASSERT_TRUE(single.ok()) << single.describe();
  expect_same(dir / "out/torus/torus.vtp", dir / "torus.vtp");
  const nlohmann::json st = parse_json(read_file(dir / "out/torus/stats.json"), "stats.json");
  EXPECT_TRUE(st.contains("curvature"));
  EXPECT_EQ(st["input"], dir / "in/torus.vdb");
}

TEST(Batch, SweepWritesEachIsovalueAsASingleCallWould) {
  TempDir dir("sweep");
  const auto r = run_isocurv({"extract", dataset("torus"), "--iso", "-0.5,0.125", "--format", "ply",
                              "-o", dir / "out", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const nlohmann::json s = parse_json(r.out, "stdout");
  ASSERT_EQ(s["entries"].size(), 2u);
  EXPECT_EQ(s["entries"][0]["isovalue"], -0.5);
  EXPECT_EQ(s["entries"][1]["isovalue"], 0.125);
  for (const char* iso : {"-0.5", "0.125"}) {
    const std::string mesh = dir / ("out/torus/torus_iso" + std::string(iso) + ".ply");
    ASSERT_TRUE(fs::exists(mesh)) << mesh;
    EXPECT_TRUE(fs::exists(dir / ("out/torus/stats_iso" + std::string(iso) + ".json")));
    const auto one =
        run_isocurv({"extract", dataset("torus"), "--iso", iso, "-o", dir / "one.ply", "--quiet"});
    ASSERT_TRUE(one.ok()) << one.describe();
    expect_same(mesh, dir / "one.ply");
  }
  EXPECT_NE(read(dir / "out/torus/torus_iso-0.5.ply").positions.size(),
            read(dir / "out/torus/torus_iso0.125.ply").positions.size());
}

// The volume estimator's coarse smoothing does not depend on the isovalue: a sweep's second
// isovalue takes the pyramid the first one built (its report says how many bricks it found),
// and its curvature is the one-shot run's to the bit.
TEST(Batch, CurvatureSweepKeepsThePyramidAndGivesTheOneShotResult) {
  const std::string lobster = std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol";
  if (!fs::exists(lobster)) GTEST_SKIP() << "no " << lobster;
  TempDir dir("sweep_pyramid");
  const auto r = run_isocurv({"curvature", lobster, "--iso", "50,60", "-o", dir / "out", "--quiet"}, 300);
  ASSERT_TRUE(r.ok()) << r.describe();
  auto kept = [&](const char* iso) {
    const nlohmann::json st = nlohmann::json::parse(
        read_file(dir / ("out/lobster/stats_iso" + std::string(iso) + ".json")));
    return st["estimator"]["pyramid_bricks_kept"].get<std::size_t>();
  };
  EXPECT_EQ(kept("50"), 0u);
  EXPECT_GT(kept("60"), 100u);
  const auto one = run_isocurv({"curvature", lobster, "--iso", "60", "-o", dir / "one.vtp", "--quiet"}, 300);
  ASSERT_TRUE(one.ok()) << one.describe();
  const io::MeshFile a = io::read_mesh(dir / "out/lobster/lobster_iso60.vtp"),
                     b = io::read_mesh(dir / "one.vtp");
  expect_same_mesh(a.mesh, b.mesh, "lobster iso 60");
  ASSERT_TRUE(a.field && b.field);
  expect_same_field(*a.field, *b.field, "lobster iso 60");
}

// A sweep's pictures share one colour range and one camera by default: their legends are the
// same pixels, and the thin torus looks smaller than the fat one; with --range each, each picture
// has its own legend and fills its frame.
TEST(Batch, SweepPicturesShareOneRangeAndCameraUnlessEach) {
  TempDir dir("sweep_pictures");
  const std::vector<std::string> common = {"run", dataset("torus"), "--iso", "-0.5,0.125",
                                           "--size", "320x240", "--json"};
  auto run = [&](const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args = common;
    args.insert(args.end(), {"-o", dir / out});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args, 120);
    EXPECT_TRUE(r.ok()) << r.describe();
    return parse_json(r.out, "run --json");
  };
  const nlohmann::json shared = run("shared", {});
  const nlohmann::json each = run("each", {"--range", "each"});
  ASSERT_TRUE(shared.contains("pictures")) << shared.dump();
  EXPECT_EQ(shared["pictures"]["range"], "shared");
  const double lo = shared["pictures"]["color_range"][0], hi = shared["pictures"]["color_range"][1];
  EXPECT_LT(lo, hi);
  EXPECT_FALSE(each.contains("pictures"));
  auto png = [&](const std::string& out, const char* iso) {
    return dir / (out + "/torus/torus_iso" + std::string(iso) + ".png");
  };
  EXPECT_EQ(test::legend_difference(png("shared", "-0.5"), png("shared", "0.125")), 0);
  EXPECT_GT(test::legend_difference(png("each", "-0.5"), png("each", "0.125")), 20);
  // The surface's width on screen (title and legend left out).
  auto width = [&](const std::string& path) {
    const std::vector<test::Box> skip = {{int(0.8 * 320), 0, 320, 240}, {0, int(0.88 * 240), 320, 240}};
    const test::Box b = test::foreground_box(path, viz::kBackgroundBottom, viz::kBackgroundTop, skip);
    return double(b.x1 - b.x0);
  };
  const double thin_shared = width(png("shared", "-0.5")), fat_shared = width(png("shared", "0.125"));
  const double thin_each = width(png("each", "-0.5")), fat_each = width(png("each", "0.125"));
  EXPECT_NE(thin_shared, fat_shared);
  EXPECT_NEAR(thin_each, fat_each, 0.04 * 320) << "each picture fills its own frame";
  EXPECT_GT(std::abs(thin_shared - fat_shared), 2 * std::abs(thin_each - fat_each) + 2)
      << "one camera: the sizes differ as the surfaces do";
  // A range given exactly applies to every picture and is not reported as shared.
  const nlohmann::json fixed = run("fixed", {"--range", "-1,1"});
  EXPECT_FALSE(fixed["pictures"].contains("color_range")) << fixed.dump();
  EXPECT_EQ(test::legend_difference(png("fixed", "-0.5"), png("fixed", "0.125")), 0);
  expect_usage_error(run_isocurv({"run", dataset("torus"), "--range", "1,-1", "-o", dir / "bad"}),
                     "--range");
  expect_usage_error(run_isocurv({"run", dataset("torus"), "--range", "everything", "-o", dir / "bad"}),
                     "--range");
}

TEST(Batch, JobsTwoWritesTheSameFilesAsJobsOne) {
  TempDir dir("jobs");
  for (const char* jobs : {"1", "2"}) {
    const auto r = run_isocurv({"curvature", dataset("sphere"), dataset("torus"), dataset("gyroid"),
                                "--jobs", jobs, "-o", dir / ("j" + std::string(jobs)), "--quiet"},
                               120);
    ASSERT_TRUE(r.ok()) << r.describe();
  }
  for (const char* name : {"sphere/sphere.vtp", "torus/torus.vtp", "gyroid/gyroid.vtp"})
    EXPECT_EQ(read_file(dir / ("j1/" + std::string(name))),
              read_file(dir / ("j2/" + std::string(name))))
        << name;
}

// features and lines run as batches in the same loop: each input's output is the file a single
// call writes, summary.json lists them with the counts their --json reports, a bad input is one
// stderr line while the others still run, and --jobs 2 writes the same files as --jobs 1.
TEST(Batch, FeaturesBatchWritesWhatSingleCallsWriteAndSurvivesABadInput) {
  TempDir dir("features_batch");
  fs::create_directories(dir / "in");
  fs::copy_file(dataset("sphere"), dir / "in/sphere.vdb");
  fs::copy_file(dataset("torus"), dir / "in/torus.vdb");
  write_file(dir / "in/broken.vdb", "not a vdb file");
  const std::vector<std::string> fast = {"--radius", "5%", "--samples", "32"};
  for (const char* jobs : {"1", "2"}) {
    std::vector<std::string> args = {"features", dir / "in/sphere.vdb", dir / "in/broken.vdb",
                                     dir / "in/torus.vdb", "--jobs", jobs,
                                     "-o", dir / ("j" + std::string(jobs))};
    args.insert(args.end(), fast.begin(), fast.end());
    const auto r = run_isocurv(args, 120);
    EXPECT_EQ(r.exit_code, 1) << r.describe();
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 2u) << r.describe();
    EXPECT_NE(lines[0].find("broken.vdb"), std::string::npos) << r.describe();
    EXPECT_NE(lines[1].find("1 of 3 entries failed"), std::string::npos) << r.describe();
  }
  const nlohmann::json s = parse_json(read_file(dir / "j1/summary.json"), "summary.json");
  EXPECT_EQ(s["command"], "features");
  EXPECT_EQ(s["inputs"], 3);
  EXPECT_EQ(s["ok"], 2);
  EXPECT_EQ(s["failed"], 1);
  ASSERT_EQ(s["entries"].size(), 3u);
  EXPECT_EQ(s["entries"][1]["status"], "failed");
  EXPECT_NE(s["entries"][1].value("error", "").find("broken.vdb"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "j1/broken")) << "a failed input leaves no folder";
  for (const char* name : {"sphere", "torus"}) {
    const std::string out = dir / ("j1/" + std::string(name) + "/" + name + ".vtp");
    const nlohmann::json& e = s["entries"][std::string(name) == "sphere" ? 0 : 2];
    EXPECT_EQ(e["status"], "ok") << e.dump(2);
    EXPECT_EQ(e["output"], out);
    EXPECT_EQ(e["output_bytes"], fs::file_size(out));
    EXPECT_GT(e["vertices"].get<int>(), 0);
    EXPECT_EQ(e["features"]["radii"][0]["as_given"], "5%") << e.dump(2);
    EXPECT_TRUE(e["timings_ms"].contains("features")) << e.dump(2);
    // stats.json is the --json report of that input.
    const nlohmann::json st = parse_json(read_file(e["stats"].get<std::string>()), "stats.json");
    EXPECT_EQ(st["features"], e["features"]);
    EXPECT_EQ(st["output"], out);
    // The file a single call writes, byte for byte, and the same with --jobs 2.
    std::vector<std::string> one = {"features", dir / ("in/" + std::string(name) + ".vdb"), "-o",
                                    dir / (std::string(name) + ".vtp"), "--quiet"};
    one.insert(one.end(), fast.begin(), fast.end());
    const auto single = run_isocurv(one, 60);
    ASSERT_TRUE(single.ok()) << single.describe();
    EXPECT_EQ(read_file(out), read_file(dir / (std::string(name) + ".vtp"))) << name;
    EXPECT_EQ(read_file(out), read_file(dir / ("j2/" + std::string(name) + "/" + name + ".vtp")))
        << name;
  }
}

TEST(Batch, LinesSweepWritesWhatSingleCallsWrite) {
  TempDir dir("lines_sweep");
  for (const char* jobs : {"1", "2"}) {
    const auto r = run_isocurv({"lines", dataset("torus"), "--iso", "-0.5,0.125", "--format", "svg",
                                "--view", "+y", "--size", "320x240", "--jobs", jobs, "-o",
                                dir / ("j" + std::string(jobs)), "--json"},
                               120);
    ASSERT_TRUE(r.ok()) << r.describe();
    const nlohmann::json s = parse_json(r.out, "lines --json");
    EXPECT_EQ(s["command"], "lines");
    ASSERT_EQ(s["entries"].size(), 2u);
    EXPECT_EQ(s["entries"][0]["isovalue"], -0.5);
    EXPECT_EQ(s["entries"][1]["isovalue"], 0.125);
    for (const auto& e : s["entries"]) {
      EXPECT_EQ(e["status"], "ok") << e.dump(2);
      EXPECT_GT(e["segments"]["contours"].get<int>(), 0) << e.dump(2);
      EXPECT_GT(e["polylines"].get<int>(), 0) << e.dump(2);
      EXPECT_TRUE(e["timings_ms"].contains("visibility")) << e.dump(2);
    }
    EXPECT_EQ(parse_json(read_file(dir / ("j" + std::string(jobs) + "/summary.json")), "summary"),
              s);
  }
  for (const char* iso : {"-0.5", "0.125"}) {
    const std::string name = "torus/torus_iso" + std::string(iso) + ".svg";
    ASSERT_TRUE(fs::exists(dir / ("j1/" + name))) << name;
    EXPECT_TRUE(fs::exists(dir / ("j1/torus/stats_iso" + std::string(iso) + ".json")));
    const auto one = run_isocurv({"lines", dataset("torus"), "--iso", iso, "--view", "+y", "--size",
                                  "320x240", "-o", dir / "one.svg", "--quiet"});
    ASSERT_TRUE(one.ok()) << one.describe();
    EXPECT_EQ(read_file(dir / ("j1/" + name)), read_file(dir / "one.svg")) << iso;
    EXPECT_EQ(read_file(dir / ("j1/" + name)), read_file(dir / ("j2/" + name))) << iso;
  }
  EXPECT_NE(read_file(dir / "j1/torus/torus_iso-0.5.svg"),
            read_file(dir / "j1/torus/torus_iso0.125.svg"));
  // The default format is .vtp, the polylines a single call writes.
  const auto vtp = run_isocurv(
      {"lines", dataset("sphere"), dataset("torus"), "-o", dir / "both", "--quiet"}, 120);
  ASSERT_TRUE(vtp.ok()) << vtp.describe();
  const auto one = run_isocurv({"lines", dataset("sphere"), "-o", dir / "sphere.vtp", "--quiet"});
  ASSERT_TRUE(one.ok()) << one.describe();
  EXPECT_EQ(read_file(dir / "both/sphere/sphere.vtp"), read_file(dir / "sphere.vtp"));
  EXPECT_TRUE(fs::exists(dir / "both/torus/torus.vtp"));
}

TEST(Batch, FeaturesAndLinesRefuseWhatOtherBatchesRefuse) {
  TempDir dir("step_refusals");
  const auto features = run_isocurv({"features", dataset("sphere"), dataset("torus"), "--radius",
                                     "5%", "-o", dir / "f.vtp"});
  expect_clean_failure(features, "f.vtp");
  EXPECT_NE(features.err.find("is a folder"), std::string::npos) << features.describe();
  expect_clean_failure(run_isocurv({"lines", dataset("torus"), "--iso", "-0.5,0.125", "-o",
                                    dir / "l.svg"}),
                       "l.svg");
  expect_clean_failure(run_isocurv({"lines", dataset("torus"), "--format", "svg", "-o",
                                    dir / "a.vtp"}),
                       "--format");
  expect_clean_failure(run_isocurv({"features", dataset("sphere"), "--radius", "5%", "--jobs", "2",
                                    "-o", dir / "a.vtp"}),
                       "--jobs");
  expect_usage_error(run_isocurv({"lines", dataset("sphere"), dataset("torus"), "--format", "ply",
                                  "-o", dir / "l"}),
                     "--format");
  // Options every entry would fail on are one error before any output folder.
  expect_clean_failure(run_isocurv({"features", dataset("sphere"), dataset("torus"), "--radius",
                                    "-1", "-o", dir / "f"}),
                       "--radius");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Batch, UnwritableOutputIsCaughtBeforeAnyWork) {
  TempDir dir("unwritable");
  write_file(dir / "file", "x");
  const auto r =
      run_isocurv({"curvature", dataset("sphere"), dataset("torus"), "-o", dir / "file/out"});
  expect_clean_failure(r, "file/out");
  const auto f = run_isocurv({"extract", dataset("sphere"), dataset("torus"), "-o", dir / "file"});
  expect_clean_failure(f, "must be a folder");
}

TEST(Batch, AnOutputNamedLikeAFileIsRefusedNotMadeAFolder) {
  // A sweep, a batch, run and a time series: -o names a folder; "sw.vtp" is a slip, refused in
  // one line before any work, and no folder of that name appears.
  TempDir dir("file_like");
  const auto sweep = run_isocurv({"extract", dataset("torus"), "--iso", "-0.5,0.125", "-o", dir / "sw.vtp"});
  expect_clean_failure(sweep, "sw.vtp");
  EXPECT_NE(sweep.err.find("is a folder"), std::string::npos) << sweep.describe();
  EXPECT_NE(sweep.err.find("sw/"), std::string::npos) << "suggests the folder: " << sweep.describe();
  const auto batch = run_isocurv({"curvature", dataset("sphere"), dataset("torus"), "-o", dir / "both.PLY"});
  expect_clean_failure(batch, "both.PLY");
  const auto run = run_isocurv({"run", dataset("sphere"), "-o", dir / "out.png"});
  expect_clean_failure(run, "out.png");
  const auto series = run_isocurv({"curvature", dataset("sphere"), dataset("torus"), "--time-series", "-o",
                                   dir / "anim.pvd"});
  expect_clean_failure(series, "anim.pvd");
  for (const char* name : {"sw.vtp", "both.PLY", "out.png", "anim.pvd"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
  // A folder name with a dot that is no file type stays a folder.
  const auto dotted = run_isocurv({"extract", dataset("torus"), "--iso", "-0.5,0.125", "-o", dir / "v1.2", "--quiet"});
  ASSERT_TRUE(dotted.ok()) << dotted.describe();
  EXPECT_TRUE(fs::is_directory(dir / "v1.2"));
}

TEST(Batch, MalformedIsovalueListIsAUsageError) {
  TempDir dir("badiso");
  expect_usage_error(run_isocurv({"extract", dataset("sphere"), "--iso", "0,x", "-o", dir / "o"}),
                     "--iso");
  expect_usage_error(run_isocurv({"extract", dataset("sphere"), "--iso", "0,0", "-o", dir / "o"}),
                     "--iso");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Batch, BatchOnlyOptionsOnOneOutputAreAnError) {
  TempDir dir("batchonly");
  expect_clean_failure(
      run_isocurv({"extract", dataset("sphere"), "--format", "ply", "-o", dir / "a.vtp"}),
      "--format");
  expect_clean_failure(
      run_isocurv({"curvature", dataset("sphere"), "--jobs", "2", "-o", dir / "a.vtp"}), "--jobs");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Compress, EveryCompressorReadsBackTheSameArraysAndSizesDiffer) {
  TempDir dir("compress");
  std::map<std::string, std::uint64_t> bytes;
  for (const char* c : {"none", "lz4", "zlib:6"}) {
    const std::string out = dir / (std::string(c).substr(0, 4) + ".vtp");
    const auto r =
        run_isocurv({"curvature", dataset("torus"), "--compress", c, "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    const nlohmann::json j = parse_json(r.out, "stdout");
    EXPECT_EQ(j["output_bytes"], fs::file_size(out));
    bytes[c] = j["output_bytes"];
  }
  expect_same(dir / "none.vtp", dir / "lz4.vtp");
  expect_same(dir / "none.vtp", dir / "zlib.vtp");
  EXPECT_GT(bytes["none"], bytes["lz4"]);
  EXPECT_GT(bytes["lz4"], bytes["zlib:6"]);
  expect_usage_error(
      run_isocurv({"curvature", dataset("torus"), "--compress", "zlib:0", "-o", dir / "x.vtp"}),
      "--compress");
  expect_usage_error(
      run_isocurv({"extract", dataset("torus"), "--compress", "gzip", "-o", dir / "x.vtp"}),
      "--compress");
}

TEST(ProgramCacheCli, SecondProcessLoadsProgramsAndWritesTheSameMesh) {
  TempDir dir("cache");
  const std::vector<std::string> env = {"ISOCURV_CACHE_DIR=" + (dir / "cache")};
  const auto first =
      run_isocurv({"curvature", dataset("sphere"), "-o", dir / "a.vtp", "--json"}, 60, env);
  ASSERT_TRUE(first.ok()) << first.describe();
  const auto second =
      run_isocurv({"curvature", dataset("sphere"), "-o", dir / "b.vtp", "--json"}, 60, env);
  ASSERT_TRUE(second.ok()) << second.describe();
  const nlohmann::json a = parse_json(first.out, "first"), b = parse_json(second.out, "second");
  EXPECT_GT(a["programs"]["compiled"].get<int>(), 0);
  EXPECT_EQ(b["programs"]["compiled"], 0);
  EXPECT_EQ(b["programs"]["from_cache"], a["programs"]["compiled"]);
  EXPECT_TRUE(a["timings_ms"].contains("compile"));
  EXPECT_EQ(read_file(dir / "a.vtp"), read_file(dir / "b.vtp"));
  // A cache folder that cannot be made: the command still works, after one warning.
  write_file(dir / "plain", "x");
  const auto off = run_isocurv({"extract", dataset("sphere"), "-o", dir / "c.ply"}, 60,
                               {"ISOCURV_CACHE_DIR=" + (dir / "plain/cache")});
  ASSERT_TRUE(off.ok()) << off.describe();
  ASSERT_EQ(off.err_lines().size(), 1u) << off.describe();
  EXPECT_NE(off.err_lines()[0].find("not writable"), std::string::npos) << off.describe();
}

}  // namespace
}  // namespace isocurv::test
