#pragma once
// The per-vertex quantities a surface can be coloured by: the curvature arrays (H, K, k1, k2,
// ShapeIndex, Curvedness, AO), the Unreliable and Boundary flags, and every extra array of the
// field (features/ "LBE", "H_ii_r0.3", curvature/multi_scale "H_s2", ...). What a name means is
// read from the name: its base (the name without a scale suffix "_s<S>" or a radius suffix
// "_r<R>") decides its kind (QuantityKind), its colour map and range (color_map.h), its unit and
// its description.
// Tested in tests/viz/test_color_map.cpp, tests/viz/test_explorer.cpp.
#include <string>
#include <vector>

#include "curvature/curvature_field.h"

namespace isocurv::viz {

/// The core colour quantities in the explorer's order: H, K, k1, k2, ShapeIndex, Curvedness, AO.
const std::vector<std::string>& color_quantities();

/// How a quantity is coloured, from its name (quantity_kind).
enum class QuantityKind {
  curvature,    ///< signed curvature: H, K, k1, k2 and names "H_..." "K_..." "k1_..." "k2_..."
                ///< (H_s2, H_ii, K_ii_r4): diverging, symmetric about 0 or 0..extreme
  shape_index,  ///< ShapeIndex, SI and "ShapeIndex_..." "SI_..." (SI_ii): diverging over [-1, 1]
  occlusion,    ///< AO and "AO_...": grey over [0, 1]
  flag,         ///< Unreliable, Boundary, FeatureBoundary (and suffixed): 0/1, viridis over [0, 1]
  magnitude,    ///< Curvedness and "Curvedness_...": never negative, viridis over [0, high]
  label,        ///< Label (of label maps): viridis over [lowest, highest], no percentile clamp
  other,        ///< anything else (LBE, NSV, Vr, ...): viridis over the percentile range
};

/// The kind of quantity `name` (see QuantityKind; case matters: "k1" is not "K1").
QuantityKind quantity_kind(const std::string& name);

/// True for the kinds whose sign means something (curvature, shape_index).
bool is_signed_quantity(const std::string& name);

/// A name split into its base and suffix: "H_ii_r0.3" -> {"H_ii", "", "0.3"}, "H_s2" -> {"H",
/// "2", ""}, "LBE" -> {"LBE", "", ""}. A suffix is the last "_s" or "_r" followed by a digit or
/// a point (as --scale and --radius write them, "_r2%" included).
struct QuantityName {
  std::string base, scale, radius;
};
QuantityName split_quantity_name(const std::string& name);

/// The canonical spelling of a core quantity given in any letter case ("shapeindex" ->
/// "ShapeIndex"; exact case wins: "k" is K); any other name is returned as it is.
std::string canonical_quantity(const std::string& name);

/// Every array of `field` that can colour its surface, in the explorer's cycling order: the core
/// quantities it carries, Unreliable and Boundary when present, then its extra arrays in order.
std::vector<std::string> field_quantities(const curvature::CurvatureField& field);

/// The name under which `field` carries the array `name` means: the exact name, else the one
/// array equal to it ignoring case. @throw Error "no point array 'X' to colour by; this mesh
/// has: H, K, ..." (field_quantities) when there is none.
std::string resolve_quantity(const curvature::CurvatureField& field, const std::string& name);

/// The values of array `name` (resolve_quantity) in `field`, one per vertex (flags as 0 or 1).
/// @throw Error when the field does not carry it.
std::vector<float> quantity_values(const curvature::CurvatureField& field, const std::string& name);

/// A reader's name for quantity `name`, for titles: "mean curvature H", "Gaussian curvature K",
/// "k1 (larger principal curvature)", "shape index", "curvedness", "ambient occlusion",
/// "H_ii (integral-invariant mean curvature)", ...; the scale or radius of a suffixed name is
/// added: "mean curvature H (scale 2)", "H_ii (integral-invariant mean curvature, r = 0.3)".
/// Any other name is itself (with its scale or radius).
std::string quantity_description(const std::string& name);

/// The short label of the legend: the base and its scale or radius: "H", "H (scale 2)",
/// "H_ii (r = 0.3)", "LBE (r = 2%)".
std::string quantity_label(const std::string& name);

/// The unit of quantity `name` when lengths are in `length_unit` (e.g. "mm"; empty: "length"):
/// "1/mm" for H, k1, k2, Curvedness and arrays named after them, "1/mm²" for K, K_ii and LBE,
/// "mm³" for Vr, empty for the dimensionless (shape index, AO, flags, NSV) and unknown arrays.
std::string quantity_unit(const std::string& name, const std::string& length_unit);

}  // namespace isocurv::viz
