// The deformers' kernels against their C++ references, skinning's identity and its file checks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "deform/affine.h"
#include "deform/noise_displace.h"
#include "deform/skinning.h"
#include "tests/deform/deform_fixtures.h"

namespace isocurv {
namespace {

TEST(Affine, KernelMatchesReference) {
  const Mesh m = test::lumpy_sphere(4);  // 2562 vertices: 41 work groups of 64
  const cl::Buffer rest = test::to_device(m.positions);
  cl::Buffer out = test::to_device(m.positions);
  for (const deform::Affine& a :
       {deform::scaling(1.5, 0.5, 0.75), deform::rotation({1, 2, 3}, 0.7),
        deform::Affine{0.9f, 0.1f, -0.2f, 0.3f, 0.0f, 1.1f, 0.4f, -0.5f, 0.2f, 0.0f, 0.8f, 2.0f}}) {
    deform::affine(test::device(), rest, m.vertex_count(), a, out);
    const Positions ref = deform::affine_reference(m.positions, a);
    EXPECT_LE(test::max_difference(test::from_device(out, m.vertex_count()), ref), 1e-6);
  }
}

TEST(Affine, RotationIsOrthonormalAndEllipsoidAxesStayInRange) {
  const deform::Affine r = deform::rotation({0, 0, 1}, 3.14159265358979 / 2);
  EXPECT_NEAR(r[1], -1, 1e-7);  // x' = -y
  EXPECT_NEAR(r[4], 1, 1e-7);   // y' = x
  for (int i = 0; i <= 100; ++i)
    for (double a : deform::ellipsoid_axes(i / 100.0)) {
      EXPECT_GE(a, 0.5 - 1e-12);
      EXPECT_LE(a, 1.5 + 1e-12);
    }
}

TEST(NoiseDisplace, KernelMatchesReferenceAndNoiseIsSmooth) {
  const Mesh m = test::icosphere(4);
  std::vector<Vec3f> normals(m.positions.begin(), m.positions.end());  // unit sphere
  const cl::Buffer rest = test::to_device(m.positions);
  const cl::Buffer nb = test::to_device(Positions(normals.begin(), normals.end()));
  cl::Buffer out = test::to_device(m.positions);
  deform::noise_displace(test::device(), rest, nb, m.vertex_count(), 5.0, 0.08, out);
  const Positions ref = deform::noise_displace_reference(m.positions, normals, 5.0, 0.08);
  EXPECT_LE(test::max_difference(test::from_device(out, m.vertex_count()), ref), 1e-6);
  EXPECT_GT(test::max_difference(ref, m.positions), 0.02);  // it moved the surface
  // In [-1, 1], Lipschitz with constant <= frequency.
  double lo = 1, hi = -1;
  for (int i = 0; i < 1000; ++i) {
    const double x = 0.013 * i, y = std::sin(i), z = std::cos(0.7 * i);
    const double n = deform::smooth_noise(x, y, z, 5.0);
    lo = std::min(lo, n), hi = std::max(hi, n);
    EXPECT_LE(std::abs(deform::smooth_noise(x + 1e-4, y, z, 5.0) - n), 5.0 * 1e-4 + 1e-12);
  }
  EXPECT_GE(lo, -1);
  EXPECT_LE(hi, 1);
  EXPECT_GT(hi - lo, 0.5);
}

// Two bones over the unit sphere's vertices: weights blend from bone 0 (z < 0) to bone 1.
// With `halves` the weights are 0, 1/2 or 1 (exact in binary, so an identity pose is exact).
std::string two_bone_skin(const Mesh& m, const std::string& second_rotation, bool halves = false) {
  std::string w = "[";
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    double u = std::clamp(0.5 + m.positions[i][2], 0.0, 1.0);
    if (halves) u = std::round(2 * u) / 2;
    w += (i ? "," : "") + std::string("[[0,") + std::to_string(1 - u) + "],[1," +
         std::to_string(u) + "]]";
  }
  w += "]";
  return R"({"bones": [{"name": "root"}, {"name": "top", "pivot": [0, 0, 0.2]}],
             "weights": )" +
         w + R"(,
             "keyframes": [
               {"time": 0, "pose": [{}, {}]},
               {"time": 2, "pose": [{"translation": [0.1, 0, 0]},
                                    {"rotation": )" +
         second_rotation + R"(,
                                     "translation": [0, 0.2, 0]}]}]})";
}

TEST(Skinning, KernelMatchesReference) {
  const Mesh m = test::icosphere(4);
  const deform::Skin skin =
      deform::parse_skin(two_bone_skin(m, "[0.8660254, 0.5, 0, 0]"), "test", m.vertex_count());
  deform::DeviceSkin ds(test::device(), skin);
  const cl::Buffer rest = test::to_device(m.positions);
  cl::Buffer out = test::to_device(m.positions);
  for (double t : {-1.0, 0.0, 0.5, 1.3, 2.0, 5.0}) {
    const std::vector<deform::Affine> mats = deform::bone_matrices(skin, t);
    ds.apply(rest, mats, out);
    const Positions ref = deform::skin_reference(m.positions, skin, mats);
    EXPECT_LE(test::max_difference(test::from_device(out, m.vertex_count()), ref), 1e-6) << t;
  }
}

TEST(Skinning, IdentityMatricesLeaveTheMeshUnchanged) {
  const Mesh m = test::lumpy_sphere(4);
  const deform::Skin skin =
      deform::parse_skin(two_bone_skin(m, "[1, 0, 0, 0]", true), "test", m.vertex_count());
  deform::DeviceSkin ds(test::device(), skin);
  const cl::Buffer rest = test::to_device(m.positions);
  cl::Buffer out = test::to_device(Positions(m.vertex_count(), Vec3f{9, 9, 9}));
  const std::vector<deform::Affine> identity(2, deform::scaling(1, 1, 1));
  ds.apply(rest, identity, out);
  const Positions got = test::from_device(out, m.vertex_count());
  EXPECT_EQ(test::max_difference(got, m.positions), 0.0);  // bit for bit
  // The keyframed skin at t = 0 is the identity pose too.
  ds.apply(rest, deform::bone_matrices(skin, 0), out);
  EXPECT_EQ(test::max_difference(test::from_device(out, m.vertex_count()), m.positions), 0.0);
}

TEST(Skinning, SlerpHalfwayIsHalfTheAngle) {
  const Mesh m = test::icosphere(0);
  // Bone 1 turns 90 degrees about x by t = 2 (quaternion cos 45, sin 45): half at t = 1.
  const deform::Skin skin = deform::parse_skin(two_bone_skin(m, "[0.70710678, 0.70710678, 0, 0]"),
                                               "test", m.vertex_count());
  const deform::Affine r = deform::bone_matrices(skin, 1.0)[1];
  EXPECT_NEAR(r[5], std::cos(3.14159265358979 / 4), 1e-6);  // R_yy
  EXPECT_NEAR(r[9], std::sin(3.14159265358979 / 4), 1e-6);  // R_zy
  const deform::Affine t0 = deform::bone_matrices(skin, 1.0)[0];
  EXPECT_NEAR(t0[3], 0.05, 1e-7);  // translation lerped halfway
}

void expect_skin_error(const std::string& text, std::size_t vertices, const std::string& words) {
  try {
    deform::parse_skin(text, "rig.json", vertices);
    ADD_FAILURE() << "no error for " << text;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(words), std::string::npos) << what;
    EXPECT_NE(what.find("rig.json"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(Skinning, BadFilesAreOneLineErrors) {
  const std::string keys = R"("keyframes": [{"time": 0, "pose": [{}]}])";
  expect_skin_error("{\"bones\": [", 1, "not valid JSON");
  expect_skin_error(R"({"bones": [{}], "weights": [[[1, 1.0]]], )" + keys + "}", 1,
                    "refers to bone 1 but the skin has 1 bones");
  expect_skin_error(R"({"bones": [{}], "weights": [[[0, 0.7]]], )" + keys + "}", 1,
                    "weights sum to 0.7, not 1");
  expect_skin_error(R"({"bones": [{}], "weights": [[[0, 1]]], )" + keys + "}", 2,
                    "weights for 1 vertices but the mesh has 2");
  expect_skin_error(R"({"bones": [{}], "weights": [[[0, 1]]]})", 1, "missing \"keyframes\"");
  expect_skin_error(R"({"bones": [{}], "weights": [[[0, 1]]], "keyframes": [
                       {"time": 1, "pose": [{}]}, {"time": 1, "pose": [{}]}]})",
                    1, "is not after the previous keyframe");
  expect_skin_error(R"({"bones": [{}], "weights": [[[0, 1]]], "keyframes": [
                       {"time": 0, "pose": [{"rotation": [0, 0, 0, 0]}]}]})",
                    1, "zero quaternion");
  expect_skin_error(
      R"({"bones": [{}], "weights": [[[0,0.2],[0,0.2],[0,0.2],[0,0.2],[0,0.2]]], )" + keys + "}", 1,
      "1 to 4");
  EXPECT_THROW(deform::load_skin("/nonexistent/rig.json", 1), Error);
}

}  // namespace
}  // namespace isocurv
