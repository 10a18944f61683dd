// .ply, written by hand (binary little-endian, every curvature array as a vertex property) and read
// by a small general reader (ascii / binary either endianness, any property types, polygons).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "io/field_arrays.h"
#include "io/mesh_formats.h"

namespace isocurv::io::detail {
namespace {

constexpr bool kHostLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

// ---------------------------------------------------------------- writing

/// Appends the bytes of `value` to `out` in little-endian order.
template <class T>
void put_le(std::vector<char>& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (!kHostLittleEndian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

template <class Element>
void put_element(std::vector<char>& out, const Element& e) {
  if constexpr (std::is_arithmetic_v<Element>) {
    put_le(out, e);
  } else {
    for (float c : e) put_le(out, c);
  }
}

/// The PLY property names of one field array: "nx ny nz" for Normals, "<name>" for scalars,
/// "<name>_0 <name>_1 ..." for vectors.
std::vector<std::string> property_names(const std::string& name, int components) {
  if (name == "Normals") return {"nx", "ny", "nz"};
  if (components == 1) return {name};
  std::vector<std::string> names;
  for (int c = 0; c < components; ++c) names.push_back(name + "_" + std::to_string(c));
  return names;
}

}  // namespace

void write_ply(const std::string& path, const Mesh& mesh, const curvature::CurvatureField* field,
               const CellArrays* cells) {
  const CellArrays no_cells;
  const CellArrays& faces = cells ? *cells : no_cells;
  const curvature::CurvatureField empty;
  const curvature::CurvatureField& f = field ? *field : empty;
  const std::size_t n = mesh.positions.size();
  if (n > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("too many vertices for PLY int indices");

  std::ostringstream header;
  header << "ply\nformat binary_little_endian 1.0\n"
         << "comment isocurv mesh; per-vertex arrays as named in isocurv's DESIGN.md, vectors as <name>_0.._n\n"
         << "element vertex " << n << "\n"
         << "property float x\nproperty float y\nproperty float z\n";
  for_each_array(f, [&](const char* name, const auto& values) {
    using Element = typename std::decay_t<decltype(values)>::value_type;
    if (values.empty()) return;
    const char* type = std::is_same_v<Element, std::uint8_t> ? "uchar" : "float";
    for (const std::string& p : property_names(name, components_of<Element>()))
      header << "property " << type << " " << p << "\n";
  });
  header << "element face " << mesh.triangles.size() << "\n"
         << "property list uchar int vertex_indices\n";
  for (const CellArray& c : faces) header << "property int " << c.name << "\n";
  header << "end_header\n";

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(std::string("cannot open for writing: ") + std::strerror(errno));
  const std::string h = header.str();
  out.write(h.data(), static_cast<std::streamsize>(h.size()));

  std::vector<char> buffer;
  constexpr std::size_t kChunk = 1 << 20;
  auto flush = [&](bool force) {
    if (buffer.size() < kChunk && !force) return;
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
  };
  for (std::size_t i = 0; i < n; ++i) {
    for (float c : mesh.positions[i]) put_le(buffer, c);
    for_each_array(f, [&](const char*, const auto& values) {
      if (!values.empty()) put_element(buffer, values[i]);
    });
    flush(false);
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    put_le(buffer, std::uint8_t{3});
    for (std::uint32_t v : mesh.triangles[i]) put_le(buffer, static_cast<std::int32_t>(v));
    for (const CellArray& c : faces) put_le(buffer, c.values[i]);
    flush(false);
  }
  flush(true);
  out.close();
  if (!out) throw std::runtime_error(std::string("write failed: ") + std::strerror(errno));
}

// ---------------------------------------------------------------- reading

namespace {

enum class Encoding { Ascii, BinaryLE, BinaryBE };
enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
  std::string name;
  Type type = Type::Float32;
  bool is_list = false;
  Type count_type = Type::UInt8;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  std::size_t data_start = 0;
};

std::size_t size_of(Type t) {
  switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    case Type::Float64: return 8;
  }
  return 0;
}

bool parse_type(const std::string& s, Type& t) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::Int8},     {"int8", Type::Int8},     {"uchar", Type::UInt8},  {"uint8", Type::UInt8},
      {"short", Type::Int16},   {"int16", Type::Int16},   {"ushort", Type::UInt16}, {"uint16", Type::UInt16},
      {"int", Type::Int32},     {"int32", Type::Int32},   {"uint", Type::UInt32},  {"uint32", Type::UInt32},
      {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
  for (const auto& [name, type] : names)
    if (s == name) return t = type, true;
  return false;
}

Header parse_header(const std::string& data, const std::string& path) {
  if (data.compare(0, 4, "ply\n") != 0 && data.compare(0, 5, "ply\r\n") != 0)
    throw Error(path, "not a PLY file (no 'ply' magic line)");
  const std::size_t end = data.find("end_header");
  if (end == std::string::npos) throw Error(path, "PLY header has no end_header line");
  Header h;
  std::size_t eol = data.find('\n', end);
  if (eol == std::string::npos) throw Error(path, "truncated after end_header");
  h.data_start = eol + 1;

  std::istringstream lines(data.substr(0, end));
  std::string line;
  bool have_format = false;
  std::getline(lines, line);  // "ply"
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "ascii") h.encoding = Encoding::Ascii;
      else if (format == "binary_little_endian") h.encoding = Encoding::BinaryLE;
      else if (format == "binary_big_endian") h.encoding = Encoding::BinaryBE;
      else throw Error(path, "unknown PLY format '" + format + "'");
      have_format = true;
    } else if (keyword == "element") {
      Element e;
      long long count = -1;
      words >> e.name >> count;
      if (!words || count < 0) throw Error(path, "bad PLY element line '" + line + "'");
      e.count = static_cast<std::uint64_t>(count);
      h.elements.push_back(e);
    } else if (keyword == "property") {
      if (h.elements.empty()) throw Error(path, "PLY property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.is_list = true;
        if (!parse_type(count_type, p.count_type) || !parse_type(item_type, p.type))
          throw Error(path, "bad PLY list property '" + line + "'");
      } else {
        words >> p.name;
        if (!parse_type(type, p.type)) throw Error(path, "unknown PLY property type in '" + line + "'");
      }
      if (p.name.empty()) throw Error(path, "PLY property without a name: '" + line + "'");
      h.elements.back().properties.push_back(p);
    } else {
      throw Error(path, "unexpected PLY header line '" + line + "'");
    }
  }
  if (!have_format) throw Error(path, "PLY header has no format line");
  return h;
}

/// Reads values one at a time from the body, in either encoding; throws on the end of the data.
class Body {
 public:
  Body(const std::string& data, std::size_t pos, Encoding enc, const std::string& path)
      : data_(data), pos_(pos), enc_(enc), path_(path) {}

  void set_context(const Element& e, std::uint64_t record) { element_ = &e, record_ = record; }

  double read(Type t) {
    if (enc_ == Encoding::Ascii) return read_ascii();
    const std::size_t size = size_of(t);
    if (data_.size() - pos_ < size) truncated();
    char b[8];
    std::memcpy(b, data_.data() + pos_, size);
    pos_ += size;
    if ((enc_ == Encoding::BinaryLE) != kHostLittleEndian)
      for (std::size_t i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
    switch (t) {
      case Type::Int8: return load<std::int8_t>(b);
      case Type::UInt8: return load<std::uint8_t>(b);
      case Type::Int16: return load<std::int16_t>(b);
      case Type::UInt16: return load<std::uint16_t>(b);
      case Type::Int32: return load<std::int32_t>(b);
      case Type::UInt32: return load<std::uint32_t>(b);
      case Type::Float32: return load<float>(b);
      case Type::Float64: return load<double>(b);
    }
    return 0;
  }

 private:
  template <class T>
  static double load(const char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }

  double read_ascii() {
    const char* begin = data_.c_str() + pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) {
      while (*begin == ' ' || *begin == '\t' || *begin == '\n' || *begin == '\r') ++begin;
      if (*begin == '\0') truncated();
      throw Error(path_, "bad number in PLY element '" + element_->name + "' record " + std::to_string(record_));
    }
    pos_ = static_cast<std::size_t>(end - data_.c_str());
    return v;
  }

  [[noreturn]] void truncated() const {
    throw Error(path_, "truncated PLY file: data ends in element '" + element_->name + "' record " +
                           std::to_string(record_) + " of " + std::to_string(element_->count));
  }

  const std::string& data_;
  std::size_t pos_;
  Encoding enc_;
  const std::string& path_;
  const Element* element_ = nullptr;
  std::uint64_t record_ = 0;
};

/// Where one vertex property goes: a float slot (stride in floats) or the Boundary bytes.
struct Target {
  float* base = nullptr;
  std::size_t stride = 0;
  std::uint8_t* bytes = nullptr;
};

/// The fewest bytes one record of `e` can take: its values' sizes in binary, a digit and a
/// separator per value in ASCII (a list counts its length only: it may be empty).
std::uint64_t min_record_bytes(const Element& e, Encoding encoding) {
  std::uint64_t bytes = 0;
  for (const Property& p : e.properties)
    bytes += encoding == Encoding::Ascii ? 2 : size_of(p.is_list ? p.count_type : p.type);
  return bytes;
}

/// Refuses, before anything is allocated, element counts the data after the header cannot hold
/// (e.g. 4e9 vertices claimed by a small file).
void check_claims(const Header& h, std::uint64_t body_bytes, const std::string& path) {
  long double needed = 0;
  std::string what;
  for (const Element& e : h.elements) {
    needed += (long double)e.count * (long double)min_record_bytes(e, h.encoding);
    what += (what.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
  }
  if (h.encoding == Encoding::Ascii && needed > 0) needed -= 1;  // the last value needs no separator
  if (needed > (long double)body_bytes) {
    char size[32];
    std::snprintf(size, sizeof size, needed < 1e9L ? "%.0Lf" : "%.3Lg", needed);
    throw Error(path, "header claims " + what + " records (at least " + size + " bytes) but the file holds " +
                          std::to_string(body_bytes) + " bytes after its header");
  }
}

/// `v` as a float, saturating to infinity outside float's range (a plain cast is undefined there).
float to_float(double v) {
  if (v > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  if (v < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

std::string read_whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw Error(path, "read error");
  return s.str();
}

}  // namespace

MeshFile read_ply(const std::string& path) {
  const std::string data = read_whole_file(path);
  const Header header = parse_header(data, path);
  check_claims(header, data.size() - header.data_start, path);
  Body body(data, header.data_start, header.encoding, path);

  MeshFile out;
  curvature::CurvatureField field;
  std::uint64_t vertex_count = 0;
  bool have_vertices = false;
  for (const Element& e : header.elements) {
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    std::vector<Target> targets(e.properties.size());
    if (is_vertex) {
      if (have_vertices) throw Error(path, "PLY file has two vertex elements");
      if (e.count > UINT32_MAX) throw Error(path, "too many vertices");
      have_vertices = true;
      vertex_count = e.count;
      const std::size_t n = static_cast<std::size_t>(e.count);
      auto find = [&](const std::string& name) -> int {
        for (std::size_t i = 0; i < e.properties.size(); ++i)
          if (e.properties[i].name == name && !e.properties[i].is_list) return static_cast<int>(i);
        return -1;
      };
      const int xyz[3] = {find("x"), find("y"), find("z")};
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw Error(path, "PLY vertex element lacks x, y or z");
      out.mesh.positions.resize(n);
      for (int c = 0; c < 3; ++c)
        targets[static_cast<std::size_t>(xyz[c])] = {n ? &out.mesh.positions[0][static_cast<std::size_t>(c)] : nullptr, 3, nullptr};
      for_each_array(field, [&](const char* name, auto& values) {
        using Elem = typename std::decay_t<decltype(values)>::value_type;
        constexpr int nc = components_of<Elem>();
        std::vector<int> where;
        for (const std::string& p : property_names(name, nc)) where.push_back(find(p));
        for (int w : where)
          if (w < 0) return;  // absent (or incomplete): leave the array empty
        values.resize(n);
        for (int c = 0; c < nc; ++c) {
          Target& t = targets[static_cast<std::size_t>(where[static_cast<std::size_t>(c)])];
          if constexpr (std::is_same_v<Elem, std::uint8_t>) t = {nullptr, 0, n ? values.data() : nullptr};
          else t = {n ? reinterpret_cast<float*>(values.data()) + c : nullptr, static_cast<std::size_t>(nc), nullptr};
        }
      });
      // Every other scalar vertex property is an extra array (features, another tool's
      // quality or colour), read as float under its own name, so nothing the file holds is lost.
      field.extra.reserve(e.properties.size());  // the targets point into these arrays
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        if (e.properties[i].is_list || targets[i].base || targets[i].bytes) continue;
        field.extra.push_back({e.properties[i].name, std::vector<float>(n)});
        targets[i] = {n ? field.extra.back().values.data() : nullptr, 1, nullptr};
      }
    }
    if (is_face && !have_vertices) throw Error(path, "PLY face element before the vertex element");
    int index_property = -1;
    if (is_face)
      for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].is_list && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
          index_property = static_cast<int>(i);
    if (is_face && index_property < 0) throw Error(path, "PLY face element lacks a vertex_indices list");

    if (e.properties.empty()) continue;  // records of nothing: no data to read (or loop over)
    std::vector<std::uint32_t> polygon;
    for (std::uint64_t r = 0; r < e.count; ++r) {
      body.set_context(e, r);
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (prop.is_list) {
          const double count = body.read(prop.count_type);
          // (any property type may carry the length: a float one may hold 1e32 or infinity)
          if (!(count >= 0 && count <= 4294967295.0) || count != std::floor(count))
            throw Error(path, "bad PLY list length " + std::to_string(count) + " in '" + e.name + "' record " +
                                  std::to_string(r));
          const bool keep = static_cast<int>(p) == index_property;
          polygon.clear();
          for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(count); ++k) {
            const double v = body.read(prop.type);
            if (!keep) continue;
            if (v < 0 || v >= static_cast<double>(vertex_count) || v != std::floor(v))
              throw Error(path, "PLY face " + std::to_string(r) + " refers to vertex " + std::to_string(v) +
                                    " of " + std::to_string(vertex_count));
            polygon.push_back(static_cast<std::uint32_t>(v));
          }
          for (std::size_t k = 2; k < polygon.size(); ++k)
            out.mesh.triangles.push_back({polygon[0], polygon[k - 1], polygon[k]});
        } else {
          const double v = body.read(prop.type);
          const Target& t = targets[p];
          if (t.base) t.base[r * t.stride] = to_float(v);
          else if (t.bytes) t.bytes[r] = v != 0;  // Boundary is a 0/1 flag, whatever its type
        }
      }
    }
  }
  if (!have_vertices) throw Error(path, "PLY file has no vertex element");
  if (!field_is_empty(field)) out.field = std::move(field);
  return out;
}

}  // namespace isocurv::io::detail
