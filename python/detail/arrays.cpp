// The numpy results of the Python module (python/detail/arrays.h): curvature fields to and from
// dicts of arrays, and isocurv.CurvatureArrays.
#include "python/detail/arrays.h"

#include <string>
#include <type_traits>

#include "io/field_arrays.h"

namespace isocurv::python {

py::handle curvature_arrays_type;

void add_curvature_arrays_type(py::module_& m) {
  py::dict ns;
  ns["__module__"] = "isocurv";
  ns["__doc__"] =
      "The dict of numpy arrays curvature(), features() and screen() return, with .report: "
      "what was used (for curvature: the estimator, its parameters and the unreliable count).";
  py::object dict_type =
      py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyDict_Type));
  py::object cls = py::module_::import("builtins")
                       .attr("type")("CurvatureArrays", py::make_tuple(dict_type), ns);
  m.attr("CurvatureArrays") = cls;
  curvature_arrays_type = cls;  // kept alive by the module
}

py::object field_dict(curvature::CurvatureField&& field, py::object out) {
  auto* owned = new curvature::CurvatureField(std::move(field));
  py::capsule base(owned, [](void* p) { delete static_cast<curvature::CurvatureField*>(p); });
  io::for_each_array(*owned, [&](const char* name, const auto& v) {
    if (v.empty()) return;
    using E = typename std::decay_t<decltype(v)>::value_type;
    constexpr int comps = io::components_of<E>();
    if constexpr (comps == 1)
      out[name] = view(v.data(), v.size(), 1, base);
    else
      out[name] = view(v.data()->data(), v.size(), comps, base);
  });
  return out;
}

curvature::CurvatureField field_from_dict(const py::dict& arrays, std::size_t vertices) {
  curvature::CurvatureField f;
  std::size_t used = 0;
  io::for_each_array(f, [&](const char* name, auto& v) {
    if (!arrays.contains(name)) return;
    ++used;
    using E = typename std::decay_t<decltype(v)>::value_type;
    constexpr int comps = io::components_of<E>();
    using S = std::conditional_t<std::is_same_v<E, std::uint8_t>, std::uint8_t, float>;
    py::array_t<S, py::array::c_style | py::array::forcecast> a;
    try {
      a = arrays[name].template cast<py::array_t<S, py::array::c_style | py::array::forcecast>>();
    } catch (const py::error_already_set&) {
      throw py::type_error(std::string("arrays['") + name + "']: expected a numeric array");
    } catch (const py::cast_error&) {
      throw py::type_error(std::string("arrays['") + name + "']: expected a numeric array");
    }
    const bool ok = comps == 1 ? (a.ndim() == 1 || (a.ndim() == 2 && a.shape(1) == 1))
                               : (a.ndim() == 2 && a.shape(1) == comps);
    if (!ok || std::size_t(a.shape(0)) != vertices)
      throw py::value_error(
          std::string("arrays['") + name + "']: expected shape (" + std::to_string(vertices) +
          (comps == 1 ? "," : ", " + std::to_string(comps)) + ") (one per vertex)");
    v.resize(vertices);
    std::memcpy(static_cast<void*>(v.data()), a.data(), vertices * sizeof(E));
  });
  if (used != arrays.size()) {
    // The others (Unreliable, Scale, features' arrays, ...): one value per vertex, written under
    // their names after the curvature arrays.
    for (auto item : arrays) {
      const std::string key = py::str(item.first);
      bool known = false;
      io::for_each_array(f, [&](const char* name, auto&) { known = known || key == name; });
      if (known) continue;
      py::array_t<float, py::array::c_style | py::array::forcecast> a;
      try {
        a = py::reinterpret_borrow<py::object>(item.second)
                .cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
      } catch (const py::error_already_set&) {
        throw py::type_error("arrays['" + key + "']: expected a numeric array");
      } catch (const py::cast_error&) {
        throw py::type_error("arrays['" + key + "']: expected a numeric array");
      }
      if (a.ndim() != 1 || std::size_t(a.shape(0)) != vertices)
        throw py::value_error("arrays['" + key + "']: expected shape (" +
                              std::to_string(vertices) +
                              ",) (one per vertex; arrays other than Normals Area k1 k2 dir1 "
                              "dir2 H K dcurv ShapeIndex Curvedness AO Boundary are scalars)");
      if (key == "Unreliable") {
        f.unreliable.resize(vertices);
        for (std::size_t i = 0; i < vertices; ++i) f.unreliable[i] = a.data()[i] != 0;
      } else {
        f.extra.push_back({key, std::vector<float>(a.data(), a.data() + vertices)});
      }
    }
  }
  return f;
}

py::object curvature_arrays(curvature::CurvatureField&& field, py::dict report) {
  py::object out = field_dict(std::move(field), curvature_arrays_type());
  out.attr("report") = report;
  return out;
}

}  // namespace isocurv::python
