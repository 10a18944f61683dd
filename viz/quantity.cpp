#include "viz/quantity.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"

namespace isocurv::viz {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

const std::vector<std::string>& color_quantities() {
  static const std::vector<std::string> names = {"H", "K", "k1", "k2", "ShapeIndex", "Curvedness", "AO"};
  return names;
}

std::string canonical_quantity(const std::string& name) {
  for (const std::string& q : color_quantities())
    if (q == name) return q;
  for (const std::string& q : color_quantities())  // "h" is H, "k" is K: exact case wins above
    if (lower(q) == lower(name)) return q;
  std::string choices;
  for (const std::string& q : color_quantities()) choices += (choices.empty() ? "" : ", ") + q;
  throw Error("unknown colour quantity '" + name + "' (choose one of " + choices + ")");
}

const std::vector<float>& quantity_values(const curvature::CurvatureField& field, const std::string& name) {
  const std::string q = canonical_quantity(name);
  const std::vector<float>* values = nullptr;
  if (q == "H") values = &field.H;
  else if (q == "K") values = &field.K;
  else if (q == "k1") values = &field.k1;
  else if (q == "k2") values = &field.k2;
  else if (q == "ShapeIndex") values = &field.shape_index;
  else if (q == "Curvedness") values = &field.curvedness;
  else values = &field.ao;
  if (values->empty()) throw Error("the curvature field has no '" + q + "' values to colour by");
  return *values;
}

bool is_signed_quantity(const std::string& name) {
  const std::string q = canonical_quantity(name);
  return q != "Curvedness" && q != "AO";
}

std::string quantity_description(const std::string& name) {
  const std::string q = canonical_quantity(name);
  if (q == "H") return "mean curvature H";
  if (q == "K") return "Gaussian curvature K";
  if (q == "k1") return "k1 (larger principal curvature)";
  if (q == "k2") return "k2 (smaller principal curvature)";
  if (q == "ShapeIndex") return "shape index";
  if (q == "Curvedness") return "curvedness";
  return "ambient occlusion";
}

std::string quantity_unit(const std::string& name, const std::string& length_unit) {
  const std::string q = canonical_quantity(name);
  const std::string l = length_unit.empty() ? "length" : length_unit;
  if (q == "ShapeIndex" || q == "AO") return "";
  return q == "K" ? "1/" + l + "\u00b2" : "1/" + l;
}

}  // namespace isocurv::viz
