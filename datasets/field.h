#pragma once
// Analytic scalar fields whose isosurfaces have exactly known curvature (the test oracles).
//
// A Field is a smooth function F: R^3 -> R with analytic gradient and Hessian, an isovalue, and
// the side of the isovalue that is the object (DESIGN.md: normals point out of the object).
// All positions and lengths are world units of that field (stated in its description()).
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "volume/volume.h"

namespace isocurv::datasets {

/// The bundled dataset the main job opens by default: "torus" (R = 0.6, r = 0.25), a closed
/// surface whose Gaussian curvature takes both signs (positive outside, negative in the hole).
inline constexpr const char* kDefaultDataset = "torus";

/// The fixed facts about a field, set once by each catalogue entry.
struct FieldInfo {
  std::string name;                ///< catalogue name, e.g. "torus"
  std::string description;         ///< one line: formula, parameters, units
  double isovalue = 0;             ///< the surface is F = isovalue
  volume::Inside inside = volume::Inside::Above;  ///< which side of the isovalue is the object
  Eigen::AlignedBox3d box;         ///< sampling domain (world); contains closed surfaces with margin
  bool closed = true;              ///< true: the surface lies strictly inside box; false: box cuts it
  std::optional<int> euler_characteristic;  ///< of the (closed) isosurface, when known
};

/// A smooth analytic scalar field. value/gradient/hessian are exact (no finite differences) and
/// thread-safe; at the few singular points (e.g. the sphere's centre) gradient/Hessian return 0.
class Field {
 public:
  virtual ~Field() = default;
  virtual double value(const Eigen::Vector3d& p) const = 0;
  virtual Eigen::Vector3d gradient(const Eigen::Vector3d& p) const = 0;
  virtual Eigen::Matrix3d hessian(const Eigen::Vector3d& p) const = 0;
  /// out[i] = value((x0 + i*dx, y, z)) for i in [0, n), bit for bit. The default calls value();
  /// fields with a faster row evaluation override it (sample() uses it).
  virtual void values_along_x(double x0, double dx, double y, double z, int n, double* out) const;

  const FieldInfo& info() const { return info_; }
  const std::string& name() const { return info_.name; }
  double isovalue() const { return info_.isovalue; }
  volume::Inside inside() const { return info_.inside; }
  const Eigen::AlignedBox3d& box() const { return info_.box; }

 protected:
  explicit Field(FieldInfo info) : info_(std::move(info)) {}

 private:
  FieldInfo info_;
};

/// Names accepted by make_field, in catalogue order: sphere, torus, ellipsoid, gyroid, schwarz_p,
/// f1, f2, marschner_lobb, hydrogen, buckyball.
std::vector<std::string> field_names();

/// Builds the named catalogue field (see fields.cpp for every formula and parameter).
/// Throws isocurv::Error for an unknown name, listing the known ones.
std::unique_ptr<Field> make_field(const std::string& name);

/// The catalogue's ellipsoid field 1 - (x/a)^2 - (y/b)^2 - (z/c)^2 (positive inside, isovalue 0)
/// with semi-axes a, b, c (world units) instead of 0.8, 0.6, 0.4; box = semi-axes + 0.2. For the
/// exact curvature of deforming-sphere animations (deform/affine.h).
/// @throw isocurv::Error for a semi-axis that is not positive and finite
std::unique_ptr<Field> make_ellipsoid(double a, double b, double c);

}  // namespace isocurv::datasets
