// Image files read through VTK: XML image data (.vti) and legacy STRUCTURED_POINTS (.vtk); VolVis
// SLC (.slc) is handed to load_slc. VTK's error messages are caught by an observer and become the
// Error text.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vtkCallbackCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredPoints.h>
#include <vtkStructuredPointsReader.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/vtk_progress.h"
#include "core/vtk_xml_blocks.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

/// Collects the first error a VTK object reports instead of printing it.
struct ErrorCatcher {
  std::string message;
  vtkNew<vtkCallbackCommand> command;
  ErrorCatcher() {
    command->SetClientData(this);
    command->SetCallback([](vtkObject*, unsigned long event, void* client, void* call) {
      auto* self = static_cast<ErrorCatcher*>(client);
      if (event == vtkCommand::ErrorEvent && self->message.empty() && call) {
        std::string text = static_cast<const char*>(call);
        // VTK prefixes "ERROR: In <file>, line <n>\n<class> (<ptr>): "; keep the last line.
        const std::size_t nl = text.find_last_of('\n', text.size() > 1 ? text.size() - 2 : 0);
        if (nl != std::string::npos) text = text.substr(nl + 1);
        const std::size_t colon = text.find("): ");
        if (colon != std::string::npos) text = text.substr(colon + 3);
        self->message = trim(text);
        if (self->message.empty()) self->message = "VTK reader error";
      }
    });
  }
  void watch(vtkObject* o) {
    o->AddObserver(vtkCommand::ErrorEvent, command);
    o->AddObserver(vtkCommand::WarningEvent, command);
  }
};

/// Replaces VTK's global output window while a file is read, so that messages VTK sends there
/// (generic warnings such as "Error reading ascii data", which no observer sees) are captured
/// instead of printed. A mutex serialises readers, as the window is process-wide.
class CapturingWindow : public vtkOutputWindow {
 public:
  static CapturingWindow* New();
  vtkTypeMacro(CapturingWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* t) override { keep(t); }
  void DisplayWarningText(const char* t) override { keep(t); }
  void DisplayGenericWarningText(const char* t) override { keep(t); }
  void DisplayDebugText(const char*) override {}
  std::string message;

 private:
  void keep(const char* t) {
    if (message.empty() && t) message = trim(t);
  }
};
vtkStandardNewMacro(CapturingWindow);

class OutputWindowGuard {
 public:
  OutputWindowGuard() : lock_(mutex()), previous_(vtkOutputWindow::GetInstance()) {
    previous_->Register(nullptr);
    vtkOutputWindow::SetInstance(window_);
  }
  ~OutputWindowGuard() {
    vtkOutputWindow::SetInstance(previous_);
    previous_->UnRegister(nullptr);
  }
  OutputWindowGuard(const OutputWindowGuard&) = delete;
  OutputWindowGuard& operator=(const OutputWindowGuard&) = delete;
  const std::string& message() const { return window_->message; }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  vtkOutputWindow* previous_;
  vtkNew<CapturingWindow> window_;
};

std::string vtk_type_name(int t) {
  switch (t) {
    case VTK_UNSIGNED_CHAR: return "uint8";
    case VTK_CHAR:
    case VTK_SIGNED_CHAR: return "int8";
    case VTK_SHORT: return "int16";
    case VTK_UNSIGNED_SHORT: return "uint16";
    case VTK_INT: return "int32";
    case VTK_UNSIGNED_INT: return "uint32";
    case VTK_LONG:
    case VTK_LONG_LONG: return "int64";
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG: return "uint64";
    case VTK_FLOAT: return "float";
    case VTK_DOUBLE: return "double";
    default: return "unknown";
  }
}

template <class T>
void to_float(const T* src, std::size_t n, float* dst) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) dst[i] = float(src[i]);
  });
}


/// The voxel and component counts a VTK image header claims (0 when it does not say).
struct Claim {
  std::array<long long, 3> dims{0, 0, 0};
  long long components = 1;
};

std::optional<std::vector<long long>> integers(const std::string& text, std::size_t n) {
  std::istringstream in(text);
  std::vector<long long> out(n);
  for (auto& v : out)
    if (!(in >> v) || v < -(1LL << 40) || v > (1LL << 40)) return std::nullopt;
  return out;
}

/// The text after `key` and an `="` that follows it, up to the closing quote (at most 256 chars).
std::optional<std::string> attribute(const std::string& head, const std::string& key, std::size_t& from) {
  while ((from = head.find(key, from)) != std::string::npos) {
    from += key.size();
    std::size_t p = from;
    while (p < head.size() && std::isspace(static_cast<unsigned char>(head[p]))) ++p;
    if (p >= head.size() || head[p] != '=') continue;
    const std::size_t open = head.find('"', p);
    if (open == std::string::npos || open > p + 8) continue;
    const std::size_t close = head.find('"', open + 1);
    if (close == std::string::npos || close - open > 256) continue;
    return head.substr(open + 1, close - open - 1);
  }
  return std::nullopt;
}

/// The rest of the first line starting with `keyword` (any case, after blanks), else empty.
std::string line_after(const std::string& lower_head, const std::string& keyword) {
  for (std::size_t p = 0; (p = lower_head.find(keyword, p)) != std::string::npos; p += keyword.size()) {
    std::size_t q = p;
    while (q > 0 && (lower_head[q - 1] == ' ' || lower_head[q - 1] == '\t')) --q;
    if (q != 0 && lower_head[q - 1] != '\n') continue;
    const std::size_t end = lower_head.find('\n', p);
    return lower_head.substr(p + keyword.size(), (end == std::string::npos ? lower_head.size() : end) - p -
                                                     keyword.size());
  }
  return {};
}

/// Reads the claim from the first 64 KiB: WholeExtent and NumberOfComponents (.vti), DIMENSIONS
/// and the SCALARS component count (.vtk).
Claim read_claim(const std::string& head, const std::string& format) {
  Claim c;
  if (format == "vti") {
    std::size_t from = 0;
    if (auto e = attribute(head, "WholeExtent", from))
      if (auto v = integers(*e, 6))
        for (std::size_t i = 0; i < 3; ++i) c.dims[i] = (*v)[2 * i + 1] - (*v)[2 * i] + 1;
    from = 0;
    while (auto n = attribute(head, "NumberOfComponents", from))
      if (auto v = integers(*n, 1)) c.components = std::max(c.components, (*v)[0]);
  } else if (format == "vtk") {
    const std::string lower = to_lower(head);
    if (auto d = integers(line_after(lower, "dimensions"), 3)) c.dims = {(*d)[0], (*d)[1], (*d)[2]};
    std::istringstream scalars(line_after(lower, "scalars"));
    std::string name, type;
    long long n = 1;
    if (scalars >> name >> type >> n) c.components = std::max(1LL, n);
  }
  return c;
}

/// Refuses, before VTK's legacy reader sees them, attribute declarations it would allocate for
/// from unchecked words (it reads words, not lines, as in `head`, lowercased): a data type that is
/// not numeric (VTK reads "string..." types as strings, each with a length taken from the data:
/// the fuzzer made it ask for 2.9e17 bytes), and counts (POINT_DATA, CELL_DATA, a LOOKUP_TABLE's
/// size, COLOR_SCALARS' values per point) beyond what the file can hold at a byte a value.
void check_legacy_attributes(const std::string& path, const std::string& head, std::uint64_t size) {
  static const char* const kNumeric[] = {"bit",  "unsigned_char", "char",         "signed_char",  "unsigned_short",
                                         "short", "unsigned_int",  "int",          "unsigned_long", "long",
                                         "float", "double",        "vtktypeint64", "vtktypeuint64", "vtkidtype"};
  std::istringstream in(head);
  std::vector<std::string> w;
  for (std::string word; in >> word;) w.push_back(word);
  auto numeric = [&](std::size_t i, const std::string& keyword) {
    if (i >= w.size()) return;  // the reader reports a short header
    for (const char* t : kNumeric)
      if (w[i] == t) return;
    throw Error(path, keyword + " data type '" + w[i] + "' is not a numeric VTK type");
  };
  auto count = [&](std::size_t i, const std::string& keyword, long double bytes_each) {
    if (i >= w.size()) return;
    char* end = nullptr;
    const long double n = std::strtold(w[i].c_str(), &end);
    if (end == w[i].c_str() || *end != '\0') return;  // not a count (the reader decides)
    if (n * bytes_each > (long double)size)
      throw Error(path, keyword + " claims " + w[i] + " entries but the file holds " + bytes_text(size));
  };
  // VTK's reader matches a keyword by its first letters (strncmp): "scalars\314" is SCALARS.
  auto is = [](const std::string& word, const char* keyword) { return word.rfind(keyword, 0) == 0; };
  for (std::size_t i = 0; i < w.size(); ++i) {
    const std::string& k = w[i];
    std::string upper = k;  // for messages: the keyword as files write it
    for (char& ch : upper) ch = char(std::toupper(static_cast<unsigned char>(ch)));
    upper.erase(std::remove_if(upper.begin(), upper.end(), [](char ch) { return !(std::isupper(static_cast<unsigned char>(ch)) || ch == '_'); }),
                upper.end());  // the keyword VTK matched, without the bytes after it
    // Each keyword's arguments are passed over (a name may be a keyword: "SCALARS scalars float").
    if (is(k, "scalars") || is(k, "vectors") || is(k, "normals") || is(k, "tensors")) {
      numeric(i + 2, upper);
      i += 2;
    } else if (is(k, "texture_coordinates")) {
      numeric(i + 3, upper);
      i += 3;
    } else if (is(k, "point_data") || is(k, "cell_data")) {
      count(i + 1, upper, 1);
      i += 1;
    } else if (is(k, "lookup_table")) {
      // A table of its own has a name and a size; the line naming the scalars' table just a name.
      const bool of_scalars = (i >= 3 && is(w[i - 3], "scalars")) || (i >= 4 && is(w[i - 4], "scalars"));
      if (!of_scalars) count(i + 2, upper, 4);
      i += of_scalars ? 1 : 2;
    } else if (is(k, "color_scalars")) {
      count(i + 2, upper, 1);
      if (i + 2 < w.size() && std::strtold(w[i + 2].c_str(), nullptr) > 16)
        throw Error(path, "COLOR_SCALARS claims " + w[i + 2] + " values per point (at most 4 are meaningful)");
      i += 2;
    }
  }
}

/// Refuses a .vti whose pieces do not cover its WholeExtent: VTK's reader allocates the whole
/// extent and fills only the pieces, so the rest would load as zeros (silent data loss). Checked
/// only when every Piece tag lies in `head` (it reaches the appended data or the end of the
/// ImageData element); the pieces must span the whole extent on each axis and hold together at
/// least its number of points.
void check_vti_pieces(const std::string& path, const std::string& head) {
  if (head.find("<AppendedData") == std::string::npos && head.find("</ImageData>") == std::string::npos)
    return;
  std::size_t from = 0;
  const std::optional<std::string> whole_text = attribute(head, "WholeExtent", from);
  if (!whole_text) return;  // VTK reports it
  const auto whole = integers(*whole_text, 6);
  if (!whole) return;
  long double whole_points = 1, piece_points = 0;
  std::array<long long, 6> span = {LLONG_MAX, LLONG_MIN, LLONG_MAX, LLONG_MIN, LLONG_MAX, LLONG_MIN};
  for (std::size_t i = 0; i < 3; ++i) whole_points *= (long double)((*whole)[2 * i + 1] - (*whole)[2 * i] + 1);
  int pieces = 0;
  for (std::size_t at = 0; (at = head.find("<Piece", at)) != std::string::npos; at += 6) {
    // The Extent of this Piece tag only: a Piece without one must not take the next one's.
    const std::size_t close = head.find('>', at);
    const std::string tag =
        head.substr(at, close == std::string::npos ? std::string::npos : close - at);
    std::size_t f = 0;
    const std::optional<std::string> e = attribute(tag, "Extent", f);
    const auto v = e ? integers(*e, 6) : std::nullopt;
    if (!v) throw Error(path, "a Piece without a readable Extent");
    ++pieces;
    long double n = 1;
    for (std::size_t i = 0; i < 3; ++i) {
      span[2 * i] = std::min(span[2 * i], (*v)[2 * i]);
      span[2 * i + 1] = std::max(span[2 * i + 1], (*v)[2 * i + 1]);
      n *= (long double)std::max(0LL, (*v)[2 * i + 1] - (*v)[2 * i] + 1);
    }
    piece_points += n;
  }
  if (pieces == 0) return;  // VTK reports it
  bool spans = true;
  for (std::size_t i = 0; i < 3; ++i)
    spans = spans && span[2 * i] <= (*whole)[2 * i] && span[2 * i + 1] >= (*whole)[2 * i + 1];
  if (!spans || piece_points < whole_points)
    throw Error(path, "the pieces' extents do not cover the WholeExtent " + *whole_text +
                          " (the rest would read as zeros)");
}

/// Refuses, before VTK allocates for it, a header claiming more voxels than the file can hold:
/// a .vtk stores at least a byte per value, a .vti at most ~1000 values per byte (deflate).
void check_claim(const std::string& path, const std::string& format, std::uint64_t size) {
  const Bytes head = read_bytes(path, 0, std::min<std::uint64_t>(size, 1 << 16));
  const std::string head_text(head.begin(), head.end());
  // VTK 9.1's legacy reader dereferences a null array on a malformed FIELD block, and it reads
  // words, not lines ("DIMENSIONS 4 3 2field" holds one): isocurv reads only the image's scalars,
  // so a header with "field" anywhere in its first 64 KiB is refused.
  if (format == "vtk" && to_lower(head_text).find("field") != std::string::npos)
    throw Error(path, "legacy .vtk files with FIELD data (or the word 'field' in their header) are not "
                      "supported: VTK's reader can crash on them; save the image as .vti");
  if (format == "vti") check_vti_pieces(path, head_text);
  if (format == "vtk") {
    // VTK's legacy reader takes what it can parse: spacing and origin are checked here (the three
    // words after the keyword, as VTK reads them), so that no format turns a NaN, infinite or zero
    // spacing into something else.
    std::istringstream words(to_lower(head_text));
    std::vector<std::string> w;
    for (std::string word; w.size() < 4096 && words >> word;) w.push_back(word);
    for (const std::string key : {"spacing", "aspect_ratio", "origin"}) {
      const auto at = std::find(w.begin(), w.end(), key);
      if (at == w.end()) continue;
      bool ok = w.end() - at > 3;
      for (int k = 1; ok && k <= 3; ++k) {
        char* end = nullptr;
        const double v = std::strtod(at[k].c_str(), &end);
        ok = *end == '\0' && end != at[k].c_str() && std::isfinite(v) && (v != 0 || key == "origin") &&
             at[k].find_first_not_of("0123456789+-.e") == std::string::npos;  // decimal, as VTK reads it
      }
      if (!ok) {
        std::string upper = key;
        for (char& ch : upper) ch = char(std::toupper(static_cast<unsigned char>(ch)));
        throw Error(path, upper + " is not three finite" + (key == "origin" ? "" : " non-zero") + " numbers");
      }
    }
  }
  const Claim c = read_claim(head_text, format);
  if (c.dims[0] == 0 && c.dims[1] == 0 && c.dims[2] == 0) {  // the reader will complain
    if (format == "vtk") check_legacy_attributes(path, to_lower(head_text), size);
    if (format == "vti") isocurv::detail::check_vtk_xml(path);
    return;
  }
  const std::string text = std::to_string(c.dims[0]) + " x " + std::to_string(c.dims[1]) + " x " +
                           std::to_string(c.dims[2]);
  for (long long d : c.dims)
    if (d <= 0 || d > 0x7fffffffLL) throw Error(path, "invalid dimensions " + text);
  const long double values = (long double)c.dims[0] * c.dims[1] * c.dims[2] * (long double)c.components;
  const long double most = format == "vtk" ? (long double)size : (long double)max_inflated(size);
  if (values > most)
    throw Error(path, "header claims " + text + " voxels" +
                          (c.components > 1 ? " of " + std::to_string(c.components) + " components" : "") +
                          " (" + bytes_text(values) + " at one byte each) but the file holds " + bytes_text(size));
  if (format == "vtk") check_legacy_attributes(path, to_lower(head_text), size);
  // Every extent, type, header, count and block length against the bytes: VTK allocates from
  // block headers, reads past short data and crashes on string arrays (core/vtk_xml_blocks.h).
  if (format == "vti") isocurv::detail::check_vtk_xml(path);
}

}  // namespace

Volume load_vtk_image(const std::string& path, const LoadOptions& options) {
  const std::uint64_t size = file_size(path);
  const std::string name = to_lower(path);
  const bool xml = name.size() >= 4 && name.compare(name.size() - 4, 4, ".vti") == 0;
  const bool slc = name.size() >= 4 && name.compare(name.size() - 4, 4, ".slc") == 0;
  if (slc) return load_slc(path, options);  // VTK's SLC reader trusts every count in the file
  const std::string format = xml ? "vti" : "vtk";
  check_claim(path, format, size);
  OutputWindowGuard window;
  ErrorCatcher errors;
  vtkSmartPointer<vtkImageData> image;

  if (xml) {
    vtkNew<vtkXMLImageDataReader> reader;
    errors.watch(reader);
    if (!reader->CanReadFile(path.c_str())) throw Error(path, "not a VTK XML image data file");
    reader->SetFileName(path.c_str());
    VtkProgressReport progress(reader);
    reader->Update();
    image = reader->GetOutput();
  } else {
    vtkNew<vtkStructuredPointsReader> reader;
    errors.watch(reader);
    reader->SetFileName(path.c_str());
    if (!reader->IsFileStructuredPoints())
      throw Error(path, errors.message.empty() ? "not a legacy VTK STRUCTURED_POINTS file" : errors.message);
    VtkProgressReport progress(reader);
    reader->Update();
    image = reader->GetOutput();
  }
  if (!errors.message.empty()) throw Error(path, errors.message);
  if (!window.message().empty()) throw Error(path, window.message());
  if (!image) throw Error(path, "VTK reader produced no image");

  vtkDataArray* array = image->GetPointData()->GetScalars();
  if (!array && image->GetPointData()->GetNumberOfArrays() > 0) array = image->GetPointData()->GetArray(0);
  if (!array) throw Error(path, "image has no point data array");
  if (array->GetNumberOfComponents() != 1)
    throw Error(path, "array '" + std::string(array->GetName() ? array->GetName() : "") + "' has " +
                          std::to_string(array->GetNumberOfComponents()) + " components; a scalar array is needed");

  int ext[6];
  image->GetExtent(ext);
  const std::array<long long, 3> dims{ext[1] - ext[0] + 1LL, ext[3] - ext[2] + 1LL, ext[5] - ext[4] + 1LL};
  const std::uint64_t count = checked_voxel_count(path, dims);
  if (std::uint64_t(array->GetNumberOfTuples()) != count)
    throw Error(path, "array has " + std::to_string(array->GetNumberOfTuples()) + " values, the image's " +
                          std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
                          " extent needs " + std::to_string(count) + " (truncated data?)");

  DenseImage out;
  out.dims = {int(dims[0]), int(dims[1]), int(dims[2])};
  out.voxel_type = vtk_type_name(array->GetDataType());
  out.array_name = array->GetName() ? array->GetName() : "";
  out.values = LargeBuffer<float>(count);
  switch (array->GetDataType()) {
    vtkTemplateMacro(to_float(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), count, out.values.data()));
    default: throw Error(path, "unsupported array type " + std::string(array->GetDataTypeAsString()));
  }

  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  vtkMatrix3x3* dir = image->GetDirectionMatrix();
  for (std::size_t i = 0; i < 3; ++i) {
    // Direction columns need not be unit vectors in the file: their length scales the spacing.
    double len = 0;
    for (std::size_t j = 0; j < 3; ++j) len += dir->GetElement(int(j), int(i)) * dir->GetElement(int(j), int(i));
    len = std::sqrt(len);
    if (!(len > 0) || !std::isfinite(len)) throw Error(path, "degenerate direction matrix");
    out.spacing[i] = std::fabs(spacing[i]) * len;
    for (std::size_t j = 0; j < 3; ++j)
      out.axes[i][j] = dir->GetElement(int(j), int(i)) / len * (spacing[i] < 0 ? -1.0 : 1.0);
  }
  // The first voxel is at extent minimum, not necessarily index 0.
  for (std::size_t j = 0; j < 3; ++j) {
    out.origin[j] = origin[j];
    for (std::size_t i = 0; i < 3; ++i) out.origin[j] += double(ext[2 * i]) * out.spacing[i] * out.axes[i][j];
  }
  return finish_dense(std::move(out), path, format, options);
}

}  // namespace isocurv::volume
