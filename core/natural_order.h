#pragma once
// Natural ("human") order of names: runs of digits compare as numbers, so frame_2 sorts before
// frame_10. Used to order the frames of a series (file names, .vdb grid names).
// Tested in tests/series/test_natural_order.cpp.
#include <string>
#include <vector>

namespace isocurv {

/// True when `a` comes before `b` in natural order: the strings are compared in chunks, a run of
/// ASCII digits against a run of digits by numeric value (any length: leading zeros are skipped,
/// then the longer run is larger, then digit by digit), everything else byte by byte. Equal
/// numeric values with different zero padding ("7" and "007") fall back to the plain byte order,
/// so the order is strict and total (two different strings are never equivalent).
bool natural_less(const std::string& a, const std::string& b);

/// Sorts `names` in natural order (natural_less); stable, in place.
void natural_sort(std::vector<std::string>& names);

}  // namespace isocurv
