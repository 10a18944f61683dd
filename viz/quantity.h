#pragma once
// The per-vertex quantities a surface can be coloured by.
#include <string>
#include <vector>

#include "curvature/curvature_field.h"

namespace isocurv::viz {

/// The colour quantities in the explorer's cycling order: H, K, k1, k2, ShapeIndex, Curvedness, AO.
const std::vector<std::string>& color_quantities();

/// The canonical spelling of a colour quantity given in any letter case ("shapeindex" ->
/// "ShapeIndex"); throws Error listing the choices for an unknown name.
std::string canonical_quantity(const std::string& name);

/// The values of quantity `name` (canonical or any case) in `field`. Throws Error for an unknown
/// name or when the field does not carry that array.
const std::vector<float>& quantity_values(const curvature::CurvatureField& field, const std::string& name);

/// True for quantities whose sign means something (H, K, k1, k2, ShapeIndex), coloured on a range
/// symmetric around zero; false for Curvedness and AO (never negative).
bool is_signed_quantity(const std::string& name);

/// A reader's name for quantity `name`: "mean curvature H", "Gaussian curvature K", "k1 (larger
/// principal curvature)", "k2 (smaller principal curvature)", "shape index", "curvedness",
/// "ambient occlusion". @throw Error for an unknown name.
std::string quantity_description(const std::string& name);

/// The unit of quantity `name` when lengths are in `length_unit` (e.g. "mm"; empty: "length"):
/// "1/mm" for H, k1, k2 and Curvedness, "1/mm²" for K, empty for the dimensionless ShapeIndex and
/// AO. @throw Error for an unknown name.
std::string quantity_unit(const std::string& name, const std::string& length_unit);

}  // namespace isocurv::viz
