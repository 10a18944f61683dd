// Zarr stores and OME-NGFF multiscale images (zarr.h): one level, time point and channel read
// into memory. The metadata is parsed in detail/zarr_metadata.cpp, the chunks decoded in
// detail/zarr_chunks.cpp.
#include "volume/zarr.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/detail/zarr_chunks.h"
#include "volume/detail/zarr_metadata.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

using zarr_detail::Codec;

ZarrInfo zarr_info_of(const zarr_detail::Store& s) {
  ZarrInfo info;
  info.path = s.path;
  info.zarr_format = s.zarr_format;
  info.ome_version = s.ome_version;
  info.axes = s.axis_names;
  info.axis_units = s.axis_units;
  info.length_unit = s.length_unit;
  info.budget = zarr_memory_budget();
  const zarr_detail::ArrayMeta& first = s.levels.front().meta;
  info.voxel_type = voxel_type_name(first.type);
  info.codecs = zarr_detail::codecs_text(first.codecs);
  info.fill_value = first.fill;
  if (voxel_size(first.type) > 1) {
    std::vector<Codec> list = first.codecs;
    while (!list.empty()) {
      const Codec* ab = nullptr;
      for (const Codec& c : list)
        if (c.kind == Codec::Kind::Bytes || c.kind == Codec::Kind::Sharding) ab = &c;
      if (!ab) break;
      if (ab->kind == Codec::Kind::Bytes) {
        info.byte_order = ab->big_endian ? "big" : "little";
        break;
      }
      std::vector<Codec> inner = ab->inner;  // not assigned from an element of `list` itself
      list = std::move(inner);
    }
  }
  for (const zarr_detail::Level& l : s.levels) {
    ZarrLevelInfo li;
    li.path = l.name;
    li.shape = l.meta.shape;
    li.chunks = l.meta.chunks;
    for (const Codec& c : l.meta.codecs)
      if (c.kind == Codec::Kind::Sharding) li.inner_chunks = c.inner_chunks;
    for (std::size_t i = 0; i < 3; ++i) {
      const std::size_t d = std::size_t(s.spatial[i]);
      li.dims[i] = l.meta.shape[d];
      li.spacing[i] = l.scale[d];
      li.origin[i] = l.translation[d];
    }
    const long double bytes = (long double)li.dims[0] * li.dims[1] * li.dims[2] * zarr_bytes_per_voxel;
    li.bytes = bytes > 1.8e19L ? ~std::uint64_t(0) : std::uint64_t(bytes);
    li.fits = li.bytes <= info.budget;
    if (li.fits && info.default_level < 0) info.default_level = int(info.levels.size());
    info.levels.push_back(li);
  }
  return info;
}

std::string zarr_fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string zarr_shape_text(const std::vector<long long>& s) {
  std::string t;
  for (std::size_t i = 0; i < s.size(); ++i) t += (i ? "x" : "") + std::to_string(s[i]);
  return t;
}

std::string zarr_level_text(const ZarrInfo& info, int level) {
  const ZarrLevelInfo& l = info.levels[std::size_t(level)];
  return "level " + std::to_string(level) + " (\"" + l.path + "\": " + std::to_string(l.dims[0]) + " x " +
         std::to_string(l.dims[1]) + " x " + std::to_string(l.dims[2]) + ", " + bytes_text((long double)l.bytes) +
         " in memory)";
}

/// The index along each non-spatial axis: options.time_point for a time axis, options.channel for
/// a channel axis, 0 for any other; throws when an index is outside its axis or an option names
/// an axis the store lacks.
std::vector<long long> zarr_fixed_indices(const zarr_detail::Store& s, const zarr_detail::Level& l,
                                          const LoadOptions& o) {
  const std::size_t n = l.meta.shape.size();
  std::vector<long long> fixed(n, -1);
  bool has_time = false, has_channel = false;
  for (std::size_t d = 0; d < n; ++d) {
    if (d == std::size_t(s.spatial[0]) || d == std::size_t(s.spatial[1]) || d == std::size_t(s.spatial[2])) continue;
    const std::string& type = s.axis_types[d];
    long long want = 0;
    const char* option = nullptr;
    if (type == "time" && !has_time) {
      has_time = true;
      want = o.time_point.value_or(0);
      option = "--time-point";
    } else if (type == "channel" && !has_channel) {
      has_channel = true;
      want = o.channel.value_or(0);
      option = "--channel";
    }
    if (want < 0 || want >= l.meta.shape[d]) {
      throw Error(s.path, std::string(option ? option : "axis") + " " + std::to_string(want) + " is outside axis '" +
                              s.axis_names[d] + "' (0 to " + std::to_string(l.meta.shape[d] - 1) + ")");
    }
    fixed[d] = want;
  }
  if (o.time_point && !has_time) throw Error(s.path, "--time-point: the store has no time axis");
  if (o.channel && !has_channel) throw Error(s.path, "--channel: the store has no channel axis");
  return fixed;
}

}  // namespace

bool is_zarr_store(const std::string& path) { return zarr_detail::looks_like_zarr(path); }

std::uint64_t zarr_memory_budget() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(4) << 30;
  return std::uint64_t(pages) * std::uint64_t(page) / 2;
}

ZarrInfo describe_zarr(const std::string& path) { return zarr_info_of(zarr_detail::read_store(path)); }

int choose_zarr_level(const ZarrInfo& info, const LoadOptions& options) {
  const std::string budget = bytes_text((long double)info.budget) + " (half the physical memory)";
  if (options.level) {
    const int n = int(info.levels.size());
    if (*options.level < 0 || *options.level >= n)
      throw Error(info.path, "--level " + std::to_string(*options.level) + ": the store has " + std::to_string(n) +
                                 (n == 1 ? " level (0)" : " levels (0 to " + std::to_string(n - 1) + ")"));
    if (!info.levels[std::size_t(*options.level)].fits)
      throw Error(info.path, zarr_level_text(info, *options.level) + " exceeds the memory budget of " + budget +
                                 "; choose a coarser --level (streaming larger volumes is not built yet)");
    return *options.level;
  }
  if (info.default_level < 0)
    throw Error(info.path, "every level exceeds the memory budget of " + budget + "; the coarsest is " +
                               zarr_level_text(info, int(info.levels.size()) - 1) +
                               " (streaming larger volumes is not built yet)");
  return info.default_level;
}

Volume load_zarr(const std::string& path, const LoadOptions& options) {
  const zarr_detail::Store s = zarr_detail::read_store(path);
  const ZarrInfo info = zarr_info_of(s);
  const int level = choose_zarr_level(info, options);
  const zarr_detail::Level& l = s.levels[std::size_t(level)];
  const ZarrLevelInfo& li = info.levels[std::size_t(level)];
  const std::uint64_t count = checked_voxel_count(l.meta.meta_path, li.dims);
  const std::vector<long long> fixed = zarr_fixed_indices(s, l, options);

  zarr_detail::Region region;
  const std::size_t n = l.meta.shape.size();
  region.lo.assign(n, 0);
  region.hi = l.meta.shape;
  region.out_stride.assign(n, 0);
  for (std::size_t d = 0; d < n; ++d)
    if (fixed[d] >= 0) region.lo[d] = fixed[d], region.hi[d] = fixed[d] + 1;
  region.out_stride[std::size_t(s.spatial[0])] = 1;
  region.out_stride[std::size_t(s.spatial[1])] = li.dims[0];
  region.out_stride[std::size_t(s.spatial[2])] = li.dims[0] * li.dims[1];

  DenseImage image;
  image.dims = {int(li.dims[0]), int(li.dims[1]), int(li.dims[2])};
  image.values = LargeBuffer<float>(std::size_t(count));
  zarr_detail::read_region(l.meta, region, image.values.data(), image.values.size());
  image.spacing = li.spacing;
  image.origin = li.origin;
  image.voxel_type = voxel_type_name(l.meta.type);
  image.array_name = li.path;
  Volume v = finish_dense(std::move(image), path, "zarr", options);
  v.length_unit = s.length_unit;
  return v;
}

nlohmann::json zarr_summary_json(const ZarrInfo& info, int level_read) {
  nlohmann::json j;
  j["zarr_format"] = info.zarr_format;
  j["ome_version"] = info.ome_version;
  j["axes"] = info.axes;
  j["axis_units"] = info.axis_units;
  j["length_unit"] = info.length_unit;
  j["dtype"] = info.voxel_type;
  j["byte_order"] = info.byte_order;
  j["codecs"] = info.codecs;
  if (std::isfinite(info.fill_value))
    j["fill_value"] = info.fill_value;
  else
    j["fill_value"] = std::isnan(info.fill_value) ? "NaN" : info.fill_value > 0 ? "Infinity" : "-Infinity";
  j["memory_budget_bytes"] = info.budget;
  j["default_level"] = info.default_level;
  j["level_read"] = level_read;
  j["levels"] = nlohmann::json::array();
  for (const ZarrLevelInfo& l : info.levels) {
    nlohmann::json e;
    e["path"] = l.path;
    e["shape"] = l.shape;
    e["chunks"] = l.chunks;
    if (!l.inner_chunks.empty()) e["inner_chunks"] = l.inner_chunks;
    e["dimensions"] = l.dims;
    e["spacing"] = l.spacing;
    e["origin"] = l.origin;
    e["bytes_in_memory"] = l.bytes;
    e["fits_budget"] = l.fits;
    j["levels"].push_back(e);
  }
  return j;
}

std::string zarr_summary_text(const ZarrInfo& info, int level_read) {
  std::ostringstream out;
  auto line = [&out](const std::string& key, const std::string& value) {
    out << key << std::string(key.size() < 18 ? 18 - key.size() : 1, ' ') << value << "\n";
  };
  line("zarr", "v" + std::to_string(info.zarr_format) +
                   (info.ome_version.empty() ? " array (no OME-NGFF metadata)" : ", OME-NGFF " + info.ome_version));
  std::string axes;
  for (std::size_t i = 0; i < info.axes.size(); ++i)
    axes += (i ? " " : "") + info.axes[i] + (info.axis_units[i].empty() ? "" : " (" + info.axis_units[i] + ")");
  line("axes", axes);
  line("dtype", info.voxel_type + (info.byte_order.empty() ? "" : " (" + info.byte_order + "-endian)"));
  line("codecs", info.codecs.empty() ? "none" : info.codecs);
  line("fill value", zarr_fmt(info.fill_value));
  line("levels", std::to_string(info.levels.size()) + " (memory budget " + bytes_text((long double)info.budget) +
                     ", half the physical memory; --level N picks one)");
  for (std::size_t i = 0; i < info.levels.size(); ++i) {
    const ZarrLevelInfo& l = info.levels[i];
    std::string t = "  " + std::to_string(i) + " \"" + l.path + "\"  shape " + zarr_shape_text(l.shape) + "  chunks " +
                    zarr_shape_text(l.chunks) + (l.inner_chunks.empty() ? "" : " (inner " + zarr_shape_text(l.inner_chunks) + ")") +
                    "  spacing " + zarr_fmt(l.spacing[0]) + " " + zarr_fmt(l.spacing[1]) + " " + zarr_fmt(l.spacing[2]) +
                    "  origin " + zarr_fmt(l.origin[0]) + " " + zarr_fmt(l.origin[1]) + " " + zarr_fmt(l.origin[2]);
    if (int(i) == level_read) t += "  <- read";
    if (!l.fits) t += "  (over the budget)";
    out << t << "\n";
  }
  return out.str();
}

}  // namespace isocurv::volume
