// curvature::resolve (curvature/request.h): the default estimator, each rule's field and problem,
// the resolved normals and host_normals, the AO rules (check_ao); and volume::checked_isovalue, the isovalue's rules. The
// command line and the Python module word these errors (tests/app, python/tests).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/mesh_measures.h"
#include "curvature/face_average_normals.h"
#include "curvature/request.h"
#include "test_meshes.h"
#include "volume/isovalue_check.h"

namespace isocurv::test {
namespace {

using curvature::Estimator;
using curvature::NormalsSource;
using curvature::Request;
using curvature::RequestField;
using curvature::RequestProblem;

/// The error resolve throws for `r`, or nothing when it resolves.
std::optional<curvature::RequestError> request_error_of(const Request& r, bool has_volume,
                                                        std::optional<float> mesh_iso = {}) {
  try {
    curvature::resolve(r, has_volume, mesh_iso);
  } catch (const curvature::RequestError& e) {
    return e;
  }
  return std::nullopt;
}

void expect_request_error(const Request& r, bool has_volume, std::optional<float> mesh_iso,
                          RequestField field, RequestProblem problem, const std::string& what) {
  const std::optional<curvature::RequestError> e = request_error_of(r, has_volume, mesh_iso);
  ASSERT_TRUE(e) << what;
  EXPECT_EQ(e->field, field) << what;
  EXPECT_EQ(e->problem, problem) << what;
  // what() names the field first, as the Python module's arguments are named.
  EXPECT_EQ(std::string(e->what()).rfind(std::string(curvature::request_field_name(field)) + ": ", 0),
            0u)
      << e->what();
}

TEST(CurvatureRequest, NormalsNamesRoundTrip) {
  for (const std::string& name : curvature::normals_names()) {
    const std::optional<NormalsSource> s = curvature::normals_from_name(name);
    ASSERT_TRUE(s) << name;
    EXPECT_EQ(curvature::normals_name(*s), name);
  }
  EXPECT_EQ(curvature::normals_names().size(), 4u);
  EXPECT_EQ(curvature::normals_from_name(""), NormalsSource::automatic);
  EXPECT_EQ(curvature::normals_from_name("face-average"), NormalsSource::face_average);
  EXPECT_FALSE(curvature::normals_from_name("gradient"));
}

TEST(CurvatureRequest, DefaultEstimatorIsVolumeOnlyWithAVolumeAndNoNormals) {
  Request r;
  EXPECT_EQ(curvature::default_estimator(r, true), Estimator::volume);
  EXPECT_EQ(curvature::default_estimator(r, false), Estimator::rusinkiewicz);
  r.normals = NormalsSource::mesh;
  EXPECT_EQ(curvature::default_estimator(r, true), Estimator::rusinkiewicz);
  r.estimator = Estimator::batagelo;
  EXPECT_EQ(curvature::default_estimator(r, true), Estimator::batagelo);
  Request volume;
  volume.estimator = Estimator::volume;
  EXPECT_EQ(curvature::default_estimator(volume, false), Estimator::volume);  // asked: not checked
}

TEST(CurvatureRequest, ResolvesTheDefaults) {
  const curvature::Resolved with_volume = curvature::resolve(Request{}, true, 40.0f);
  EXPECT_EQ(with_volume.estimator, Estimator::volume);
  EXPECT_TRUE(with_volume.volume_estimator());
  EXPECT_EQ(with_volume.normals, NormalsSource::automatic);
  EXPECT_EQ(with_volume.isovalue, 40.0f);
  EXPECT_EQ(curvature::normals_report_name(with_volume), "volume estimator");

  Request mesh_estimator;
  mesh_estimator.estimator = Estimator::rusinkiewicz;
  const curvature::Resolved gradient = curvature::resolve(mesh_estimator, true, 40.0f);
  EXPECT_EQ(gradient.normals, NormalsSource::volume);  // a mesh estimator with a volume
  EXPECT_EQ(gradient.isovalue, 0.0f);
  EXPECT_EQ(curvature::normals_report_name(gradient), "volume");

  const curvature::Resolved alone = curvature::resolve(Request{}, false);
  EXPECT_EQ(alone.estimator, Estimator::rusinkiewicz);
  EXPECT_EQ(alone.normals, NormalsSource::mesh);
  EXPECT_FALSE(alone.ao_scale);

  Request given;
  given.estimator = Estimator::volume;
  given.scale = 1.5;
  given.scale_given = true;
  given.iso = 7.0f;  // iso= wins over the mesh's own
  given.ao_scale = 2.0f;
  const curvature::Resolved r = curvature::resolve(given, true, 40.0f);
  EXPECT_EQ(r.scale, 1.5);
  EXPECT_EQ(r.isovalue, 7.0f);
  EXPECT_EQ(r.ao_scale, 2.0f);
}

TEST(CurvatureRequest, EachRuleNamesItsField) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Request volume_estimator;
  volume_estimator.estimator = Estimator::volume;
  expect_request_error(volume_estimator, false, 1.0f, RequestField::estimator,
                       RequestProblem::estimator_needs_volume, "volume estimator, no volume");

  Request normals = volume_estimator;
  normals.normals = NormalsSource::mesh;
  expect_request_error(normals, true, 1.0f, RequestField::normals,
                       RequestProblem::normals_not_for_volume, "normals with the volume estimator");

  Request scale;
  scale.estimator = Estimator::rusinkiewicz;
  scale.scale = 2;
  scale.scale_given = true;
  expect_request_error(scale, true, 1.0f, RequestField::scale, RequestProblem::scale_not_for_mesh,
                       "scale with a mesh estimator");
  scale.estimator = Estimator::volume;
  scale.scale = -1;
  expect_request_error(scale, true, 1.0f, RequestField::scale, RequestProblem::not_positive,
                       "negative scale");
  scale.scale = std::numeric_limits<double>::infinity();
  expect_request_error(scale, true, 1.0f, RequestField::scale, RequestProblem::not_finite,
                       "infinite scale");

  Request volume_normals;
  volume_normals.normals = NormalsSource::volume;
  expect_request_error(volume_normals, false, std::nullopt, RequestField::normals,
                       RequestProblem::volume_normals_need_volume, "volume normals, no volume");
  EXPECT_NO_THROW(curvature::resolve(volume_normals, true));

  Request iso;
  iso.estimator = Estimator::rusinkiewicz;
  iso.iso = 3.0f;
  expect_request_error(iso, true, std::nullopt, RequestField::iso,
                       RequestProblem::iso_not_for_mesh, "iso with a mesh estimator");
  expect_request_error(Request{}, true, std::nullopt, RequestField::iso,
                       RequestProblem::needs_isovalue, "volume estimator, no isovalue");
  expect_request_error(Request{}, true, nan, RequestField::iso, RequestProblem::not_finite,
                       "the mesh's isovalue NaN");
  iso.estimator = Estimator::volume;
  iso.iso = nan;
  expect_request_error(iso, true, 1.0f, RequestField::iso, RequestProblem::not_finite, "iso NaN");

  Request ao;
  ao.ao_scale = 0.0f;
  expect_request_error(ao, false, std::nullopt, RequestField::ao_scale,
                       RequestProblem::not_positive, "ao_scale 0");
  ao.ao_scale = nan;
  expect_request_error(ao, false, std::nullopt, RequestField::ao_scale, RequestProblem::not_finite,
                       "ao_scale NaN");
}

TEST(CurvatureRequest, TheAmbientOcclusionRules) {
  // Resolved as asked; griffin (every estimator's own) when not asked.
  EXPECT_EQ(curvature::resolve(Request{}, false).ao_method, ao::Method::griffin);
  Request hattori;
  hattori.ao_method = ao::Method::hattori;
  hattori.hattori_half = true;
  const curvature::Resolved r = curvature::resolve(hattori, false);
  EXPECT_EQ(r.ao_method, ao::Method::hattori);
  EXPECT_TRUE(r.hattori_half);

  // hattori_half with another method, or none.
  Request half;
  half.hattori_half = true;
  expect_request_error(half, false, std::nullopt, RequestField::hattori_half,
                       RequestProblem::hattori_half_not_hattori, "hattori_half, no method");
  half.ao_method = ao::Method::prantl;
  expect_request_error(half, false, std::nullopt, RequestField::hattori_half,
                       RequestProblem::hattori_half_not_hattori, "hattori_half with prantl");

  // The ray casts need a volume; the curvature formulas do not.
  for (ao::Method m : {ao::Method::raycast, ao::Method::raycast_cos}) {
    Request ray;
    ray.ao_method = m;
    expect_request_error(ray, false, std::nullopt, RequestField::ao_method,
                         RequestProblem::ao_needs_volume, ao::method_name(m));
    EXPECT_NO_THROW(curvature::resolve(ray, true, 1.0f)) << ao::method_name(m);
    EXPECT_THROW(curvature::check_ao(ray, false), curvature::RequestError);
    EXPECT_NO_THROW(curvature::check_ao(ray, true));
  }
  for (ao::Method m : {ao::Method::griffin, ao::Method::griffin_exact, ao::Method::hattori,
                       ao::Method::prantl}) {
    Request formula;
    formula.ao_method = m;
    EXPECT_NO_THROW(curvature::resolve(formula, false)) << ao::method_name(m);
  }

  // check_ao alone (a file's own curvature): the same rules, the estimator's not among them.
  Request file;
  file.estimator = Estimator::volume;  // no volume: resolve's problem, not check_ao's
  file.ao_method = ao::Method::hattori;
  EXPECT_NO_THROW(curvature::check_ao(file, false));
  file.ao_scale = 0.0f;
  try {
    curvature::check_ao(file, false);
    ADD_FAILURE() << "ao_scale 0 passed check_ao";
  } catch (const curvature::RequestError& e) {
    EXPECT_EQ(e.field, RequestField::ao_scale);
  }
}

TEST(CurvatureRequest, TheFirstBrokenRuleWins) {
  // The volume estimator on a mesh alone with normals and no isovalue: the estimator is the
  // problem, reported with the estimator the request resolved to.
  Request r;
  r.estimator = Estimator::volume;
  r.normals = NormalsSource::area;
  const std::optional<curvature::RequestError> e = request_error_of(r, false);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->field, RequestField::estimator);
  EXPECT_EQ(e->estimator, Estimator::volume);
}

TEST(CurvatureRequest, HostNormalsPerSource) {
  const Mesh m = icosphere(2, 3.0f);
  EXPECT_TRUE(curvature::host_normals(NormalsSource::mesh, m, nullptr).normals.empty());
  EXPECT_TRUE(curvature::host_normals(NormalsSource::automatic, m, nullptr).normals.empty());
  EXPECT_EQ(curvature::host_normals(NormalsSource::area, m, nullptr).normals,
            area_weighted_normals(m));
  EXPECT_EQ(curvature::host_normals(NormalsSource::face_average, m, nullptr).normals,
            curvature::face_average_normals(m));
  EXPECT_THROW(curvature::host_normals(NormalsSource::volume, m, nullptr), Error);
  EXPECT_TRUE(curvature::host_computed(NormalsSource::area));
  EXPECT_FALSE(curvature::host_computed(NormalsSource::mesh));
}

TEST(IsovalueCheck, RangeAndTheInsideEnd) {
  volume::Volume v;
  v.stats.min = 0;
  v.stats.max = 10;
  v.stats.suggested_isovalue = 4;
  EXPECT_EQ(volume::checked_isovalue(v, std::nullopt), 4.0f);
  EXPECT_EQ(volume::checked_isovalue(v, 0.0f), 0.0f);  // the outside end: a surface
  auto message = [&](std::optional<float> iso) -> std::string {
    try {
      volume::checked_isovalue(v, iso);
    } catch (const volume::IsovalueError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message(11.0f), "isovalue 11 is outside the value range [0, 10]");
  EXPECT_EQ(message(std::numeric_limits<float>::infinity()), "isovalue must be a finite number");
  EXPECT_EQ(message(10.0f).rfind("isovalue 10 equals the maximum value, so there is no surface", 0),
            0u);
  v.inside = volume::Inside::Below;
  EXPECT_EQ(message(0.0f).rfind("isovalue 0 equals the minimum value", 0), 0u);
  EXPECT_EQ(volume::checked_isovalue(v, 10.0f), 10.0f);
  v.stats.suggested_isovalue = std::nan("");
  EXPECT_EQ(message(std::nullopt), "isovalue must be a finite number");
}

}  // namespace
}  // namespace isocurv::test
