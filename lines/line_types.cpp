#include "lines/line_types.h"

#include <sstream>

#include "core/error.h"

namespace isocurv::lines {

std::string to_string(LineType t) {
  switch (t) {
  case LineType::contour:
    return "contours";
  case LineType::suggestive:
    return "suggestive";
  case LineType::ridge:
    return "ridges";
  case LineType::valley:
    return "valleys";
  }
  return "unknown";
}

bool LineSelection::has(LineType t) const {
  switch (t) {
  case LineType::contour:
    return contours;
  case LineType::suggestive:
    return suggestive;
  case LineType::ridge:
    return ridges;
  case LineType::valley:
    return valleys;
  }
  return false;
}

std::string LineSelection::to_string() const {
  std::string out;
  for (int i = 0; i < kLineTypeCount; ++i) {
    const auto t = LineType(i);
    if (!has(t))
      continue;
    if (!out.empty())
      out += ",";
    out += lines::to_string(t);
  }
  return out;
}

LineSelection parse_line_selection(const std::string &list) {
  LineSelection s;
  const std::string choices = "contours, suggestive, ridges, valleys or all";
  if (list.empty())
    throw Error("--lines: empty list (choose from " + choices + ")");
  std::stringstream in(list);
  std::string name;
  int count = 0;
  while (std::getline(in, name, ',')) {
    ++count;
    bool *flag = nullptr;
    if (name == "contours" || name == "contour")
      flag = &s.contours;
    else if (name == "suggestive")
      flag = &s.suggestive;
    else if (name == "ridges" || name == "ridge")
      flag = &s.ridges;
    else if (name == "valleys" || name == "valley")
      flag = &s.valleys;
    else if (name == "all") {
      s.contours = s.suggestive = s.ridges = s.valleys = true;
      continue;
    } else {
      throw Error("--lines: unknown line type '" + name + "' (choose from " +
                  choices + ")");
    }
    if (*flag)
      throw Error("--lines: '" + name + "' given twice");
    *flag = true;
  }
  if (count == 0 || list.back() == ',')
    throw Error("--lines: empty entry in '" + list + "'");
  return s;
}

} // namespace isocurv::lines
