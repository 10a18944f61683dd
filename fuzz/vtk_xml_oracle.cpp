#include "fuzz/vtk_xml_oracle.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace isocurv::fuzz {
namespace {

using ull = unsigned long long;

/// The value of `key="..."` in `tag` (preceded by whitespace), "" when absent.
std::string attribute_in(const std::string& tag, const std::string& key) {
  const std::string pattern = key + "=\"";
  for (std::size_t p = tag.find(pattern); p != std::string::npos; p = tag.find(pattern, p + 1)) {
    if (p == 0 || !std::isspace(static_cast<unsigned char>(tag[p - 1]))) continue;
    const std::size_t b = p + pattern.size(), e = tag.find('"', b);
    if (e == std::string::npos) return "";
    return tag.substr(b, e - b);
  }
  return "";
}

}  // namespace

unsigned type_bytes(const std::string& t) {
  if (t == "Int8" || t == "UInt8") return 1;
  if (t == "Int16" || t == "UInt16") return 2;
  if (t == "Int32" || t == "UInt32" || t == "Float32") return 4;
  if (t == "Int64" || t == "UInt64" || t == "Float64") return 8;
  return 0;
}

std::string xml_attribute(const std::string& file, const std::string& element, const std::string& key) {
  const std::size_t p = file.find("<" + element + " ");
  if (p == std::string::npos) return "";
  const std::size_t e = file.find('>', p);
  return attribute_in(file.substr(p, e == std::string::npos ? std::string::npos : e - p), key);
}

std::vector<RawArray> raw_appended_arrays(const std::string& file, bool& applies, std::string& problem) {
  applies = false;
  problem.clear();
  std::vector<RawArray> arrays;
  const std::size_t tag = file.find("<AppendedData");
  if (tag == std::string::npos) return arrays;
  const std::size_t tag_end = file.find('>', tag);
  if (tag_end == std::string::npos) return arrays;
  std::size_t marker = tag_end + 1;
  while (marker < file.size() && std::isspace(static_cast<unsigned char>(file[marker]))) ++marker;
  if (marker >= file.size() || file[marker] != '_') return arrays;
  const std::string xml = file.substr(0, marker);
  if (attribute_in(file.substr(tag, tag_end - tag), "encoding") != "raw") return arrays;
  if (xml.find("<!--") != std::string::npos || xml.find("<!") != std::string::npos ||
      xml.find('&') != std::string::npos || xml.find('\'') != std::string::npos)
    return arrays;
  for (std::size_t e = xml.find('='); e != std::string::npos; e = xml.find('=', e + 1))  // key="value" only
    if ((e > 0 && std::isspace(static_cast<unsigned char>(xml[e - 1]))) ||
        (e + 1 < xml.size() && xml[e + 1] != '"'))
      return arrays;
  const std::size_t root = xml.find("<VTKFile ");
  if (root == std::string::npos) return arrays;
  const std::string root_tag = xml.substr(root, xml.find('>', root) - root);
  if (root_tag.find("compressor") != std::string::npos) return arrays;
  const std::string order = attribute_in(root_tag, "byte_order"), header = attribute_in(root_tag, "header_type");
  if (order != "LittleEndian" && order != "BigEndian") return arrays;
  const int word = header == "UInt64" ? 8 : header.empty() || header == "UInt32" ? 4 : 0;
  if (word == 0) return arrays;
  std::size_t pieces = 0;
  for (std::size_t p = xml.find("<Piece"); p != std::string::npos; p = xml.find("<Piece", p + 1)) ++pieces;
  if (pieces != 1) return arrays;

  // Every DataArray, with its offset and the element it sits in.
  std::vector<std::pair<ull, RawArray>> found;
  std::string section;
  for (std::size_t p = xml.find('<'); p != std::string::npos; p = xml.find('<', p + 1)) {
    const std::size_t e = xml.find('>', p);
    if (e == std::string::npos) break;
    const std::string t = xml.substr(p, e - p);
    const std::size_t name_end = std::min(t.find_first_of(" \t\r\n/"), t.size());
    const std::string name = t.substr(1, name_end - 1);
    if (name != "DataArray" && name != "Array") {
      if (!name.empty() && name[0] != '/' && name[0] != '?' && t.back() != '/') section = name;
      continue;
    }
    if (attribute_in(t, "format") != "appended") return arrays;  // not the simple layout
    const std::string offset = attribute_in(t, "offset");
    if (offset.empty() || !std::all_of(offset.begin(), offset.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) ||
        offset.size() > 15)
      return arrays;
    RawArray a;
    a.name = attribute_in(t, "Name");
    a.type = attribute_in(t, "type");
    a.section = section;
    found.emplace_back(std::strtoull(offset.c_str(), nullptr, 10), a);
  }
  if (found.empty()) return arrays;
  applies = true;
  const std::size_t close = file.rfind("</AppendedData>");
  const ull start = marker + 1, end = close == std::string::npos || close < start ? file.size() : close;
  std::vector<ull> offsets;
  for (const auto& f : found) offsets.push_back(f.first);
  std::sort(offsets.begin(), offsets.end());
  offsets.erase(std::unique(offsets.begin(), offsets.end()), offsets.end());
  auto count_at = [&](ull pos, bool& ok) {
    ull v = 0;
    ok = pos + ull(word) <= end;
    for (int k = 0; ok && k < word; ++k)
      v = (v << 8) | static_cast<unsigned char>(file[std::size_t(pos) + std::size_t(order == "BigEndian" ? k : word - 1 - k)]);
    return v;
  };
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    bool ok = false;
    const ull bytes = count_at(start + offsets[i], ok);
    if (!ok) {
      problem = "an array header at offset " + std::to_string(offsets[i]) + " lies outside the appended data";
      break;
    }
    for (auto& f : found)
      if (f.first == offsets[i]) f.second.bytes = bytes;
    const ull next = i + 1 < offsets.size() ? start + offsets[i + 1] : end;
    if (bytes > end || start + offsets[i] + ull(word) + bytes > next) {
      problem = "the array at offset " + std::to_string(offsets[i]) + " claims " + std::to_string(bytes) +
                " bytes, more than lie before the next array or the end of the appended data";
      break;
    }
    const ull stop = start + offsets[i] + ull(word) + bytes;
    if (i + 1 < offsets.size() ? stop != next
                               : !std::all_of(file.begin() + long(stop), file.begin() + long(end),
                                              [](char c) { return std::isspace(static_cast<unsigned char>(c)); })) {
      problem = "the array at offset " + std::to_string(offsets[i]) + " ends at " + std::to_string(stop - start) +
                ", short of the next array or the end of the appended data";
      break;
    }
  }
  for (auto& f : found) arrays.push_back(f.second);
  return arrays;
}

}  // namespace isocurv::fuzz
