#pragma once
// Label maps: integer volumes where each value is an object (segmentations from 3D Slicer,
// TotalSegmentator, ITK-SNAP). Each label becomes its own surface, extracted at the half level of
// its indicator (1 on the label's voxels, 0 elsewhere), so touching labels each get a closed
// surface of their own.
// Tested in tests/labels/test_label_map.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include "volume/volume.h"

namespace isocurv::labels {

/// The most labels a label map may hold (the distinct non-zero values), as uint16 segmentations.
inline constexpr std::size_t kMaxLabels = 65535;

/// The largest label value (in magnitude): volumes hold their voxels as 32-bit floats, whose
/// integers are exact up to 2^24. One less than that, because a file's 2^24 + 1 arrives rounded
/// to 2^24 and must not pass as it (and merge with a true 2^24): every integer beyond this one
/// reads as a float of magnitude 2^24 or more, and is refused.
inline constexpr std::int64_t kMaxLabelValue = 16777215;

/// One label of a label map: its value, how many voxels hold it, and their box (index space,
/// inclusive).
struct Label {
  std::int64_t value = 0;
  std::uint64_t voxels = 0;
  openvdb::CoordBBox box;
};

/// The labels of `v`: every distinct non-zero value of its data domain, ascending, with its voxel
/// count and box. One pass over the domain (OpenVDB's value iterator; tiles count as their voxels).
/// Label 0 is the background.
/// @throw Error naming v.path when the volume is not an integer one (its voxel_type is float,
///        double or half: labels must be exact), when a value is not an integer (a NIfTI
///        scl_slope/scl_inter scaling), when it holds more than kMaxLabels labels, or a value
///        beyond kMaxLabelValue.
std::vector<Label> label_map_labels(const volume::Volume& v);

/// Parses a --label list ("3,7" or "3, 7"): distinct integers. @throw Error for anything else.
std::vector<std::int64_t> parse_label_list(const std::string& text);

/// The notes the command line and the Python module give, without a prefix: "no voxel holds
/// label(s) 3, 9; left out" (asked for, absent) and "label 5 has no surface (it fills the box);
/// left out" (or "labels 5, 6 have ... they fill ..."). `labels` is not empty.
std::string missing_labels_note(const std::vector<std::int64_t>& labels);
std::string filling_labels_note(const std::vector<std::int64_t>& labels);

/// The labels of `all` named in `wanted` (all of them when `wanted` is empty), in `wanted`'s order.
/// Values in `wanted` that `all` lacks are appended to `missing` (the caller warns about them).
std::vector<Label> pick_labels(const std::vector<Label>& all, const std::vector<std::int64_t>& wanted,
                               std::vector<std::int64_t>& missing);

/// The margin label_indicator needs for a volume-estimator scale of `scale_voxels` (the largest
/// deviation, in voxels): one marching-cubes cell beyond the label plus 4 deviations, so that the
/// bricks the estimator gathers lie in the indicator's domain (capped at 64 deviations).
int indicator_margin(double scale_voxels);

/// The indicator volume of `label` in `v`: 1 on its voxels, 0 elsewhere, as a "uint8" volume whose
/// domain is the label's box grown by `margin` voxels on every side, clipped to v's domain, in
/// v's index space and transform (so world positions agree). Outside that domain the grid's
/// background, 0, is the indicator's true value there. Its isosurface at 0.5 is the label's
/// surface: closed, unless the label reaches the side of v's domain. A binary volume
/// (curvature::is_binary) when the grown box holds voxels of both kinds.
/// @param margin  at least 1 (a marching-cubes cell beyond the label's last voxel).
volume::Volume label_indicator(const volume::Volume& v, const Label& label, int margin = 2);

/// The indicator of the union of `labels` (at least one) in `v`, as label_indicator makes it for
/// one: 1 on the voxels of any of them, 0 elsewhere, on the box around all of theirs grown by
/// `margin`. Its isosurface at 0.5 is the outside of the labels together, without the walls
/// between touching labels: what a picture of all of them shows (screen --labels).
volume::Volume labels_indicator(const volume::Volume& v, const std::vector<Label>& labels,
                                int margin = 2);

}  // namespace isocurv::labels
