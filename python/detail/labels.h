#pragma once
// The label-map arguments the Python module's measure_labels, extract_labels and curvature_labels
// share: labels= (which labels), the labels picked from the map with the command line's notes as
// UserWarnings, and the extraction each label's indicator gets on the chosen device
// (labels::LabelSurfaceSteps, labels/label_surfaces.h).
#include <cstdint>
#include <vector>

#include "labels/label_map.h"
#include "labels/label_surfaces.h"
#include "python/detail/args.h"

namespace isocurv::python {

/// labels= : None (every label: an empty list), an int, or a sequence of ints (Python or numpy
/// integers: anything with __index__, not bools), distinct, within +-labels::kMaxLabelValue.
/// TypeError or ValueError naming `labels` otherwise (an empty sequence too).
std::vector<std::int64_t> label_values_of(const py::object& labels);

/// The labels of the label map `v` that `labels` names (label_values_of; all of them for None), in
/// its order. Those `v` lacks are named in one UserWarning (labels::missing_labels_note).
/// @throw isocurv::Error from labels::label_map_labels (a float volume, too many labels);
///        ValueError when `v` holds no label, or none of those named.
std::vector<labels::Label> picked_labels_of(const volume::Volume& v, const py::object& labels);

/// The extraction of an indicator for labels::LabelSurfaceSteps::extract on the device `dc`, as
/// isocurv.extract(indicator, 0.5) makes it (cap off, the default snap): the GIL released and the
/// device lock held while it runs. Call the result with the GIL held.
std::function<Mesh(const volume::Volume&, float)> label_extraction(const DeviceChoice& dc);

/// The UserWarning for labels whose surface is empty (labels::filling_labels_note), when there
/// are any, as the command line's warning line.
void warn_filling_labels(const std::vector<std::int64_t>& empty);

}  // namespace isocurv::python
