// Bad arguments and bad files: one line on stderr starting with "isocurv:", exit status 2 for a
// usage error and 1 for bad input, no crash, no output file left behind, and an existing output
// file never clobbered (DESIGN.md, "Errors and data safety").
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include "cli.h"

using namespace isocurv::test;

namespace {

/// n^3 uint8 ball (255 inside radius n/3, 0 outside), X fastest.
std::string ball_u8(int n) {
  std::string b(std::size_t(n) * n * n, '\0');
  const double c = (n - 1) / 2.0;
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x, ++i)
        if ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) < n * n / 9.0) b[i] = char(255);
  return b;
}

}  // namespace

TEST(CliErrors, MissingInput) {
  TempDir dir("missing");
  for (const char* cmd : {"info", "check"}) {
    const auto r = run_isocurv({cmd, dir / "missing.vdb"});
    expect_clean_failure(r, "missing.vdb");
  }
  for (const char* cmd : {"extract", "curvature", "render"}) {
    const auto r = run_isocurv({cmd, dir / "missing.vdb", "-o", dir / "out.ply"});
    expect_clean_failure(r, "missing.vdb");
  }
  const auto mesh = run_isocurv({"curvature", dir / "missing.ply", "-o", dir / "out.vtp"});
  expect_clean_failure(mesh, "missing.ply");
  const auto run = run_isocurv({"run", dir / "missing.nrrd", "-o", dir / "out"});
  expect_clean_failure(run, "missing.nrrd");
  EXPECT_TRUE(dir.entries().empty()) << "left behind: " << ::testing::PrintToString(dir.entries());
}

TEST(CliErrors, UnknownExtensions) {
  TempDir dir("ext");
  write_file(dir / "data.xyz", "some bytes that are not a volume\n");
  expect_clean_failure(run_isocurv({"info", dir / "data.xyz"}), "data.xyz");
  expect_clean_failure(run_isocurv({"extract", dir / "data.xyz", "-o", dir / "out.vtp"}), "data.xyz");
  // An output extension nobody writes: the surface is made, the write refuses, nothing is left.
  expect_clean_failure(run_isocurv({"extract", dataset("sphere"), "-o", dir / "out.xyz"}), "out.xyz");
  expect_clean_failure(run_isocurv({"curvature", dataset("sphere"), "-o", dir / "out.png"}), "out.png");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"data.xyz"});
}

TEST(CliErrors, CorruptFiles) {
  TempDir dir("corrupt");
  write_file(dir / "bad.vdb", "this is not an OpenVDB file at all, just text\n");
  expect_clean_failure(run_isocurv({"info", dir / "bad.vdb"}), "bad.vdb");
  expect_clean_failure(run_isocurv({"extract", dir / "bad.vdb", "-o", dir / "o.vtp"}), "bad.vdb");
  write_file(dir / "bad.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nend_header\n");
  expect_clean_failure(run_isocurv({"check", dir / "bad.ply"}), "bad.ply");
  write_file(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");  // index out of range
  expect_clean_failure(run_isocurv({"check", dir / "bad.obj"}), "bad.obj");
  // NRRD whose data stops short of its sizes.
  write_file(dir / "short.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n\n" +
                                     ball_u8(16).substr(0, 1000));
  expect_clean_failure(run_isocurv({"info", dir / "short.nrrd"}), "short.nrrd");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"bad.obj", "bad.ply", "bad.vdb", "short.nrrd"}));
}

TEST(CliErrors, EmptyVdbGrid) {
  TempDir dir("emptyvdb");
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  openvdb::GridPtrVec grids{grid};
  openvdb::io::File file(dir / "empty.vdb");
  file.write(grids);
  file.close();
  expect_clean_failure(run_isocurv({"extract", dir / "empty.vdb", "-o", dir / "o.vtp"}), "empty.vdb");
  EXPECT_FALSE(fs::exists(dir / "o.vtp"));
}

TEST(CliErrors, RawLayoutProblems) {
  TempDir dir("raw");
  const std::string full = ball_u8(16);
  write_file(dir / "ball.raw", full);
  write_file(dir / "short.raw", full.substr(0, full.size() - 100));
  const std::vector<std::string> layout = {"--dims", "16", "16", "16", "--type", "uint8"};
  auto with = [&](std::vector<std::string> a) {
    a.insert(a.end(), layout.begin(), layout.end());
    return a;
  };
  // The good file works (so the failures below are about the files, not the options).
  const auto good = run_isocurv(with({"extract", dir / "ball.raw", "-o", dir / "ball.vtp", "--json"}));
  ASSERT_TRUE(good.ok()) << good.describe();
  EXPECT_TRUE(parse_json(good.out, "extract --json")["watertight"].get<bool>());
  fs::remove(dir / "ball.vtp");

  expect_clean_failure(run_isocurv(with({"extract", dir / "short.raw", "-o", dir / "o.vtp"})), "short.raw");
  expect_clean_failure(run_isocurv(with({"info", dir / "short.raw"})), "short.raw");
  // No layout at all, a type the file cannot have, zero dimensions.
  expect_clean_failure(run_isocurv({"info", dir / "ball.raw"}), "ball.raw");
  expect_clean_failure(run_isocurv({"info", dir / "ball.raw", "--dims", "16", "16", "16", "--type", "uint16"}),
                       "ball.raw");
  expect_clean_failure(run_isocurv({"info", dir / "ball.raw", "--dims", "0", "16", "16", "--type", "uint8"}),
                       "ball.raw");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"ball.raw", "short.raw"}));
}

TEST(CliErrors, IsovalueOutsideTheRange) {
  TempDir dir("iso");
  const auto r = run_isocurv({"extract", dataset("sphere"), "--iso", "1000", "-o", dir / "o.vtp"});
  expect_clean_failure(r, "outside the value range");
  EXPECT_NE(r.err.find("sphere.vdb"), std::string::npos) << "names the file: " << r.err;
  expect_clean_failure(run_isocurv({"curvature", dataset("torus"), "--iso", "-50", "-o", dir / "o.vtp"}),
                       "outside the value range");
  expect_clean_failure(run_isocurv({"run", dataset("torus"), "--iso", "-50", "-o", dir / "out"}),
                       "outside the value range");
  const auto nan = run_isocurv({"extract", dataset("sphere"), "--iso", "nan", "-o", dir / "o.vtp"});
  EXPECT_GT(nan.exit_code, 0) << nan.describe();
  EXPECT_EQ(nan.signal, 0) << nan.describe();
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CliErrors, RunWithNoSurfaceOrAMeshMakesNoFolder) {
  TempDir dir("run");
  // The torus field peaks at 0.25 on its core circle; just below the maximum there is no surface
  // worth the name, at the maximum none at all.
  const auto info = run_isocurv({"info", dataset("torus"), "--json"});
  ASSERT_TRUE(info.ok()) << info.describe();
  const double max = parse_json(info.out, "info --json")["max"].get<double>();
  char iso[64];
  std::snprintf(iso, sizeof iso, "%.9g", max);
  expect_clean_failure(run_isocurv({"run", dataset("torus"), "--iso", iso, "-o", dir / "out"}), "no surface");
  write_file(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_clean_failure(run_isocurv({"run", dir / "m.obj", "-o", dir / "out"}), "m.obj");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"m.obj"}) << "run made its folder before failing";
}

TEST(CliErrors, UnknownOptionsAndBadValues) {
  TempDir dir("options");
  expect_usage_error(run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--bogus"}), "--bogus");
  expect_usage_error(run_isocurv({"extract", dataset("sphere")}), "--output");  // required
  expect_usage_error(run_isocurv({"curvature", dataset("sphere"), "-o", dir / "o.vtp", "--normals", "vertex"}),
                     "--normals");
  // --color takes any point array, so an unknown one is found once the mesh exists: not a usage
  // error, but still one line naming the option.
  expect_clean_failure(run_isocurv({"render", dataset("sphere"), "-o", dir / "o.png", "--color", "Z"}), "--color");
  expect_usage_error(run_isocurv({"run", dataset("sphere"), "-o", dir / "out", "--format", "stl"}), "--format");
  expect_usage_error(run_isocurv({"info", dataset("sphere"), "--type", "float16"}), "--type");
  expect_usage_error(run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--iso", "abc"}), "--iso");
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CliErrors, UnknownCommandIsNamed) {
  // A mistyped command should be named in the error, as a mistyped option is ("--bogus" above).
  const auto r = run_isocurv({"extrct", dataset("sphere"), "-o", "/nonexistent/o.vtp"});
  expect_usage_error(r, "extrct");
}

TEST(CliErrors, BadSize) {
  TempDir dir("size");
  for (const char* size : {"10x10", "320", "320x", "x240", "320*240", "0x0", "100000x100", "abc"}) {
    const auto r = run_isocurv({"render", dataset("sphere"), "--size", size, "-o", dir / "o.png"});
    expect_usage_error(r, "--size");
    EXPECT_NE(r.err.find("WIDTHxHEIGHT"), std::string::npos) << size << "\n" << r.describe();
  }
  expect_usage_error(run_isocurv({"run", dataset("sphere"), "--size", "5x5", "-o", dir / "out"}), "--size");
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CliErrors, BadDevice) {
  TempDir dir("device");
  const auto r = run_isocurv({"extract", dataset("sphere"), "--device", "99", "-o", dir / "o.vtp"});
  expect_clean_failure(r, "99");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliErrors, UnwritableOutput) {
  TempDir dir("unwritable");
  expect_clean_failure(run_isocurv({"extract", dataset("sphere"), "-o", dir / "no/such/folder/o.vtp"}), "o.vtp");
  expect_clean_failure(run_isocurv({"render", dataset("sphere"), "--size", "64x64", "-o", dir / "no/such/o.png"}),
                       "o.png");
  // -o naming an existing regular file where run wants a folder.
  write_file(dir / "afile", "x");
  expect_clean_failure(run_isocurv({"run", dataset("sphere"), "--size", "64x64", "-o", dir / "afile"}), "afile");
  EXPECT_EQ(read_file(dir / "afile"), "x");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"afile"});
}

TEST(CliErrors, AnUnwritableOutputIsCaughtBeforeAnyWork) {
  TempDir dir("unwritable_early");
  const std::string nowhere = dir / "no/such/folder";
  // Each of these would fail later for another reason (an isovalue outside the values, found
  // while extracting): the output's folder must be the error, found first.
  const std::vector<std::vector<std::string>> commands = {
      {"extract", dataset("sphere"), "--iso", "99", "-o", nowhere + "/o.vtp"},
      {"curvature", dataset("sphere"), "--iso", "99", "-o", nowhere + "/o.vtp"},
      {"features", dataset("sphere"), "--iso", "99", "--radius", "5%", "-o", nowhere + "/o.vtp"},
      {"lines", dataset("sphere"), "--iso", "99", "-o", nowhere + "/o.svg"},
      {"render", dataset("sphere"), "--iso", "99", "--size", "64x64", "-o", nowhere + "/o.png"},
      {"screen", dataset("sphere"), "--iso", "99", "--size", "64x64", "-o", nowhere + "/o.png"},
      {"extract", dataset("sphere"), "--iso", "99", "-o", dir.path().string()}};  // a folder
  for (const auto& args : commands) {
    const auto r = run_isocurv(args);
    expect_clean_failure(r, args.back());
    EXPECT_EQ(r.err.find("value range"), std::string::npos) << args[0] << ": worked first: " << r.err;
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(CliErrors, ExistingOutputIsNotClobbered) {
  TempDir dir("clobber");
  const std::string precious = "precious bytes: a file the user cares about\n";
  for (const char* name : {"o.vtp", "o.ply", "o.png"}) write_file(dir / name, precious);
  expect_clean_failure(run_isocurv({"extract", dir / "missing.vdb", "-o", dir / "o.vtp"}), "missing.vdb");
  expect_clean_failure(run_isocurv({"extract", dataset("sphere"), "--iso", "99", "-o", dir / "o.vtp"}),
                       "outside the value range");
  expect_clean_failure(run_isocurv({"curvature", dir / "o.ply", "-o", dir / "o.vtp"}), "o.ply");  // not a PLY
  expect_usage_error(run_isocurv({"render", dataset("sphere"), "--size", "1x1", "-o", dir / "o.png"}), "--size");
  expect_clean_failure(run_isocurv({"render", dir / "missing.nrrd", "-o", dir / "o.png"}), "missing.nrrd");
  for (const char* name : {"o.vtp", "o.ply", "o.png"}) EXPECT_EQ(read_file(dir / name), precious) << name;
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"o.ply", "o.png", "o.vtp"})) << "temporary files left behind";

  // A failing run into a folder holding an earlier run's results leaves them as they were.
  fs::create_directories(dir / "out");
  write_file(dir / "out/stats.json", "{\"earlier\": true}\n");
  expect_clean_failure(run_isocurv({"run", dataset("torus"), "--iso", "-50", "-o", dir / "out"}),
                       "outside the value range");
  EXPECT_EQ(read_file(dir / "out/stats.json"), "{\"earlier\": true}\n");

  // And a successful write replaces it whole.
  const auto ok = run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.ply", "--quiet"});
  ASSERT_TRUE(ok.ok()) << ok.describe();
  EXPECT_NE(read_file(dir / "o.ply"), precious);
  EXPECT_EQ(read_file(dir / "o.ply").rfind("ply\n", 0), 0u);
}
