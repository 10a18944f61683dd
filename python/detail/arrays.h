#pragma once
// The Python module's numpy results: views of C++ arrays kept alive by their owner, copies, and
// a CurvatureField to and from a dict of arrays named as in the files (isocurv.CurvatureArrays).
#include <cstring>
#include <utility>
#include <vector>

#include "curvature/curvature_field.h"
#include "python/detail/args.h"

namespace isocurv::python {

/// A numpy view of `n` rows of `cols` elements of T at `data`, kept alive by `base`.
template <class T>
py::array view(const T* data, std::size_t n, std::size_t cols, py::handle base) {
  if (n == 0)
    return cols == 1 ? py::array_t<T>(std::vector<py::ssize_t>{0})
                     : py::array_t<T>(std::vector<py::ssize_t>{0, py::ssize_t(cols)});
  if (cols == 1) return py::array_t<T>({n}, {sizeof(T)}, data, base);
  return py::array_t<T>({n, cols}, {cols * sizeof(T), sizeof(T)}, data, base);
}

/// A copy of `v` as a numpy array of `shape`.
template <class T>
py::array copy_array(const std::vector<T>& v, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
  return std::move(a);
}

/// isocurv.CurvatureArrays: the dict subclass curvature() returns (made at module import).
extern py::handle curvature_arrays_type;

/// Makes isocurv.CurvatureArrays in `m` (curvature_arrays_type).
void add_curvature_arrays_type(py::module_& m);

/// The field's non-empty arrays as numpy views of one heap copy of the field (owned by a capsule),
/// stored by name into `out` (a dict, or a CurvatureArrays).
py::object field_dict(curvature::CurvatureField&& field, py::object out = py::dict());

/// A dict of arrays (names as in the files) -> CurvatureField, each checked against `vertices`.
curvature::CurvatureField field_from_dict(const py::dict& arrays, std::size_t vertices);

/// A CurvatureArrays of the field's arrays carrying `report`.
py::object curvature_arrays(curvature::CurvatureField&& field, py::dict report);

}  // namespace isocurv::python
