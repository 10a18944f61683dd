#include "viz/explorer_script.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace isocurv::viz {
namespace {

/// `word` as a number (the whole of it), or false.
bool to_number(const std::string& word, double& v) {
  if (word.empty()) return false;
  char* end = nullptr;
  v = std::strtod(word.c_str(), &end);
  return *end == '\0' && std::isfinite(v);
}

/// `word` as an int (the whole of it), or false.
bool to_int(const std::string& word, int& v) {
  double d = 0;
  if (!to_number(word, d) || d != std::floor(d) || std::abs(d) > 1e9) return false;
  v = static_cast<int>(d);
  return true;
}

}  // namespace

std::vector<ExplorerAction> parse_explorer_script(const std::string& text, const std::string& origin) {
  std::vector<ExplorerAction> actions;
  std::istringstream in(text);
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const std::size_t end = line.find_first_of(" \t", start);
    const std::string verb = line.substr(start, end == std::string::npos ? end : end - start);
    std::string rest;
    if (end != std::string::npos) {
      const std::size_t r = line.find_first_not_of(" \t", end);
      if (r != std::string::npos) rest = line.substr(r);
    }
    std::istringstream words(rest);
    std::string w1, w2, w3;
    words >> w1 >> w2 >> w3;
    const auto bad = [&](const std::string& why) {
      return Error(origin, "line " + std::to_string(number) + " ('" + line.substr(start) + "'): " + why);
    };
    double v = 0;
    int a = 0, b = 0;
    if (verb == "screenshot" || verb == "status") {
      if (rest.empty()) throw bad(verb + " needs a path");
      actions.push_back(verb == "screenshot" ? ExplorerAction::screenshot(rest) : ExplorerAction::status(rest));
    } else if (verb == "iso") {
      if (!to_number(w1, v) || !w2.empty()) throw bad("iso needs one number");
      actions.push_back(ExplorerAction::set_isovalue(static_cast<float>(v)));
    } else if (verb == "frame") {
      if (!to_int(w1, a) || !w2.empty()) throw bad("frame needs one whole number");
      actions.push_back(ExplorerAction::set_frame(a));
    } else if (verb == "key") {
      char key = 0;
      if (w1 == "space") key = ' ';
      else if (w1 == "enter") key = '\r';
      else if (w1 == "escape") key = 27;
      else if (w1 == "backspace") key = 8;
      else if (w1.size() == 1) key = w1[0];
      else throw bad("key needs one character, or space, enter, escape, backspace");
      if (!w2.empty()) throw bad("key takes one key");
      actions.push_back(ExplorerAction::press(key));
    } else if (verb == "type") {
      if (rest.empty()) throw bad("type needs text");
      actions.push_back(ExplorerAction::type(rest));
    } else if (verb == "resize") {
      if (!to_int(w1, a) || !to_int(w2, b) || !w3.empty() || a < 64 || b < 64)
        throw bad("resize needs a width and a height of at least 64 pixels");
      actions.push_back(ExplorerAction::resize(a, b));
    } else if (verb == "wait") {
      if (!rest.empty()) throw bad("wait takes nothing");
      actions.push_back(ExplorerAction::wait());
    } else {
      throw bad("unknown action '" + verb +
                "' (screenshot, status, iso, frame, key, type, resize, wait)");
    }
  }
  return actions;
}

std::vector<ExplorerAction> read_explorer_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path, "cannot read the explorer script");
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<ExplorerAction> actions = parse_explorer_script(text.str(), path);
  if (actions.empty()) throw Error(path, "the explorer script has no action");
  return actions;
}

}  // namespace isocurv::viz
