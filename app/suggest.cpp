// Suggestions for mistyped names (see suggest.h).
#include "app/suggest.h"

#include <algorithm>
#include <cstddef>

namespace isocurv::app {
namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string strip_dashes(const std::string& s) {
  return s.substr(std::min(s.find_first_not_of('-'), s.size()));
}

}  // namespace

std::string closest_name(const std::string& typed, const std::vector<std::string>& candidates) {
  const std::string t = strip_dashes(typed);
  if (t.empty()) return "";
  const std::size_t allowed = t.size() <= 4 ? 1 : t.size() <= 8 ? 2 : 3;
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(t, strip_dashes(c));
    if (d < best_distance) best = c, best_distance = d;
  }
  if (!best.empty()) return best;
  for (const std::string& c : candidates) {
    const std::string n = strip_dashes(c);
    if (n.size() < 3) continue;
    const bool prefix = t.rfind(n, 0) == 0 || n.rfind(t, 0) == 0;
    if (prefix && n.size() > strip_dashes(best).size()) best = c;
  }
  return best;
}

std::string option_suggestion(const CLI::App* command, int argc, char** argv) {
  if (!command) return "";
  std::vector<std::string> names;
  for (const CLI::Option* opt : command->get_options())
    for (const std::string& n : opt->get_lnames()) names.push_back("--" + n);
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0 || arg.size() < 3) continue;
    arg = arg.substr(0, arg.find('='));
    if (std::find(names.begin(), names.end(), arg) != names.end()) continue;
    const std::string best = closest_name(arg, names);
    if (!best.empty()) return " (did you mean " + best + "?)";
  }
  return "";
}

}  // namespace isocurv::app
