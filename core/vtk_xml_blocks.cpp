// Structure checks for VTK XML files (core/vtk_xml_blocks.h).
#include "core/vtk_xml_blocks.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace isocurv::detail {
namespace {

using ull = unsigned long long;
constexpr std::size_t npos = std::string::npos;

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

/// An XML tag as expat reads it: `<name key="value" key='value' ...>` (or `/>`, or `</name>`).
struct Tag {
  std::string name;  ///< empty for comments, declarations and processing instructions
  bool closing = false, empty = false;
  std::size_t end = 0;  ///< index just past the '>'
  std::vector<std::pair<std::string, std::string>> attributes;
  const std::string* get(const std::string& key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
  std::string value(const std::string& key) const {
    const std::string* v = get(key);
    return v ? *v : std::string();
  }
};

/// Parses the tag at text[lt] == '<'; false when the text ends inside it.
/// @throw Error for a tag expat would refuse too (an attribute without '=' or quotes)
bool parse_tag(const std::string& path, const std::string& text, std::size_t lt, Tag& t) {
  t = Tag{};
  const std::size_t n = text.size();
  if (text.compare(lt, 4, "<!--") == 0) {
    const std::size_t e = text.find("-->", lt + 4);
    if (e == npos) return false;
    t.end = e + 3;
    return true;
  }
  if (lt + 1 < n && (text[lt + 1] == '?' || text[lt + 1] == '!')) {
    const std::size_t e = text.find('>', lt);
    if (e == npos) return false;
    t.end = e + 1;
    return true;
  }
  std::size_t p = lt + 1;
  if (p < n && text[p] == '/') {
    t.closing = true;
    ++p;
  }
  const std::size_t b = p;
  while (p < n && !is_space(text[p]) && text[p] != '>' && text[p] != '/') ++p;
  t.name = text.substr(b, p - b);
  auto malformed = [&] { return Error(path, "malformed XML tag <" + t.name.substr(0, 40) + ">"); };
  for (;;) {
    while (p < n && is_space(text[p])) ++p;
    if (p >= n) return false;
    if (text[p] == '>') {
      t.end = p + 1;
      return true;
    }
    if (text[p] == '/') {
      if (p + 1 >= n) return false;
      if (text[p + 1] != '>') throw malformed();
      t.empty = true;
      t.end = p + 2;
      return true;
    }
    const std::size_t kb = p;
    while (p < n && !is_space(text[p]) && text[p] != '=' && text[p] != '>' && text[p] != '/') ++p;
    const std::string key = text.substr(kb, p - kb);
    while (p < n && is_space(text[p])) ++p;
    if (p >= n) return false;
    if (key.empty() || text[p] != '=') throw malformed();
    ++p;
    while (p < n && is_space(text[p])) ++p;
    if (p >= n) return false;
    const char quote = text[p];
    if (quote != '"' && quote != '\'') throw malformed();
    const std::size_t ve = text.find(quote, p + 1);
    if (ve == npos) return false;
    t.attributes.emplace_back(key, text.substr(p + 1, ve - p - 1));
    p = ve + 1;
  }
}

/// Exactly `n` whitespace-separated integers in [-2^31+2, 2^31-2], else nullopt.
std::optional<std::vector<long long>> integers(const std::string& s, std::size_t n) {
  std::vector<long long> out;
  const char* p = s.c_str();
  for (;;) {
    while (*p && is_space(*p)) ++p;
    if (!*p) break;
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(p, &end, 10);
    if (end == p || (*end && !is_space(*end)) || errno == ERANGE) return std::nullopt;
    if (v < -0x7ffffffeLL || v > 0x7ffffffeLL) return std::nullopt;
    out.push_back(v);
    p = end;
  }
  if (out.size() != n) return std::nullopt;
  return out;
}

/// A non-negative integer count (at most 2^62), else nullopt.
std::optional<ull> count_of(const std::string& s) {
  const char* p = s.c_str();
  while (*p && is_space(*p)) ++p;
  if (!std::isdigit(static_cast<unsigned char>(*p))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const ull v = std::strtoull(p, &end, 10);
  while (*end && is_space(*end)) ++end;
  if (*end || errno == ERANGE || v > (1ULL << 62)) return std::nullopt;
  return v;
}

/// Exactly `n` whitespace-separated finite decimal numbers, else nullopt. Only the characters of
/// decimal notation: VTK reads these with a stream, which stops at "nan" or the "x" of hex floats
/// that strtod would accept (and then takes the default 1 1 1 instead).
std::optional<std::vector<double>> finite_numbers(const std::string& s, std::size_t n) {
  std::vector<double> out;
  const char* p = s.c_str();
  for (;;) {
    while (*p && is_space(*p)) ++p;
    if (!*p) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || (*end && !is_space(*end)) || !std::isfinite(v)) return std::nullopt;
    for (const char* c = p; c != end; ++c)
      if (!std::isdigit(static_cast<unsigned char>(*c)) && *c != '+' && *c != '-' && *c != '.' && *c != 'e' &&
          *c != 'E')
        return std::nullopt;
    out.push_back(v);
    p = end;
  }
  if (out.size() != n) return std::nullopt;
  return out;
}

bool is_base64(char ch) {
  return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '+' ||
         ch == '/';
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
    else if (is_space(ch))
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

/// Bytes of one value of a VTK XML numeric type, 0 for anything else.
std::size_t type_size(const std::string& t) {
  if (t == "Int8" || t == "UInt8") return 1;
  if (t == "Int16" || t == "UInt16") return 2;
  if (t == "Int32" || t == "UInt32" || t == "Float32") return 4;
  if (t == "Int64" || t == "UInt64" || t == "Float64") return 8;
  return 0;
}

std::string text_of(ull v) { return std::to_string(v); }

/// The file's bytes [pos, pos + n) (fewer at its end).
std::string file_range(std::ifstream& in, ull pos, std::size_t n) {
  std::string raw(n, '\0');
  in.clear();
  in.seekg(std::streamoff(pos));
  in.read(raw.data(), std::streamsize(raw.size()));
  raw.resize(std::size_t(std::max<std::streamsize>(in.gcount(), 0)));
  in.clear();
  return raw;
}

}  // namespace

VtkXmlLayout check_vtk_xml(const std::string& path) {
  VtkXmlLayout layout;
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto size = static_cast<ull>(std::filesystem::file_size(path, ec));
  if (!in || ec) return layout;  // the reader reports it
  // The XML text: everything before the appended data's '_' (or the whole file without it).
  std::string text;
  std::size_t appended = npos, app_tag = npos;
  for (std::string chunk(1 << 20, '\0'); in;) {
    in.read(chunk.data(), std::streamsize(chunk.size()));
    const std::size_t from = text.size() > 16 ? text.size() - 16 : 0;
    text.append(chunk.data(), std::size_t(in.gcount()));
    if (app_tag == npos) app_tag = text.find("<AppendedData", from);
    if (app_tag == npos) continue;
    // VTK takes the first character after the tag and its whitespace as the '_' marker, whatever
    // it is, and reads the data from the next byte: anything else there shifts every header.
    const std::size_t close = text.find('>', app_tag);
    std::size_t mark = close == npos ? close : close + 1;
    while (mark < text.size() && is_space(text[mark])) ++mark;
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
  // The appended data ends at the file's last </AppendedData> (else at the end of the file).
  ull data_end = size;
  if (appended != npos) {
    const std::size_t tail = std::size_t(std::min<ull>(size - appended, 1 << 16));
    const std::string last = file_range(in, size - tail, tail);
    const std::size_t close = last.rfind("</AppendedData>");
    if (close != npos) data_end = size - tail + close;
  }

  std::string byte_order, header_type, compressor, encoding = "base64";
  int word = 4;
  bool big = false, compressed = false;
  std::string dataset;  // the dataset element VTK reads: ImageData or PolyData
  // The current Piece: a .vti's points and cells, a .vtp's points and cells of each kind.
  struct Piece {
    ull points = 0, cells = 0, verts = 0, lines = 0, strips = 0, polys = 0;
  } piece;
  std::size_t piece_index = 0, pieces = 0;
  std::vector<Piece> piece_counts;  // every Piece but the current one
  // Raw appended arrays as [first byte, past the last byte) of the file, with their names: VTK
  // writes them one after the other, and a header_type that does not match the headers (a
  // UInt64 file read as UInt32) leaves gaps or overlaps even where each header looks plausible.
  struct Span {
    ull begin, end;
    std::string where;
  };
  std::vector<Span> spans;
  std::vector<std::string> stack;
  auto refuse = [&](const std::string& what) { throw Error(path, what); };
  auto word_at = [&](const std::string& b, std::size_t i) {
    ull v = 0;
    for (int k = 0; k < word; ++k) {
      const unsigned char byte =
          static_cast<unsigned char>(b[i * std::size_t(word) + std::size_t(big ? k : word - 1 - k)]);
      v = (v << 8) | byte;
    }
    return v;
  };

  if (app_tag != npos) {  // the encoding of all appended arrays, which come before this tag
    Tag t;
    if (parse_tag(path, text, app_tag, t) && t.get("encoding")) encoding = t.value("encoding");
    if (encoding != "raw" && encoding != "base64")
      refuse("appended data encoding '" + encoding.substr(0, 40) + "' is neither raw nor base64");
  }
  Tag tag;
  for (std::size_t lt = text.find('<'); lt != npos; lt = text.find('<', tag.end)) {
    if (!parse_tag(path, text, lt, tag)) break;  // the text ends inside a tag: the reader reports it
    if (tag.name.empty()) continue;
    if (tag.closing) {
      // Close the innermost element of that name (expat refuses mismatched tags anyway).
      for (std::size_t i = stack.size(); i-- > 0;)
        if (stack[i] == tag.name) {
          stack.resize(i);
          break;
        }
      continue;
    }
    if (!tag.empty) stack.push_back(tag.name);
    const std::string& name = tag.name;
    if (name == "VTKFile") {
      layout.type = tag.value("type");
      byte_order = tag.value("byte_order");
      if (!byte_order.empty() && byte_order != "LittleEndian" && byte_order != "BigEndian")
        refuse("byte_order '" + byte_order + "' is neither LittleEndian nor BigEndian");
      big = byte_order == "BigEndian";
      header_type = tag.value("header_type");
      if (header_type.empty() || header_type == "UInt32")
        word = 4;
      else if (header_type == "UInt64")
        word = 8;
      else
        refuse("header_type '" + header_type + "' is neither UInt32 nor UInt64");
      compressor = tag.value("compressor");
      if (!compressor.empty() && compressor != "vtkZLibDataCompressor" && compressor != "vtkLZ4DataCompressor" &&
          compressor != "vtkLZMADataCompressor")
        refuse("unknown compressor '" + compressor.substr(0, 60) + "'");
      compressed = !compressor.empty();
      continue;
    }
    if (name == "ImageData" || name == "PolyData") {
      dataset = layout.type = name;
      if (name == "PolyData") continue;
      if (const std::string* w = tag.get("WholeExtent")) {
        const auto v = integers(*w, 6);
        if (!v) refuse("WholeExtent '" + w->substr(0, 80) + "' is not six integers below 2^31 in magnitude");
        for (std::size_t i = 0; i < 3; ++i)
          if ((*v)[2 * i] > (*v)[2 * i + 1]) refuse("WholeExtent '" + *w + "' is empty");
      }
      if (const std::string* o = tag.get("Origin"))
        if (!finite_numbers(*o, 3)) refuse("Origin '" + o->substr(0, 80) + "' is not three finite numbers");
      if (const std::string* s = tag.get("Spacing")) {
        const auto v = finite_numbers(*s, 3);
        if (!v || (*v)[0] == 0 || (*v)[1] == 0 || (*v)[2] == 0)
          refuse("Spacing '" + s->substr(0, 80) + "' is not three finite non-zero numbers");
      }
      if (const std::string* d = tag.get("Direction"))
        if (!finite_numbers(*d, 9)) refuse("Direction '" + d->substr(0, 80) + "' is not nine finite numbers");
      continue;
    }
    if (name == "Piece") {
      if (pieces > 0) piece_counts.push_back(piece);
      piece = Piece{};
      piece_index = pieces++;
      if (dataset == "ImageData") {
        const std::string* e = tag.get("Extent");
        const auto v = e ? integers(*e, 6) : std::nullopt;
        if (!v) refuse("a Piece without an Extent of six integers below 2^31 in magnitude");
        piece.points = piece.cells = 1;
        for (std::size_t i = 0; i < 3; ++i) {
          const long long lo = (*v)[2 * i], hi = (*v)[2 * i + 1];
          if (lo > hi) refuse("Piece Extent '" + *e + "' is empty");
          const ull d = ull(hi - lo + 1);
          if (piece.points > (1ULL << 62) / d) refuse("Piece Extent '" + *e + "' is implausibly large");
          piece.points *= d;
          piece.cells *= std::max<ull>(d - 1, 1);
        }
      } else {
        const char* keys[] = {"NumberOfPoints", "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys"};
        ull* fields[] = {&piece.points, &piece.verts, &piece.lines, &piece.strips, &piece.polys};
        for (std::size_t k = 0; k < 5; ++k)
          if (const std::string* v = tag.get(keys[k])) {
            const auto c = count_of(*v);
            if (!c) refuse(std::string(keys[k]) + " '" + v->substr(0, 40) + "' is not a non-negative integer");
            *fields[k] = *c;
          }
        piece.cells = piece.verts + piece.lines + piece.strips + piece.polys;
      }
      continue;
    }
    if (name != "DataArray" && name != "Array") continue;

    // A data array: where it is, what it declares, and what it holds.
    static const char* const kSections[] = {"PointData", "CellData", "FieldData", "Points", "Verts",
                                            "Lines",     "Strips",   "Polys",     "Coordinates"};
    std::string section;
    for (std::size_t i = stack.size(); i-- > 0 && section.empty();)
      for (const char* s : kSections)
        if (stack[i] == s) section = s;
    VtkXmlArray array;
    array.section = section;
    array.name = tag.value("Name");
    array.type = tag.value("type");
    array.piece = piece_index;
    const std::string where = "array '" + array.name.substr(0, 60) + "'" +
                              (section.empty() ? "" : " in " + section) +
                              (pieces > 0 && section != "FieldData" ? " of piece " + std::to_string(piece_index) : "");
    const bool text_array = array.type == "String";
    const std::size_t tsize = type_size(array.type);
    if (text_array && section != "FieldData")
      refuse(where + " is a String array; only numeric arrays (Int8 ... Float64) are supported here");
    if (!tsize && !text_array)
      refuse(where + " has type '" + array.type.substr(0, 40) +
             "'; supported: Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64");
    ull components = 1;
    if (const std::string* c = tag.get("NumberOfComponents")) {
      const auto v = count_of(*c);
      if (!v || *v == 0 || *v > (1U << 20))
        refuse(where + " has NumberOfComponents '" + c->substr(0, 40) + "'");
      components = *v;
    }
    const std::string format = tag.value("format");
    if (format != "ascii" && format != "binary" && format != "appended")
      refuse(where + " has format '" + format.substr(0, 40) + "' (ascii, binary or appended)");
    // The tuples the declaration needs, where the file fixes them.
    std::optional<ull> tuples;
    if (section == "PointData" || section == "Points") {
      tuples = piece.points;
      if (section == "Points" && components != 3) refuse(where + " has " + text_of(components) + " components, not 3");
    } else if (section == "CellData") {
      tuples = piece.cells;
    } else if (section == "Verts" || section == "Lines" || section == "Strips" || section == "Polys") {
      const ull cells = section == "Verts" ? piece.verts : section == "Lines" ? piece.lines
                        : section == "Strips" ? piece.strips : piece.polys;
      if (array.name == "offsets")
        tuples = cells;
      else if (cells == 0)
        tuples = 0;  // VTK reads nothing: the file must hold nothing either
    }
    if (const std::string* t = tag.get("NumberOfTuples")) {
      const auto v = count_of(*t);
      if (!v) refuse(where + " has NumberOfTuples '" + t->substr(0, 40) + "'");
      if (tuples && *tuples != *v)
        refuse(where + " declares " + text_of(*v) + " tuples where its piece has " + text_of(*tuples));
      tuples = *v;
    }
    if (tuples && components > 1 && *tuples > (1ULL << 62) / components)
      refuse(where + " declares implausibly many values");
    const bool known = tuples.has_value();
    const ull tuple_count = tuples.value_or(0), value_count = tuple_count * components;
    auto declared = [&] {
      return text_of(tuple_count) + " x " + text_of(components) + " " + array.type + " values";
    };
    auto needed_bytes = [&] {  // what the declaration needs, for messages
      const long double b = (long double)value_count * (long double)tsize;
      return b < 1e18L ? text_of(ull(b)) : std::to_string(double(b));
    };

    if (format == "ascii") {
      // The element's text up to the next tag: whitespace-separated values.
      ull count = 0;
      if (!tag.empty) {
        const std::size_t end = std::min(text.find('<', tag.end), text.size());
        for (std::size_t p = tag.end; p < end;) {
          while (p < end && is_space(text[p])) ++p;
          if (p >= end) break;
          ++count;
          while (p < end && !is_space(text[p])) ++p;
        }
      }
      array.values = count;
      if (text_array) {
        if (known && value_count > count)
          refuse(where + " declares " + text_of(value_count) + " strings but holds " + text_of(count) + " characters");
      } else if (known && count != value_count) {
        refuse(where + " holds " + text_of(count) + " ASCII values, its declaration " + declared() + " (" +
               text_of(value_count) + ")");
      }
      layout.arrays.push_back(std::move(array));
      continue;
    }

    if (byte_order.empty()) refuse("binary data without a byte_order on <VTKFile>");
    // Where the encoded bytes are: a range of the text (inline) or of the file (appended).
    bool base64 = true, inline_data = false;
    ull begin = 0, end = 0;
    if (format == "appended") {
      if (appended == npos) refuse(where + " is appended but the file has no <AppendedData> beginning with '_'");
      const std::string* o = tag.get("offset");
      const auto offset = o ? count_of(*o) : std::nullopt;
      if (!offset) refuse(where + " has no valid offset");
      begin = ull(appended) + *offset;
      end = data_end;
      if (begin >= end)
        refuse(where + " starts at offset " + *o + ", past the appended data's " + text_of(end - appended) + " bytes");
      base64 = encoding == "base64";
    } else {
      inline_data = true;
      if (tag.empty) refuse(where + " is binary but has no data");
      begin = tag.end;
      while (begin < text.size() && is_space(text[std::size_t(begin)])) ++begin;
      end = std::min(text.find('<', tag.end), text.size());
      if (begin > end) begin = end;
    }
    // `n` decoded bytes from `skip` encoded characters past `begin`; fewer at the end.
    auto bytes_at = [&](ull skip, std::size_t n) {
      const ull from = begin + skip;
      if (from >= end) return std::string();
      const std::size_t want = std::size_t(std::min<ull>(base64 ? (n + 2) / 3 * 4 : n, end - from));
      std::string raw = inline_data ? text.substr(std::size_t(from), want) : file_range(in, from, want);
      if (!base64) return raw;
      const std::vector<unsigned char> b = base64_decode(raw);
      return std::string(b.begin(), b.begin() + long(std::min(b.size(), n)));
    };
    // Decoded bytes the range [begin + skip, end) can hold at most.
    auto capacity = [&](ull skip) -> ull {
      if (begin + skip >= end) return 0;
      if (!base64) return end - begin - skip;
      if (!inline_data) return (end - begin - skip) / 4 * 3 + 3;  // appended base64: a bound
      ull chars = 0;
      for (std::size_t p = std::size_t(begin + skip); p < std::size_t(end); ++p)
        if (is_base64(text[p]) || text[p] == '=') ++chars;
      return chars / 4 * 3 + 3;
    };
    const std::size_t header = std::size_t(word) * (compressed ? 3 : 1);
    const std::string first = bytes_at(0, header);
    if (first.size() < header) refuse(where + " is cut inside its " + text_of(header) + "-byte header");
    ull stored;
    if (!compressed) {
      stored = word_at(first, 0);
      const ull room = capacity(0);
      if ((long double)stored + word > (long double)room)
        refuse(where + " claims " + text_of(stored) + " bytes but its data holds at most " +
               text_of(room > ull(word) ? room - ull(word) : 0));
      if (!base64 && !inline_data) spans.push_back({begin, begin + ull(word) + stored, where});
    } else {
      const ull blocks = word_at(first, 0), block = word_at(first, 1), last = word_at(first, 2);
      auto too_big = [&](const std::string& what) {
        refuse("compressed array '" + array.name + "' " + what + " but the file holds " + text_of(size) + " bytes");
      };
      // VTK allocates a block's buffer even when there are no blocks (found by the VTP fuzzer).
      const long double most = (long double)size * 1040 + 1024;
      if ((long double)block > most || (long double)last > most)
        too_big("claims blocks of " + text_of(std::max(block, last)) + " bytes");
      if (blocks > size / unsigned(word))
        too_big("claims " + text_of(blocks) + " blocks (a " + text_of(blocks * ull(word)) + "-byte header)");
      if (blocks > 0 && block == 0)  // VTK divides by it (a floating-point exception, found by the VTP fuzzer)
        refuse("compressed array '" + array.name + "' claims a block size of 0");
      const std::size_t full = std::size_t((3 + blocks) * ull(word));
      const std::string all = bytes_at(0, full);
      if (all.size() < full) refuse(where + " is cut inside its " + text_of(full) + "-byte block header");
      long double packed = 0;
      for (ull i = 0; i < blocks; ++i) {
        const ull c = word_at(all, std::size_t(3 + i));
        const ull u = i + 1 == blocks && last != 0 ? last : block;
        packed += (long double)c;
        if ((long double)u > (long double)c * 1040 + 1024 || packed > (long double)size)
          too_big("claims a block of " + text_of(u) + " bytes from " + text_of(c) + " compressed");
      }
      if (blocks > 0 && last > block)
        refuse(where + " claims a last block of " + text_of(last) + " bytes, larger than its blocks of " +
               text_of(block));
      stored = blocks == 0 ? 0 : (blocks - 1) * block + (last != 0 ? last : block);
      // The blocks follow the header: raw bytes, or base64 encoded apart from the header.
      const ull skip = base64 ? ull(full + 2) / 3 * 4 : ull(full);
      const ull room = capacity(skip);
      if (packed > (long double)room)
        refuse(where + " claims " + text_of(ull(packed)) + " compressed bytes but its data holds at most " +
               text_of(room));
      if (!base64 && !inline_data) spans.push_back({begin, begin + ull(full) + ull(packed), where});
    }
    if (text_array) {
      array.values = stored;  // bytes of NUL-terminated strings
      if (known && value_count > stored)
        refuse(where + " declares " + text_of(value_count) + " strings but holds " + text_of(stored) + " bytes");
    } else {
      if (stored % tsize != 0)
        refuse(where + " holds " + text_of(stored) + " bytes, not a whole number of " + array.type + " values");
      array.values = stored / tsize;
      if (known && (value_count > (1ULL << 62) / tsize || stored != value_count * tsize))
        refuse(where + " holds " + text_of(stored) + " bytes, its declaration " + declared() + " (" +
               needed_bytes() + " bytes)");
    }
    layout.arrays.push_back(std::move(array));
  }
  if (pieces > 0) piece_counts.push_back(piece);

  // Raw appended arrays tile the appended data: from its first byte, each where the last ended,
  // the last followed by nothing but whitespace before </AppendedData>.
  std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.begin < b.begin; });
  ull at = appended == npos ? 0 : ull(appended);
  for (std::size_t i = 0; i < spans.size(); ++i) {
    if (i > 0 && spans[i].begin == spans[i - 1].begin && spans[i].end == spans[i - 1].end) continue;  // shared
    if (spans[i].begin > at)
      refuse(spans[i].where + " starts " + text_of(spans[i].begin - at) +
             " bytes after the previous array's data ends (a header_type or byte count that does not match the "
             "data?)");
    if (spans[i].begin < at)
      refuse(spans[i].where + " starts inside the previous array's data (a header_type or byte count that does "
                              "not match the data?)");
    at = spans[i].end;
  }
  if (!spans.empty()) {
    const bool ends_clean = at <= data_end && data_end - at <= 4096 && [&] {
      const std::string rest = file_range(in, at, std::size_t(data_end - at));
      return rest.size() == data_end - at && std::all_of(rest.begin(), rest.end(), is_space);
    }();
    if (!ends_clean)
      refuse("the appended data holds " + text_of(data_end > at ? data_end - at : 0) +
             " bytes after its last array (" + spans.back().where + ") that no array accounts for");
  }

  // Every cell kind a .vtp piece declares must be stored (VTK read a mesh without them).
  if (dataset == "PolyData") {
    for (std::size_t p = 0; p < piece_counts.size(); ++p) {
      const Piece& c = piece_counts[p];
      const std::pair<const char*, ull> kinds[] = {
          {"Points", c.points}, {"Verts", c.verts}, {"Lines", c.lines}, {"Strips", c.strips}, {"Polys", c.polys}};
      for (const auto& kind : kinds) {
        const std::string section = kind.first;  // not a structured binding: lambdas capture it
        const ull n = kind.second;
        if (n == 0) continue;
        for (const char* needed : {"offsets", "connectivity"}) {
          if (section == "Points" && std::string(needed) == "connectivity") continue;
          const bool found = std::any_of(layout.arrays.begin(), layout.arrays.end(), [&](const VtkXmlArray& a) {
            return a.piece == p && a.section == section && (section == "Points" || a.name == needed);
          });
          if (!found)
            refuse("piece " + std::to_string(p) + " declares " + text_of(n) + " " + section + " but holds no " +
                   (section == "Points" ? std::string("Points array") : "'" + std::string(needed) + "' array for them"));
        }
      }
    }
  }
  return layout;
}

}  // namespace isocurv::detail
