#pragma once
// Writing output files safely: to a temporary name beside the target, then renamed over it.
#include <functional>
#include <string>

namespace isocurv {

/// Calls write(tmp_path) to produce the file under a temporary name in the same folder, then
/// renames it to `path`. If write throws (or the rename fails) the temporary is removed, the
/// exception propagates and any existing file at `path` is left untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

/// The temporary name write_atomically uses for `path` (same folder, same extension so that
/// writers choosing a format by extension still work).
std::string temporary_path_for(const std::string& path);

}  // namespace isocurv
