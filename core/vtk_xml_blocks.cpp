// Block-header checks for VTK XML files (core/vtk_xml_blocks.h).
#include "core/vtk_xml_blocks.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"

namespace isocurv::detail {
namespace {

/// The value of attribute `key` in the XML start tag `tag` ("" when absent).
std::string attribute(const std::string& tag, const std::string& key) {
  const std::string pattern = key + "=\"";
  for (std::size_t p = tag.find(pattern); p != std::string::npos; p = tag.find(pattern, p + 1)) {
    if (p == 0 || !std::isspace(static_cast<unsigned char>(tag[p - 1]))) continue;
    const std::size_t begin = p + pattern.size(), end = tag.find('"', begin);
    return tag.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  }
  return "";
}

/// Decodes base64 `text` (whitespace skipped, stopping at '=' or anything else) into bytes.
std::vector<unsigned char> base64_decode(const std::string& text) {
  std::vector<unsigned char> out;
  unsigned bits = 0;
  int n = 0;
  for (const char ch : text) {
    int v;
    if (ch >= 'A' && ch <= 'Z')
      v = ch - 'A';
    else if (ch >= 'a' && ch <= 'z')
      v = ch - 'a' + 26;
    else if (ch >= '0' && ch <= '9')
      v = ch - '0' + 52;
    else if (ch == '+')
      v = 62;
    else if (ch == '/')
      v = 63;
    else if (std::isspace(static_cast<unsigned char>(ch)))
      continue;
    else
      break;
    bits = (bits << 6) | unsigned(v);
    if ((n += 6) >= 8) {
      n -= 8;
      out.push_back(static_cast<unsigned char>((bits >> n) & 0xffu));
    }
  }
  return out;
}

}  // namespace

void check_vtk_xml_compressed_blocks(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = static_cast<unsigned long long>(std::filesystem::file_size(path, ec));
  if (!in || ec) return;  // VTK reports it
  // The XML text: everything before the appended data's '_' (or the whole file without it).
  std::string text;
  std::size_t appended = std::string::npos, tag = std::string::npos;
  for (std::string chunk(1 << 20, '\0'); in;) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const std::size_t from = text.size() > 16 ? text.size() - 16 : 0;
    text.append(chunk.data(), std::size_t(in.gcount()));
    if (tag == std::string::npos) tag = text.find("<AppendedData", from);
    if (tag == std::string::npos) continue;
    // VTK takes the first character after the tag and its whitespace as the '_' marker, whatever
    // it is, and reads the data from the next byte: anything else there shifts every header.
    const std::size_t close = text.find('>', tag);
    std::size_t mark = close == std::string::npos ? close : close + 1;
    while (mark < text.size() && std::isspace(static_cast<unsigned char>(text[mark]))) ++mark;
    if (mark >= text.size()) {
      if (in) continue;
      break;
    }
    if (text[mark] != '_')
      throw Error(path, "appended data does not begin with '_' (found byte " +
                            std::to_string(static_cast<unsigned char>(text[mark])) + ")");
    appended = mark + 1;
    text.resize(appended);
    break;
  }
  in.clear();
  const std::size_t root = text.find("<VTKFile");
  if (root == std::string::npos) return;
  const std::string root_tag = text.substr(root, text.find('>', root) - root);
  if (attribute(root_tag, "compressor").empty()) return;
  const int word = attribute(root_tag, "header_type") == "UInt64" ? 8 : 4;
  const bool big = attribute(root_tag, "byte_order") == "BigEndian";
  const std::size_t app_tag = text.find("<AppendedData");
  const bool appended_base64 =
      app_tag != std::string::npos &&
      attribute(text.substr(app_tag, text.find('>', app_tag) - app_tag), "encoding") != "raw";
  // `n` header bytes from file offset `pos`, decoded from base64 when `base64`; fewer at the end.
  auto header_bytes = [&](unsigned long long pos, std::size_t n, bool base64) {
    std::vector<unsigned char> bytes;
    if (pos >= size) return bytes;
    std::string raw(base64 ? (n + 2) / 3 * 4 : n, '\0');
    if (base64) {  // skip the whitespace before inline data
      in.seekg(std::streamoff(pos));
      char c;
      while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) ++pos;
    }
    in.clear();
    in.seekg(std::streamoff(pos));
    in.read(raw.data(), std::streamsize(raw.size()));
    raw.resize(std::size_t(in.gcount()));
    in.clear();
    if (!base64) return std::vector<unsigned char>(raw.begin(), raw.end());
    bytes = base64_decode(raw);
    if (bytes.size() > n) bytes.resize(n);
    return bytes;
  };
  auto word_at = [&](const std::vector<unsigned char>& b, std::size_t i) {
    unsigned long long v = 0;
    for (int k = 0; k < word; ++k) {
      const unsigned char byte = b[i * word + std::size_t(big ? k : word - 1 - k)];
      v = (v << 8) | byte;
    }
    return v;
  };
  for (std::size_t p = text.find("<DataArray"); p != std::string::npos;
       p = text.find("<DataArray", p + 1)) {
    const std::size_t end = text.find('>', p);
    if (end == std::string::npos) break;
    const std::string tag = text.substr(p, end - p);
    const std::string format = attribute(tag, "format");
    unsigned long long pos;
    bool base64 = true;
    if (format == "appended") {
      if (appended == std::string::npos) continue;
      const unsigned long long offset =
          std::strtoull(attribute(tag, "offset").c_str(), nullptr, 10);
      if (offset >= size) continue;  // VTK reports it
      pos = appended + offset;
      base64 = appended_base64;
    } else if (format == "binary") {
      pos = end + 1;
    } else {
      continue;  // ascii: values parsed one by one
    }
    const std::vector<unsigned char> first = header_bytes(pos, std::size_t(3 * word), base64);
    if (first.size() < std::size_t(3 * word)) continue;  // VTK reports the short header
    const unsigned long long blocks = word_at(first, 0), block = word_at(first, 1),
                             last = word_at(first, 2);
    auto refuse = [&](const std::string& what) {
      throw Error(path, "compressed array '" + attribute(tag, "Name") + "' " + what +
                            " but the file holds " + std::to_string(size) + " bytes");
    };
    // VTK allocates a block's buffer even when there are no blocks (found by the VTP fuzzer).
    const long double most = (long double)size * 1040 + 1024;
    if ((long double)block > most || (long double)last > most)
      refuse("claims blocks of " + std::to_string(std::max(block, last)) + " bytes");
    if (blocks == 0) continue;
    if (blocks > size / unsigned(word))
      refuse("claims " + std::to_string(blocks) + " blocks (a " + std::to_string(blocks * word) +
             "-byte header)");
    if (block == 0)  // VTK divides by it (a floating-point exception, found by the VTP fuzzer)
      throw Error(path,
                  "compressed array '" + attribute(tag, "Name") + "' claims a block size of 0");
    const std::vector<unsigned char> all =
        header_bytes(pos, std::size_t((3 + blocks) * word), base64);
    if (all.size() < std::size_t((3 + blocks) * word)) continue;
    long double compressed = 0;
    for (unsigned long long i = 0; i < blocks; ++i) {
      const unsigned long long c = word_at(all, std::size_t(3 + i));
      const unsigned long long u = i + 1 == blocks && last != 0 ? last : block;
      compressed += (long double)c;
      if ((long double)u > (long double)c * 1040 + 1024 || compressed > (long double)size)
        refuse("claims a block of " + std::to_string(u) + " bytes from " + std::to_string(c) +
               " compressed");
    }
  }
}

}  // namespace isocurv::detail
