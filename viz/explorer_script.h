#pragma once
// Explorer scripts as text, one action a line, for scripted runs of `isocurv view --script` (demos,
// headless pictures and the end-to-end tests): the same ExplorerActions a test builds in code.
// Tested in tests/viz/test_explorer_view.cpp.
#include <string>
#include <vector>

#include "viz/explorer.h"

namespace isocurv::viz {

/// Parses a script, one action a line (blank lines and lines starting with # are skipped):
///   screenshot PATH   a PNG of the window            status PATH   the status line's text
///   iso V             moves the isovalue slider      frame K       moves the time slider
///   key C             presses the key C (one character, or space, enter, escape, backspace)
///   type TEXT         types TEXT, one key each      resize W H    resizes the window
///   wait              one tick (~100 ms) doing nothing (a series plays meanwhile)
/// PATH and TEXT are the rest of the line. @throw Error naming `origin` and the line.
std::vector<ExplorerAction> parse_explorer_script(const std::string& text,
                                                  const std::string& origin = "script");

/// Reads the file `path` and parses it (parse_explorer_script). @throw Error naming the file.
std::vector<ExplorerAction> read_explorer_script(const std::string& path);

}  // namespace isocurv::viz
