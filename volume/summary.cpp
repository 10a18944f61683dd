// summary_json / summary_text: what `isocurv info` prints about a loaded volume.
#include "volume/summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "volume/from_dense.h"

namespace isocurv::volume {
namespace {

/// Value below which `fraction` of the histogram's voxels lie (linear within a bin).
double percentile(const ValueStats& s, double fraction) {
  std::uint64_t total = 0;
  for (auto c : s.histogram) total += c;
  if (total == 0 || s.histogram.empty() || !(s.max > s.min)) return s.min;
  const double target = fraction * double(total);
  const double width = (s.max - s.min) / double(s.histogram.size());
  double cumulative = 0;
  for (std::size_t i = 0; i < s.histogram.size(); ++i) {
    const double c = double(s.histogram[i]);
    if (c > 0 && cumulative + c >= target) return s.min + width * (double(i) + (target - cumulative) / c);
    cumulative += c;
  }
  return s.max;
}

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string vec3(const openvdb::Vec3d& v) { return fmt(v.x()) + " " + fmt(v.y()) + " " + fmt(v.z()); }

/// The 1st, 50th and 99th percentiles: exact values for integer data (exact_integer_percentiles),
/// else interpolated within the 256-bin histogram. `exact` says which.
std::vector<double> percentiles(const Volume& v, bool& exact) {
  const std::vector<double> fractions = {0.01, 0.5, 0.99};
  std::vector<double> p = exact_integer_percentiles(v, fractions);
  exact = !p.empty();
  if (!exact)
    for (double f : fractions) p.push_back(percentile(v.stats, f));
  return p;
}

/// The histogram's 256 bins summed into 16.
std::vector<std::uint64_t> coarse_histogram(const ValueStats& s) {
  std::vector<std::uint64_t> coarse(16, 0);
  for (std::size_t i = 0; i < s.histogram.size(); ++i) coarse[i * 16 / s.histogram.size()] += s.histogram[i];
  return coarse;
}

}  // namespace

std::size_t label_map_hint(const Volume& v) {
  const ValueStats& s = v.stats;
  // With min 0 and max <= 255 the 256 bins are narrower than 1: one integer value per bin.
  if (!is_integer_type(v.voxel_type) || s.min != 0 || !(s.max >= 2) || s.max > 255 ||
      s.histogram.size() != 256 || s.voxels == 0)
    return 0;
  if (2 * s.histogram[0] < s.voxels) return 0;  // no background
  std::size_t labels = 0;
  for (std::size_t b = 1; b < s.histogram.size(); ++b) labels += s.histogram[b] > 0;
  // A scan quantised to few levels holds nearly every value of its range; a label map's values
  // are few (and often skip some).
  const bool few = labels <= 64;
  return labels >= 2 && few ? labels : 0;
}

nlohmann::json summary_json(const Volume& v) {
  nlohmann::json j;
  const ValueStats& s = v.stats;
  j["path"] = v.path;
  j["format"] = v.format;
  j["grid_name"] = v.grid_name;
  if (!v.world_space.empty()) j["world_space"] = v.world_space;
  if (!v.length_unit.empty()) j["length_unit"] = v.length_unit;
  j["grid_class"] = v.grid_class;
  j["voxel_type"] = v.voxel_type;
  j["dense"] = v.dense;
  const openvdb::Coord dim = v.domain.dim();
  j["dims"] = {dim.x(), dim.y(), dim.z()};
  j["domain"] = {{"min", {v.domain.min().x(), v.domain.min().y(), v.domain.min().z()}},
                 {"max", {v.domain.max().x(), v.domain.max().y(), v.domain.max().z()}}};
  if (v.grid) {
    const openvdb::Vec3d sp = v.spacing(), o = v.origin();
    j["spacing"] = {sp.x(), sp.y(), sp.z()};
    j["origin"] = {o.x(), o.y(), o.z()};
    // Present when --spacing / --origin replaced the file's values: what the file said.
    if (v.file_spacing)
      j["file_spacing"] = {v.file_spacing->x(), v.file_spacing->y(), v.file_spacing->z()};
    if (v.file_origin)
      j["file_origin"] = {v.file_origin->x(), v.file_origin->y(), v.file_origin->z()};
    j["active_voxels"] = v.grid->activeVoxelCount();
    j["background"] = v.grid->background();
  }
  j["inside"] = v.inside == Inside::Above ? "above" : "below";
  j["voxels"] = s.voxels;
  j["min"] = s.min;
  j["max"] = s.max;
  j["mean"] = s.mean;
  j["nan_count"] = s.nan_count;
  j["inf_count"] = s.inf_count;
  bool exact = false;
  const std::vector<double> p = percentiles(v, exact);
  j["percentiles"] = {{"p1", p[0]}, {"p50", p[1]}, {"p99", p[2]}};
  j["percentiles_exact"] = exact;  // integer data: values the volume holds; else interpolated
  // 16 coarse bins, each the sum of 16 of the 256 fine ones, over [min, max].
  j["histogram16"] = coarse_histogram(s);
  j["suggested_isovalue"] = s.suggested_isovalue;
  j["suggested_from"] = s.suggested_from;
  const std::size_t labels = label_map_hint(v);
  j["looks_like_label_map"] = labels > 0;
  if (labels > 0) j["label_count"] = labels;
  return j;
}

std::string summary_text(const Volume& v) {
  const ValueStats& s = v.stats;
  std::ostringstream out;
  auto line = [&out](const std::string& key, const std::string& value) {
    out << key << std::string(key.size() < 18 ? 18 - key.size() : 1, ' ') << value << "\n";
  };
  const openvdb::Coord dim = v.domain.dim();
  line("path", v.path);
  line("format", v.format + (v.dense ? " (dense)" : " (sparse)"));
  if (!v.grid_name.empty()) line("grid", v.grid_name);
  if (!v.world_space.empty()) line("world axes", v.world_space + " (anatomical: +x +y +z)");
  if (!v.length_unit.empty()) line("length unit", v.length_unit);
  line("grid class", v.grid_class);
  line("voxel type", v.voxel_type);
  line("dimensions", std::to_string(dim.x()) + " x " + std::to_string(dim.y()) + " x " + std::to_string(dim.z()) +
                         (v.dense ? "" : "  (active bbox " + std::to_string(v.domain.min().x()) + "," +
                                             std::to_string(v.domain.min().y()) + "," +
                                             std::to_string(v.domain.min().z()) + " .. " +
                                             std::to_string(v.domain.max().x()) + "," +
                                             std::to_string(v.domain.max().y()) + "," +
                                             std::to_string(v.domain.max().z()) + ")"));
  if (v.grid) {
    // An override says so, with what the file said ("header" unless the file has none).
    auto note = [&v](const char* option, const std::optional<openvdb::Vec3d>& file) {
      if (!file) return std::string();
      if (v.format == "raw") return std::string("  (from ") + option + ")";
      return std::string("  (from ") + option + "; header says " + vec3(*file) + ")";
    };
    line("spacing", vec3(v.spacing()) + note("--spacing", v.file_spacing));
    line("origin", vec3(v.origin()) + note("--origin", v.file_origin));
    if (!v.dense) line("active voxels", std::to_string(v.grid->activeVoxelCount()));
  }
  line("inside", v.inside == Inside::Above ? "above the isovalue" : "below the isovalue");
  line("value range", fmt(s.min) + " .. " + fmt(s.max) + "  (mean " + fmt(s.mean) + ")");
  bool exact = false;
  const std::vector<double> p = percentiles(v, exact);
  line("percentiles", "1%: " + fmt(p[0]) + "  50%: " + fmt(p[1]) + "  99%: " + fmt(p[2]) +
                          (exact ? "" : "  (interpolated in the histogram)"));
  line("non-finite", std::to_string(s.nan_count) + " NaN, " + std::to_string(s.inf_count) + " Inf" +
                         (s.nan_count + s.inf_count ? " (replaced by the outside value)" : ""));
  line("suggested iso", fmt(s.suggested_isovalue) + " (" + s.suggested_from + ")");
  if (const std::size_t labels = label_map_hint(v))
    line("label map?", "looks like one: " + std::to_string(labels) +
                           " non-zero values over a background of 0; --labels makes one surface "
                           "per label (isocurv measure VOLUME --labels; docs/labels.md)");
  // The histogram as text: 16 bins over the range, bars on a log scale (CT and MR histograms are
  // dominated by the air), with the counts.
  const std::vector<std::uint64_t> coarse = coarse_histogram(s);
  std::uint64_t most = 0;
  for (std::uint64_t c : coarse) most = std::max(most, c);
  if (most > 0 && s.max > s.min) {
    line("histogram", "16 bins, bars on a log scale");
    const double width = (s.max - s.min) / 16;
    constexpr int kBar = 30;
    for (std::size_t i = 0; i < coarse.size(); ++i) {
      const int bar = coarse[i] == 0 ? 0
                      : std::max(1, int(std::lround(kBar * std::log1p(double(coarse[i])) / std::log1p(double(most)))));
      char edges[64];
      std::snprintf(edges, sizeof edges, "%10.4g .. %-10.4g", s.min + width * double(i), s.min + width * double(i + 1));
      out << "  " << edges << " " << std::string(std::size_t(bar), '#') << std::string(std::size_t(kBar - bar), ' ') << " "
          << coarse[i] << "\n";
    }
  }
  return out.str();
}

}  // namespace isocurv::volume
