#pragma once
// The named per-vertex arrays of a CurvatureField, in one place, so that every file format and the
// renderer use the same names and component counts (DESIGN.md: "Output array names").
// Tested in tests/io/test_mesh_file.cpp.
#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "curvature/curvature_field.h"

namespace isocurv::io {

/// Number of components of one element of a field array (float or uint8 -> 1, Vec3f -> 3, ...).
template <class T>
constexpr int components_of() {
  if constexpr (std::is_arithmetic_v<T>) return 1;
  else return static_cast<int>(std::tuple_size<T>::value);
}

/// Calls fn(name, vector) for every array of the field in the canonical order: Normals, Area, k1,
/// k2, dir1, dir2, H, K, dcurv, ShapeIndex, Curvedness, AO, Boundary, Unreliable. The vector is a
/// std::vector<float>, <Vec3f>, <std::array<float, 4>> or <std::uint8_t>; fn is usually a generic
/// lambda. Works on const and non-const fields. The field's `extra` arrays come last, in order.
template <class Field, class Fn>
void for_each_array(Field& f, Fn&& fn) {
  static_assert(std::is_same_v<std::remove_const_t<Field>, curvature::CurvatureField>);
  fn("Normals", f.normals);
  fn("Area", f.area);
  fn("k1", f.k1);
  fn("k2", f.k2);
  fn("dir1", f.dir1);
  fn("dir2", f.dir2);
  fn("H", f.H);
  fn("K", f.K);
  fn("dcurv", f.dcurv);
  fn("ShapeIndex", f.shape_index);
  fn("Curvedness", f.curvedness);
  fn("AO", f.ao);
  fn("Boundary", f.boundary);
  fn("Unreliable", f.unreliable);
  for (auto& e : f.extra) fn(e.name.c_str(), e.values);
}

/// Checks that every array of `field` holds either `vertex_count` entries or none (absent);
/// throws Error(path, ...) naming the first array of another length.
void check_field_sizes(const curvature::CurvatureField& field, std::size_t vertex_count,
                       const std::string& path);

/// True when `name` is one of the fixed arrays above (not an `extra` one).
bool is_curvature_array(const std::string& name);

/// True when no array of the field holds any entries.
bool field_is_empty(const curvature::CurvatureField& field);

/// The field at the vertices `index` (each below the field's vertex count): every non-empty array,
/// surface_points included, holds `index.size()` entries, entry i that of vertex index[i]; empty
/// arrays stay empty, metadata is copied.
curvature::CurvatureField select_vertices(const curvature::CurvatureField& field,
                                          const std::vector<std::uint32_t>& index);

}  // namespace isocurv::io
