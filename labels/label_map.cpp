#include "labels/label_map.h"

#include <openvdb/tools/Dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <unordered_map>

#include "core/error.h"
#include "volume/from_dense.h"

namespace isocurv::labels {

namespace {

/// Throws when `value`, a voxel of the integer-typed map `v`, is not an integer. Only a scaling
/// makes that: NIfTI's scl_slope / scl_inter, which the loader applies (the values are real
/// values); rounding them instead once merged labels (slope 0.5: labels 1 and 2 both became 1)
/// or left every label without voxels (inter 0.25).
void check_integer(const volume::Volume& v, double value) {
  if (value == std::nearbyint(value)) return;
  std::ostringstream text;
  text << value;
  if (v.format == "nifti")
    throw Error(v.path, "--labels: the NIfTI header's scl_slope/scl_inter scale this " + v.voxel_type +
                            " label map to non-integer values (" + text.str() +
                            "), which cannot be labels; a label map must be stored unscaled (scl_slope 0 or 1, "
                            "scl_inter 0) or scaled to integers");
  throw Error(v.path, "--labels needs integer labels, and this " + v.voxel_type + " volume holds the value " +
                          text.str());
}

}  // namespace

std::vector<Label> label_map_labels(const volume::Volume& v) {
  const std::string& t = v.voxel_type;
  if (!volume::is_integer_type(t))
    throw Error(v.path, "--labels needs an integer label map (each voxel value an object); this volume holds " +
                            (t.empty() ? std::string("floats") : t) + " values");
  std::unordered_map<std::int64_t, Label> found;
  std::uint64_t visited = 0;
  const openvdb::CoordBBox& domain = v.domain;
  for (auto it = v.grid->cbeginValueAll(); it; ++it) {
    openvdb::CoordBBox b;
    it.getBoundingBox(b);
    b.intersect(domain);
    if (b.empty()) continue;
    const std::uint64_t n = b.volume();
    visited += n;
    check_integer(v, static_cast<double>(*it));
    const std::int64_t value = std::llround(static_cast<double>(*it));
    if (value == 0) continue;
    if (std::llabs(value) > kMaxLabelValue)
      throw Error(v.path, "--labels: label " + std::to_string(value) + " is beyond +-" +
                              std::to_string(kMaxLabelValue) +
                              " (2^24 - 1: volumes hold 32-bit floats, which round larger labels)");
    auto [entry, fresh] = found.try_emplace(value);
    Label& l = entry->second;
    if (fresh) {
      if (found.size() > kMaxLabels)
        throw Error(v.path, "--labels: the volume holds more than " + std::to_string(kMaxLabels) +
                                " labels (distinct non-zero values); is it a label map?");
      l.value = value;
      l.box = b;
    } else {
      l.box.expand(b);
    }
    l.voxels += n;
  }
  // Blocks equal to the grid's background everywhere are not stored; they hold the background.
  const std::int64_t background = std::llround(static_cast<double>(v.grid->background()));
  if (visited < domain.volume()) check_integer(v, static_cast<double>(v.grid->background()));
  if (visited < domain.volume() && background != 0) {
    Label& l = found[background];
    l.value = background;
    l.voxels += domain.volume() - visited;
    l.box = domain;  // where exactly is not known without a second pass; the domain holds it
  }
  std::vector<Label> out;
  out.reserve(found.size());
  for (auto& [value, l] : found) out.push_back(l);
  std::sort(out.begin(), out.end(), [](const Label& a, const Label& b) { return a.value < b.value; });
  return out;
}

std::vector<std::int64_t> parse_label_list(const std::string& text) {
  std::vector<std::int64_t> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    const std::string word = first == std::string::npos ? "" : item.substr(first, last - first + 1);
    std::size_t used = 0;
    long long value = 0;
    try {
      value = std::stoll(word, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (word.empty() || used != word.size())
      throw Error("--label: expected integer labels separated by commas (e.g. 3,7), got '" + text + "'");
    if (std::find(out.begin(), out.end(), value) != out.end())
      throw Error("--label: label " + word + " is given twice");
    out.push_back(value);
  }
  if (out.empty()) throw Error("--label: expected at least one label (e.g. 3,7)");
  return out;
}

std::vector<Label> pick_labels(const std::vector<Label>& all, const std::vector<std::int64_t>& wanted,
                               std::vector<std::int64_t>& missing) {
  if (wanted.empty()) return all;
  std::vector<Label> out;
  for (std::int64_t w : wanted) {
    auto it = std::find_if(all.begin(), all.end(), [&](const Label& l) { return l.value == w; });
    if (it == all.end()) missing.push_back(w);
    else out.push_back(*it);
  }
  return out;
}

int indicator_margin(double scale_voxels) {
  return 2 + static_cast<int>(std::ceil(4 * std::min(std::max(scale_voxels, 0.0), 64.0)));
}

volume::Volume label_indicator(const volume::Volume& v, const Label& label, int margin) {
  return labels_indicator(v, {label}, margin);
}

volume::Volume labels_indicator(const volume::Volume& v, const std::vector<Label>& labels,
                                int margin) {
  if (margin < 1) throw Error("label_indicator: the margin must be at least one voxel");
  if (labels.empty()) throw Error("labels_indicator: no label given");
  openvdb::CoordBBox box;
  std::vector<float> want;
  for (const Label& l : labels) {
    box.expand(l.box);
    want.push_back(static_cast<float>(l.value));
  }
  std::sort(want.begin(), want.end());
  box.expand(margin);
  box.intersect(v.domain);
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, 0.0f);
  openvdb::tools::copyToDense(*v.grid, dense);
  float* data = dense.data();
  const std::size_t n = dense.valueCount();
  if (want.size() == 1)
    for (std::size_t i = 0; i < n; ++i) data[i] = data[i] == want[0] ? 1.0f : 0.0f;
  else
    for (std::size_t i = 0; i < n; ++i)
      data[i] = std::binary_search(want.begin(), want.end(), data[i]) ? 1.0f : 0.0f;
  volume::Volume out;
  out.grid = openvdb::FloatGrid::create(0.0f);
  out.grid->setTransform(v.grid->transform().copy());
  out.grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  out.grid->setName(labels.size() == 1 ? "label " + std::to_string(labels[0].value)
                                       : std::to_string(labels.size()) + " labels");
  openvdb::tools::copyFromDense(dense, *out.grid, 0.0f);
  out.path = v.path;
  out.format = v.format;
  out.voxel_type = "uint8";
  out.grid_class = "fog volume";
  out.grid_name = out.grid->getName();
  out.world_space = v.world_space;
  out.length_unit = v.length_unit;
  out.dense = true;
  out.domain = box;
  out.inside = volume::Inside::Above;
  volume::compute_stats(out);
  out.stats.suggested_isovalue = 0.5;
  out.stats.suggested_from = "half the indicator";
  return out;
}

namespace {

std::string joined(const std::vector<std::int64_t>& values) {
  std::string s;
  for (std::int64_t v : values) s += (s.empty() ? "" : ", ") + std::to_string(v);
  return s;
}

}  // namespace

std::string missing_labels_note(const std::vector<std::int64_t>& labels) {
  return std::string("no voxel holds label") + (labels.size() == 1 ? " " : "s ") + joined(labels) +
         "; left out";
}

std::string filling_labels_note(const std::vector<std::int64_t>& labels) {
  const bool one = labels.size() == 1;
  return std::string("label") + (one ? " " : "s ") + joined(labels) + (one ? " has" : " have") +
         " no surface (" + (one ? "it fills" : "they fill") + " the box); left out";
}

}  // namespace isocurv::labels
