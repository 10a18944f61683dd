#include "compare.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/vec3.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {
double angle(const Vec3f& a, const Vec3f& b, bool as_lines) {
  const double d = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  const double la = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
  const double lb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
  if (la == 0 || lb == 0) return la == lb ? 0 : M_PI;
  const double c = std::clamp(d / (la * lb), -1.0, 1.0);
  return std::acos(as_lines ? std::abs(c) : c);
}
}  // namespace

std::string FieldDifference::str() const {
  std::ostringstream s;
  s << "k1 " << k1 << ", k2 " << k2 << ", H " << H << ", K " << K << ", normals " << normal_angle
    << " rad, dir1 " << dir_angle << " rad (" << dir_count << " vertices), dcurv " << dcurv
    << ", area " << area << (same_boundary ? "" : ", boundary flags differ");
  return s.str();
}

FieldDifference compare(const curvature::CurvatureField& x, const curvature::CurvatureField& ref,
                        double gap) {
  FieldDifference d;
  const std::size_t n = ref.size();
  std::vector<double> a[5], b[5];
  std::vector<double> dc, dc_ref;
  for (std::size_t i = 0; i < n; ++i) {
    const float xs[5] = {x.k1[i], x.k2[i], x.H[i], x.K[i], x.area[i]};
    const float rs[5] = {ref.k1[i], ref.k2[i], ref.H[i], ref.K[i], ref.area[i]};
    for (int q = 0; q < 5; ++q) a[q].push_back(xs[q]), b[q].push_back(rs[q]);
    d.normal_angle = std::max(d.normal_angle, angle(x.normals[i], ref.normals[i], false));
    if (ref.k1[i] - ref.k2[i] > gap) {
      d.dir_angle = std::max(d.dir_angle, angle(x.dir1[i], ref.dir1[i], true));
      ++d.dir_count;
      // dcurv = (C111, C112, C122, C222) flips with dir1 (odd powers of it) and dir2.
      const double s1 = vec3::wide_dot(x.dir1[i], ref.dir1[i]) < 0 ? -1 : 1;
      const double s2 = vec3::wide_dot(x.dir2[i], ref.dir2[i]) < 0 ? -1 : 1;
      const double sign[4] = {s1, s2, s1, s2};
      for (int q = 0; q < 4; ++q)
        dc.push_back(sign[q] * x.dcurv[i][q]), dc_ref.push_back(ref.dcurv[i][q]);
    }
    d.same_boundary = d.same_boundary && x.boundary[i] == ref.boundary[i];
  }
  double c2 = 0, c4 = 0;  // mean curvedness^2 and ^4
  for (float c : ref.curvedness) c2 += double(c) * c / n, c4 += double(c) * c * c * c / n;
  auto scaled_rms = [&](const std::vector<double>& x, const std::vector<double>& r, double scale2) {
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) sum += (x[i] - r[i]) * (x[i] - r[i]) / n;
    return scale2 > 0 ? std::sqrt(sum / scale2) : std::sqrt(sum);
  };
  d.k1 = scaled_rms(a[0], b[0], c2);
  d.k2 = scaled_rms(a[1], b[1], c2);
  d.H = scaled_rms(a[2], b[2], c2);
  d.K = scaled_rms(a[3], b[3], c4);
  d.area = relative_rms(a[4], b[4]);
  d.dcurv = relative_rms(dc, dc_ref);
  return d;
}

}  // namespace isocurv::test
