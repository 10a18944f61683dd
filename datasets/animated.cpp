#include "datasets/animated.h"

#include <array>
#include <cmath>
#include <functional>
#include <sstream>

#include "core/error.h"

namespace isocurv::datasets {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using volume::Inside;

constexpr double kPi = 3.14159265358979323846;

Eigen::AlignedBox3d cube(double half) {
  return Eigen::AlignedBox3d(Vector3d::Constant(-half), Vector3d::Constant(half));
}

std::string at(double t) {
  std::ostringstream s;
  s.precision(17);
  s << ", t = " << t;
  return s.str();
}

class PulsingSphere final : public Field {
 public:
  explicit PulsingSphere(double t)
      : Field({"pulsing_sphere",
               "signed distance |p| - R(t), R(t) = 0.6 + 0.2 sin(2 pi t), negative inside" + at(t),
               0.0, Inside::Below, cube(1.0), true, 2}),
        r_(pulsing_sphere_radius(t)) {}
  double value(const Vector3d& p) const override { return p.norm() - r_; }
  Vector3d gradient(const Vector3d& p) const override {
    const double n = p.norm();
    return n > 0 ? Vector3d(p / n) : Vector3d::Zero();
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double n = p.norm();
    if (n == 0) return Matrix3d::Zero();
    const Vector3d u = p / n;
    return (Matrix3d::Identity() - u * u.transpose()) / n;
  }

 private:
  double r_;
};

class GyroidPhase final : public Field {
 public:
  static constexpr double w = 2 * kPi;
  explicit GyroidPhase(double t)
      : Field({"gyroid_phase",
               "sin(wx + f)cos(wy) + sin(wy)cos(wz) + sin(wz)cos(wx + f), w = 2 pi, f = 2 pi t, "
               "cut by [-1,1]^3" +
                   at(t),
               0.0, Inside::Above, cube(1.0), false, std::nullopt}),
        phase_(2 * kPi * t) {}
  double value(const Vector3d& p) const override {
    const double ax = w * p.x() + phase_, ay = w * p.y(), az = w * p.z();
    return std::sin(ax) * std::cos(ay) + std::sin(ay) * std::cos(az) + std::sin(az) * std::cos(ax);
  }
  Vector3d gradient(const Vector3d& p) const override {
    const Vector3d a(w * p.x() + phase_, w * p.y(), w * p.z());
    const Vector3d s = a.array().sin(), c = a.array().cos();
    return w * Vector3d(c.x() * c.y() - s.z() * s.x(), c.y() * c.z() - s.x() * s.y(),
                        c.z() * c.x() - s.y() * s.z());
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const Vector3d a(w * p.x() + phase_, w * p.y(), w * p.z());
    const Vector3d s = a.array().sin(), c = a.array().cos();
    Matrix3d h;
    h(0, 0) = -s.x() * c.y() - s.z() * c.x();
    h(1, 1) = -s.y() * c.z() - s.x() * c.y();
    h(2, 2) = -s.z() * c.x() - s.y() * c.z();
    h(0, 1) = h(1, 0) = -c.x() * s.y();
    h(1, 2) = h(2, 1) = -c.y() * s.z();
    h(0, 2) = h(2, 0) = -c.z() * s.x();
    return w * w * h;
  }

 private:
  double phase_;
};

class Metaballs final : public Field {
 public:
  static constexpr double sigma = 0.22, amplitude = 0.45;
  explicit Metaballs(double t)
      : Field({"metaballs",
               "sum of 5 Gaussians exp(-d^2/(2 s^2)), s = 0.22, iso 0.5, centres on Lissajous "
               "paths of amplitude 0.45" +
                   at(t),
               0.5, Inside::Above, cube(1.0), true, std::nullopt}) {
    // Frequencies (a, b, c) and phases (p, q, r) in periods of each site's path.
    static const std::array<std::array<double, 6>, 5> paths = {{{1, 2, 3, 0.00, 0.25, 0.10},
                                                                {2, 1, 1, 0.20, 0.00, 0.45},
                                                                {3, 2, 1, 0.40, 0.60, 0.80},
                                                                {1, 3, 2, 0.65, 0.35, 0.55},
                                                                {2, 3, 1, 0.85, 0.15, 0.30}}};
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const auto& q = paths[i];
      sites_[i] = amplitude * Vector3d(std::sin(2 * kPi * (q[0] * t + q[3])),
                                       std::sin(2 * kPi * (q[1] * t + q[4])),
                                       std::sin(2 * kPi * (q[2] * t + q[5])));
    }
  }
  double value(const Vector3d& p) const override {
    double v = 0;
    for (const Vector3d& s : sites_) v += gauss(p - s);
    return v;
  }
  Vector3d gradient(const Vector3d& p) const override {
    Vector3d g = Vector3d::Zero();
    for (const Vector3d& s : sites_) g -= gauss(p - s) * (p - s) / (sigma * sigma);
    return g;
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double s2 = sigma * sigma;
    Matrix3d h = Matrix3d::Zero();
    for (const Vector3d& s : sites_) {
      const Vector3d d = p - s;
      h += gauss(d) * (d * d.transpose() / (s2 * s2) - Matrix3d::Identity() / s2);
    }
    return h;
  }

 private:
  static double gauss(const Vector3d& d) {
    return std::exp(-d.squaredNorm() / (2 * sigma * sigma));
  }
  std::array<Vector3d, 5> sites_;
};

using Maker = std::function<std::unique_ptr<Field>(double)>;
const std::vector<std::pair<std::string, Maker>>& catalogue() {
  static const std::vector<std::pair<std::string, Maker>> entries = {
      {"pulsing_sphere", [](double t) { return std::make_unique<PulsingSphere>(t); }},
      {"gyroid_phase", [](double t) { return std::make_unique<GyroidPhase>(t); }},
      {"metaballs", [](double t) { return std::make_unique<Metaballs>(t); }},
  };
  return entries;
}

}  // namespace

double pulsing_sphere_radius(double t) { return 0.6 + 0.2 * std::sin(2 * kPi * t); }

std::vector<std::string> animated_field_names() {
  std::vector<std::string> names;
  for (const auto& e : catalogue()) names.push_back(e.first);
  return names;
}

std::unique_ptr<Field> make_animated_field(const std::string& name, double t) {
  if (!std::isfinite(t)) throw Error("animated dataset '" + name + "': time is not finite");
  for (const auto& e : catalogue())
    if (e.first == name) return e.second(t);
  std::string known;
  for (const auto& e : catalogue()) known += (known.empty() ? "" : ", ") + e.first;
  throw Error("unknown animated dataset '" + name + "' (known: " + known + ")");
}

}  // namespace isocurv::datasets
