#include "viz/quantity.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"

namespace isocurv::viz {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// `name` is `word` or starts with `word` + "_" (H_ii, H_s2 for H; not Hattori).
bool named_after(const std::string& name, const std::string& word) {
  return name == word || name.rfind(word + "_", 0) == 0;
}

/// The core array of `field` named `q` (canonical), or null.
const std::vector<float>* core_values(const curvature::CurvatureField& field,
                                      const std::string& q) {
  if (q == "H") return &field.H;
  if (q == "K") return &field.K;
  if (q == "k1") return &field.k1;
  if (q == "k2") return &field.k2;
  if (q == "ShapeIndex") return &field.shape_index;
  if (q == "Curvedness") return &field.curvedness;
  if (q == "AO") return &field.ao;
  return nullptr;
}

const std::vector<std::uint8_t>* flag_values(const curvature::CurvatureField& field,
                                             const std::string& q) {
  if (q == "Unreliable") return &field.unreliable;
  if (q == "Boundary") return &field.boundary;
  return nullptr;
}

/// The description of a base name, before its scale or radius: (head, detail in parentheses).
std::pair<std::string, std::string> describe_base(const std::string& b) {
  if (b == "H") return {"mean curvature H", ""};
  if (b == "K") return {"Gaussian curvature K", ""};
  if (b == "k1") return {"k1", "larger principal curvature"};
  if (b == "k2") return {"k2", "smaller principal curvature"};
  if (b == "ShapeIndex") return {"shape index", ""};
  if (b == "Curvedness") return {"curvedness", ""};
  if (b == "AO") return {"ambient occlusion", ""};
  if (b == "H_ii") return {"H_ii", "integral-invariant mean curvature"};
  if (b == "K_ii") return {"K_ii", "geodesic-disc Gaussian curvature"};
  if (b == "SI_ii") return {"SI_ii", "integral-invariant shape index"};
  if (b == "LBE") return {"LBE", "local bending energy"};
  if (b == "NSV") return {"NSV", "normalised sphere volume"};
  if (b == "Vr") return {"Vr", "volume integral invariant"};
  if (b == "Unreliable") return {"Unreliable", "1: not measured"};
  if (b == "Boundary") return {"Boundary", "1: open-boundary vertex"};
  if (b == "FeatureBoundary") return {"FeatureBoundary", "1: neighbourhood left the data"};
  return {b, ""};
}

std::string suffix_text(const QuantityName& n) {
  if (!n.scale.empty()) return "scale " + n.scale;
  if (!n.radius.empty()) return "r = " + n.radius;
  return "";
}

}  // namespace

const std::vector<std::string>& color_quantities() {
  static const std::vector<std::string> names = {"H",          "K",          "k1", "k2",
                                                 "ShapeIndex", "Curvedness", "AO"};
  return names;
}

QuantityName split_quantity_name(const std::string& name) {
  const std::size_t u = name.rfind('_');
  if (u != std::string::npos && u > 0 && u + 2 < name.size() &&
      (name[u + 1] == 's' || name[u + 1] == 'r') &&
      (std::isdigit(static_cast<unsigned char>(name[u + 2])) || name[u + 2] == '.')) {
    QuantityName n{name.substr(0, u), "", ""};
    (name[u + 1] == 's' ? n.scale : n.radius) = name.substr(u + 2);
    return n;
  }
  return {name, "", ""};
}

QuantityKind quantity_kind(const std::string& name) {
  const std::string b = split_quantity_name(canonical_quantity(name)).base;
  for (const char* w : {"H", "K", "k1", "k2"})
    if (named_after(b, w)) return QuantityKind::curvature;
  if (named_after(b, "ShapeIndex") || named_after(b, "SI")) return QuantityKind::shape_index;
  if (named_after(b, "AO")) return QuantityKind::occlusion;
  if (b == "Unreliable" || b == "Boundary" || b == "FeatureBoundary") return QuantityKind::flag;
  if (named_after(b, "Curvedness")) return QuantityKind::magnitude;
  if (b == "Label") return QuantityKind::label;
  return QuantityKind::other;
}

bool is_signed_quantity(const std::string& name) {
  const QuantityKind k = quantity_kind(name);
  return k == QuantityKind::curvature || k == QuantityKind::shape_index;
}

std::string canonical_quantity(const std::string& name) {
  for (const std::string& q : color_quantities())
    if (q == name) return q;
  for (const std::string& q : color_quantities())  // "h" is H, "k" is K: exact case wins above
    if (lower(q) == lower(name)) return q;
  return name;
}

std::vector<std::string> field_quantities(const curvature::CurvatureField& field) {
  std::vector<std::string> out;
  for (const std::string& q : color_quantities())
    if (!core_values(field, q)->empty()) out.push_back(q);
  for (const char* q : {"Unreliable", "Boundary"})
    if (!flag_values(field, q)->empty()) out.push_back(q);
  for (const auto& e : field.extra)
    if (!e.values.empty()) out.push_back(e.name);
  return out;
}

std::string resolve_quantity(const curvature::CurvatureField& field, const std::string& name) {
  const std::vector<std::string> names = field_quantities(field);
  for (const std::string& q : names)
    if (q == name) return q;
  std::vector<std::string> matches;
  for (const std::string& q : names)
    if (lower(q) == lower(name)) matches.push_back(q);
  if (matches.size() == 1) return matches.front();
  std::string list;
  for (const std::string& q : names) list += (list.empty() ? "" : ", ") + q;
  throw Error("no point array '" + name +
              "' to colour by (--color); this mesh has: " + (list.empty() ? "none" : list));
}

std::vector<float> quantity_values(const curvature::CurvatureField& field,
                                   const std::string& name) {
  const std::string q = resolve_quantity(field, name);
  if (const auto* v = core_values(field, q)) return *v;
  if (const auto* f = flag_values(field, q)) return std::vector<float>(f->begin(), f->end());
  for (const auto& e : field.extra)
    if (e.name == q) return e.values;
  throw Error("no point array '" + name + "' to colour by");  // not reached: resolve_quantity
}

std::string quantity_description(const std::string& name) {
  const QuantityName n = split_quantity_name(canonical_quantity(name));
  auto [head, detail] = describe_base(n.base);
  const std::string s = suffix_text(n);
  if (!s.empty()) detail += (detail.empty() ? "" : ", ") + s;
  return detail.empty() ? head : head + " (" + detail + ")";
}

std::string quantity_label(const std::string& name) {
  const QuantityName n = split_quantity_name(canonical_quantity(name));
  const std::string s = suffix_text(n);
  return s.empty() ? n.base : n.base + " (" + s + ")";
}

std::string quantity_unit(const std::string& name, const std::string& length_unit) {
  const std::string q = canonical_quantity(name);
  const std::string b = split_quantity_name(q).base;
  const std::string l = length_unit.empty() ? "length" : length_unit;
  switch (quantity_kind(q)) {
    case QuantityKind::curvature:
      return named_after(b, "K") ? "1/" + l + "\u00b2" : "1/" + l;
    case QuantityKind::magnitude:
      return "1/" + l;
    case QuantityKind::shape_index:
    case QuantityKind::occlusion:
    case QuantityKind::flag:
    case QuantityKind::label:
      return "";
    case QuantityKind::other:
      break;
  }
  if (b == "LBE") return "1/" + l + "\u00b2";
  if (b == "Vr") return l + "\u00b3";
  return "";
}

}  // namespace isocurv::viz
