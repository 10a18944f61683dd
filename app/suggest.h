#pragma once
// "Did you mean ...?" for mistyped option and command names: the closest of the names a command
// knows, by edit distance, or the one a typed name starts with (--isovalue for --iso).
// Tested in tests/app/test_usage.cpp.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace isocurv::app {

/// The candidate closest to `typed`: within an edit distance of 1 for names up to 4 letters, 2 up
/// to 8, 3 beyond (ties to the first), else the longest candidate of at least 3 letters that
/// `typed` starts with or that starts with `typed`; "" when none is close. Leading dashes count
/// as letters: pass both with them or both without.
std::string closest_name(const std::string& typed, const std::vector<std::string>& candidates);

/// For a parse error of `command` (nullptr: the top level) caused by arguments it does not know:
/// " (did you mean --color?)" for the first mistyped `--option` among argv[1..argc), else "".
std::string option_suggestion(const CLI::App* command, int argc, char** argv);

}  // namespace isocurv::app
