#include "labels/label_merge.h"

#include <algorithm>
#include <limits>
#include <type_traits>

#include "core/error.h"
#include "io/field_arrays.h"

namespace isocurv::labels {
namespace {

/// Appends `b` to `a` when both sides have the array; a part without it empties it for good.
template <class A, class B>
void concat(A& a, const B& b, bool first) {
  if constexpr (std::is_same_v<std::remove_const_t<A>, std::remove_const_t<B>>) {
    if (first) a = b;
    else if (a.empty() || b.empty()) a.clear();
    else a.insert(a.end(), b.begin(), b.end());
  }
}

/// Calls fn(into's array, part's array of the same name) for every array of `into`; part's
/// missing extras are passed as an empty vector.
template <class Fn>
void for_each_pair(curvature::CurvatureField& into, const curvature::CurvatureField& part, Fn&& fn) {
  io::for_each_array(into, [&](const char* name, auto& a) {
    bool matched = false;
    io::for_each_array(part, [&](const char* other, const auto& b) {
      if (matched || std::string(name) != other) return;
      if constexpr (std::is_same_v<std::decay_t<decltype(a)>, std::decay_t<decltype(b)>>) {
        fn(a, b);
        matched = true;
      }
    });
    if (!matched) a.clear();
  });
}

}  // namespace

void append_label(LabelledMesh& into, std::int64_t value, const Mesh& mesh,
                  const curvature::CurvatureField* field) {
  const std::size_t base = into.mesh.positions.size();
  if (base + mesh.positions.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("the labels' surfaces hold more than 2^32 - 1 vertices together");
  const curvature::CurvatureField none;
  const curvature::CurvatureField& f = field ? *field : none;
  io::check_field_sizes(f, mesh.positions.size(), "label " + std::to_string(value));
  const bool first = into.parts.empty();

  LabelPart part;
  part.value = value;
  part.first_vertex = static_cast<std::uint32_t>(base);
  part.vertices = static_cast<std::uint32_t>(mesh.positions.size());
  part.first_triangle = into.mesh.triangles.size();
  part.triangles = mesh.triangles.size();

  into.mesh.positions.insert(into.mesh.positions.end(), mesh.positions.begin(), mesh.positions.end());
  into.mesh.triangles.reserve(into.mesh.triangles.size() + mesh.triangles.size());
  const auto b = static_cast<std::uint32_t>(base);
  for (const Tri& t : mesh.triangles) into.mesh.triangles.push_back({t[0] + b, t[1] + b, t[2] + b});
  into.mesh.edge_keys.clear();
  into.triangle_labels.insert(into.triangle_labels.end(), mesh.triangles.size(),
                              static_cast<std::int32_t>(value));

  // The Label array travels outside the pairing and is put back last.
  curvature::CurvatureField::Named label{"Label", {}};
  auto& extra = into.field.extra;
  auto it = std::find_if(extra.begin(), extra.end(), [](const auto& e) { return e.name == "Label"; });
  if (it != extra.end()) {
    label = std::move(*it);
    extra.erase(it);
  }
  if (first) {
    into.field = f;
    into.field.extra.erase(std::remove_if(into.field.extra.begin(), into.field.extra.end(),
                                          [](const auto& e) { return e.name == "Label"; }),
                           into.field.extra.end());
  } else if (!mesh.positions.empty()) {
    for_each_pair(into.field, f, [&](auto& a, const auto& src) { concat(a, src, false); });
    concat(into.field.surface_points, f.surface_points, false);  // not a file array
  }
  label.values.insert(label.values.end(), mesh.positions.size(), static_cast<float>(value));
  into.field.extra.push_back(std::move(label));
  into.parts.push_back(part);
}

void extract_label(const LabelledMesh& m, std::int64_t value, Mesh& mesh,
                   curvature::CurvatureField& field) {
  auto p = std::find_if(m.parts.begin(), m.parts.end(), [&](const LabelPart& q) { return q.value == value; });
  if (p == m.parts.end()) {
    mesh = Mesh{};
    field = curvature::CurvatureField{};
    return;
  }
  extract_label(m.mesh, m.field, *p, mesh, field);
}

void extract_label(const Mesh& merged, const curvature::CurvatureField& merged_field,
                   const LabelPart& part, Mesh& mesh, curvature::CurvatureField& field) {
  mesh = Mesh{};
  field = curvature::CurvatureField{};
  const LabelPart* p = &part;
  const std::uint32_t v0 = p->first_vertex;
  mesh.positions.assign(merged.positions.begin() + v0, merged.positions.begin() + v0 + p->vertices);
  mesh.triangles.reserve(p->triangles);
  for (std::size_t t = p->first_triangle; t < p->first_triangle + p->triangles; ++t) {
    const Tri& tri = merged.triangles[t];
    mesh.triangles.push_back({tri[0] - v0, tri[1] - v0, tri[2] - v0});
  }
  field.metadata = merged_field.metadata;
  if (!merged_field.surface_points.empty())
    field.surface_points.assign(merged_field.surface_points.begin() + v0,
                                merged_field.surface_points.begin() + v0 + p->vertices);
  io::for_each_array(merged_field, [&](const char* name, const auto& src) {
    if (src.empty()) return;
    auto slice = [&](auto& dst) { dst.assign(src.begin() + v0, src.begin() + v0 + p->vertices); };
    bool fixed = false;
    io::for_each_array(field, [&](const char* other, auto& dst) {
      if constexpr (std::is_same_v<std::decay_t<decltype(dst)>, std::decay_t<decltype(src)>>) {
        if (!fixed && std::string(name) == other) {
          slice(dst);
          fixed = true;
        }
      }
    });
    if (!fixed) {
      if constexpr (std::is_same_v<std::decay_t<decltype(src)>, std::vector<float>>) {
        field.extra.push_back({name, {}});
        slice(field.extra.back().values);
      }
    }
  });
}

}  // namespace isocurv::labels
