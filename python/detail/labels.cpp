// The label-map arguments of the Python module (python/detail/labels.h).
#include "python/detail/labels.h"

#include <algorithm>
#include <mutex>
#include <string>

#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/options.h"

namespace isocurv::python {

std::vector<std::int64_t> label_values_of(const py::object& labels_arg) {
  std::vector<std::int64_t> wanted;
  auto add = [&](const py::handle& item) {
    // Python and numpy integers (anything with __index__), not bools.
    if (py::isinstance<py::bool_>(item) || !PyIndex_Check(item.ptr()))
      throw py::type_error("labels: expected int labels, not " + type_name_of(item));
    const py::object whole = py::reinterpret_steal<py::object>(PyNumber_Index(item.ptr()));
    if (!whole) throw py::error_already_set();
    int overflow = 0;
    const long long value = PyLong_AsLongLongAndOverflow(whole.ptr(), &overflow);
    if (overflow != 0 || value > labels::kMaxLabelValue || value < -labels::kMaxLabelValue)
      throw py::value_error("labels: label " + std::string(py::str(whole)) +
                            " is beyond +-" + std::to_string(labels::kMaxLabelValue) +
                            " (labels are read as 32-bit floats, exact up to 2^24)");
    if (std::find(wanted.begin(), wanted.end(), value) != wanted.end())
      throw py::value_error("labels: label " + std::to_string(value) + " is given twice");
    wanted.push_back(value);
  };
  if (labels_arg.is_none()) {
  } else if (PyIndex_Check(labels_arg.ptr()) && !py::isinstance<py::bool_>(labels_arg)) {
    add(labels_arg);
  } else if (py::isinstance<py::sequence>(labels_arg) && !py::isinstance<py::str>(labels_arg)) {
    for (const py::handle item : labels_arg.cast<py::sequence>()) add(item);
    if (wanted.empty()) throw py::value_error("labels: empty; pass None for every label");
  } else {
    throw py::type_error("labels: expected None, an int or a sequence of ints, not " +
                         type_name_of(labels_arg));
  }
  return wanted;
}

std::vector<labels::Label> picked_labels_of(const volume::Volume& v, const py::object& labels_arg) {
  const std::vector<std::int64_t> wanted = label_values_of(labels_arg);
  const std::vector<labels::Label> all = labels::label_map_labels(v);
  std::vector<std::int64_t> missing;
  const std::vector<labels::Label> picked = labels::pick_labels(all, wanted, missing);
  if (all.empty()) throw py::value_error("volume: holds no label (every voxel is 0)");
  if (picked.empty())
    throw py::value_error("labels: none of the labels given is in the volume (it holds " +
                          std::to_string(all.size()) + " labels, from " +
                          std::to_string(all.front().value) + " to " +
                          std::to_string(all.back().value) + ")");
  if (!missing.empty() &&
      PyErr_WarnEx(PyExc_UserWarning, labels::missing_labels_note(missing).c_str(), 1) != 0)
    throw py::error_already_set();
  return picked;
}

std::function<Mesh(const volume::Volume&, float)> label_extraction(const DeviceChoice& dc) {
  return [dc](const volume::Volume& indicator, float isovalue) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(device_lock);
    return dc.reference ? mc::extract_reference(indicator, isovalue, mc::Options{})
                        : mc::extract(indicator, isovalue, opened_device(dc), mc::Options{});
  };
}

void warn_filling_labels(const std::vector<std::int64_t>& empty) {
  if (!empty.empty() &&
      PyErr_WarnEx(PyExc_UserWarning, labels::filling_labels_note(empty).c_str(), 1) != 0)
    throw py::error_already_set();
}

}  // namespace isocurv::python
