// What the commands write, and what they leave when something fails: curvature outputs only in
// formats that hold the arrays, VTK's messages as one line, a dead X display replaced by the
// private Xvfb, and `run`'s outputs all together or not at all.
#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataWriter.h>

#include <random>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv::test;

TEST(CurvatureFormats, ObjAndStlAreRefusedForCurvature) {
  TempDir dir("formats");
  for (const char* name : {"c.obj", "c.stl"}) {
    const auto r = run_isocurv({"curvature", dataset("sphere"), "-o", dir / name});
    expect_clean_failure(r, name);
    EXPECT_NE(r.err.find(".vtp"), std::string::npos) << r.describe();
    EXPECT_NE(r.err.find(".ply"), std::string::npos) << r.describe();
  }
  const auto run = run_isocurv({"run", dataset("sphere"), "--format", "obj", "-o", dir / "out"});
  expect_usage_error(run, "--format");
  EXPECT_NE(run.err.find("vtp"), std::string::npos) << run.describe();
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CurvatureFormats, ExtractStillWritesObjAndStl) {
  TempDir dir("extract");
  for (const char* name : {"e.obj", "e.stl"}) {
    const auto r = run_isocurv({"extract", dataset("sphere"), "-o", dir / name, "--quiet"});
    ASSERT_TRUE(r.ok()) << r.describe();
    EXPECT_FALSE(isocurv::io::read_mesh(dir / name).mesh.triangles.empty()) << name;
  }
}

TEST(VtkMessages, TruncatedVtiIsOneLine) {
  TempDir dir("vti");
  vtkNew<vtkImageData> image;
  image->SetDimensions(16, 16, 16);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(16 * 16 * 16);
  std::mt19937 random(7);  // incompressible values, so half the file is half the data
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    values->SetValue(i, float(random() % 1000));
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName((dir / "full.vti").c_str());
  writer->SetInputData(image);
  writer->SetDataModeToBinary();  // base64 inside the XML: a cut file is malformed XML
  ASSERT_EQ(writer->Write(), 1);
  const std::string full = read_file(dir / "full.vti");
  ASSERT_GT(full.size(), 2000u);
  write_file(dir / "cut.vti", full.substr(0, full.size() / 2));
  // VTK printed a dozen lines of its log (with colour codes) before our error.
  expect_clean_failure(run_isocurv({"info", dir / "cut.vti"}), "cut.vti");
  expect_clean_failure(run_isocurv({"extract", dir / "cut.vti", "-o", dir / "o.vtp"}), "cut.vti");
  EXPECT_FALSE(fs::exists(dir / "o.vtp"));
}

TEST(Display, AnUnreachableDisplayFallsBackToThePrivateXvfb) {
  TempDir dir("display");
  // VTK aborted (exit 134, "bad X server connection") on a DISPLAY nobody serves.
  const auto r = run_isocurv({"render", dataset("torus"), "--size", "64x64", "-o", dir / "t.png"},
                             120, {"DISPLAY=:55"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_EQ(png_size(dir / "t.png"), (std::array<std::uint32_t, 2>{64, 64}));
}

TEST(RunOutputs, AFailedRenderLeavesNoNewFile) {
  TempDir dir("run");
  // No display, and an Xvfb on the PATH that fails at once: the render fails after the mesh was
  // made.
  fs::create_directories(dir / "bin");
  write_file(dir / "bin/Xvfb", "#!/bin/sh\nexit 1\n");
  fs::permissions(dir / "bin/Xvfb", fs::perms::owner_all);
  const char* path = std::getenv("PATH");
  const std::vector<std::string> no_xvfb = {"PATH=" + (dir / "bin") + ":" +
                                            (path ? path : "/usr/bin:/bin")};
  const auto fresh =
      run_isocurv({"run", dataset("torus"), "--size", "64x64", "-o", dir / "fresh"}, 120, no_xvfb);
  expect_clean_failure(fresh, "Xvfb");
  EXPECT_FALSE(fs::exists(dir / "fresh")) << "run left its new folder (with the mesh) behind";

  // Into a folder holding an earlier run: everything stays as it was, nothing is added.
  fs::create_directories(dir / "old");
  write_file(dir / "old/torus.vtp", "earlier mesh");
  write_file(dir / "old/stats.json", "{\"earlier\": true}\n");
  const auto old =
      run_isocurv({"run", dataset("torus"), "--size", "64x64", "-o", dir / "old"}, 120, no_xvfb);
  expect_clean_failure(old, "Xvfb");
  EXPECT_EQ(read_file(dir / "old/torus.vtp"), "earlier mesh");
  EXPECT_EQ(read_file(dir / "old/stats.json"), "{\"earlier\": true}\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir / "old"))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"stats.json", "torus.vtp"}));
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"bin", "old"}));

  // And a run that works replaces the set whole.
  const auto ok =
      run_isocurv({"run", dataset("torus"), "--size", "64x64", "-o", dir / "old", "--quiet"}, 120);
  ASSERT_TRUE(ok.ok()) << ok.describe();
  EXPECT_NE(read_file(dir / "old/stats.json"), "{\"earlier\": true}\n");
  EXPECT_EQ(png_size(dir / "old/torus.png"), (std::array<std::uint32_t, 2>{64, 64}));
  EXPECT_FALSE(isocurv::io::read_mesh(dir / "old/torus.vtp").mesh.triangles.empty());
}
