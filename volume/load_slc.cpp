// VolVis SLC files: an ASCII header (magic 11111, X Y Z and bits per voxel, spacing, unit type,
// data origin, data modification, compression), an icon (width height X, then its red, green and
// blue planes), then Z planes of X*Y uint8 voxels, X fastest: raw (compression 0) or run-length
// coded (1: "<bytes> X" and the codes; a code's low 7 bits count, its high bit says "copy that
// many bytes", else "repeat the next byte", and a zero count ends the plane). Read here with
// every count checked (VTK's vtkSLCReader trusts them).
#include <cctype>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

/// A cursor over the file's bytes; every read past the end throws "truncated".
class Cursor {
 public:
  Cursor(const Bytes& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  long long integer(const char* what) {
    const std::string token = number_token();
    char* end = nullptr;
    const long long v = std::strtoll(token.c_str(), &end, 10);
    if (token.empty() || *end || v < -(1LL << 40) || v > (1LL << 40)) bad(what);
    return v;
  }
  double real(const char* what) {
    const std::string token = number_token();
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (token.empty() || *end) bad(what);
    return v;
  }
  /// Skips whitespace, then requires the letter X (the separator before binary data).
  void separator(const char* what) {
    skip_space();
    if (pos_ >= bytes_.size() || bytes_[pos_] != 'X') bad(what);
    ++pos_;
  }
  const std::uint8_t* take(std::uint64_t n, const std::string& what) {
    if (n > bytes_.size() - pos_)
      throw Error(path_, "SLC file is truncated in the " + what + ": needs " + std::to_string(n) + " bytes, has " +
                             std::to_string(bytes_.size() - pos_));
    const std::uint8_t* p = bytes_.data() + pos_;
    pos_ += n;
    return p;
  }
  std::uint64_t left() const { return bytes_.size() - pos_; }

 private:
  void skip_space() {
    while (pos_ < bytes_.size() && std::isspace(bytes_[pos_])) ++pos_;
  }
  std::string number_token() {
    skip_space();
    std::string token;
    while (pos_ < bytes_.size() && token.size() < 64 &&
           (std::isalnum(bytes_[pos_]) || bytes_[pos_] == '.' || bytes_[pos_] == '-' || bytes_[pos_] == '+') &&
           bytes_[pos_] != 'X')
      token += char(bytes_[pos_++]);
    return token;
  }
  [[noreturn]] void bad(const char* what) const { throw Error(path_, std::string("bad SLC header: ") + what); }

  const Bytes& bytes_;
  const std::string& path_;
  std::size_t pos_ = 0;
};

/// Decodes one run-length coded plane of exactly `out_size` bytes.
void decode_plane(const std::uint8_t* in, std::uint64_t in_size, std::uint8_t* out, std::uint64_t out_size,
                  const std::string& path, long long z) {
  std::uint64_t i = 0, o = 0;
  const std::string where = "SLC plane " + std::to_string(z);
  while (true) {
    if (i >= in_size) throw Error(path, where + ": run-length codes end without their terminator");
    const std::uint8_t code = in[i++];
    const std::uint64_t count = code & 0x7f;
    if (count == 0) break;
    if (count > out_size - o) throw Error(path, where + ": run-length codes overflow the plane");
    if (code & 0x80) {
      if (count > in_size - i) throw Error(path, where + ": run-length codes end in a copy");
      for (std::uint64_t k = 0; k < count; ++k) out[o++] = in[i++];
    } else {
      if (i >= in_size) throw Error(path, where + ": run-length codes end in a run");
      const std::uint8_t value = in[i++];
      for (std::uint64_t k = 0; k < count; ++k) out[o++] = value;
    }
  }
  if (o != out_size)
    throw Error(path, where + " decodes to " + std::to_string(o) + " bytes, not " + std::to_string(out_size));
}

}  // namespace

Volume load_slc(const std::string& path, const LoadOptions& options) {
  const Bytes file = read_bytes(path, 0, file_size(path));
  Cursor in(file, path);
  if (in.integer("magic number") != 11111) throw Error(path, "not an SLC file (magic number is not 11111)");
  std::array<long long, 3> dims{};
  for (auto& d : dims) d = in.integer("size");
  const long long bits = in.integer("bits per voxel");
  if (bits != 8) throw Error(path, "only 8-bit SLC files are supported (bits per voxel: " + std::to_string(bits) + ")");
  DenseImage image;
  for (auto& s : image.spacing) s = in.real("spacing");
  for (const char* what : {"unit type", "data origin", "data modification"}) in.integer(what);
  const long long compression = in.integer("compression");
  if (compression != 0 && compression != 1)
    throw Error(path, "unknown SLC compression " + std::to_string(compression));
  const long long icon_w = in.integer("icon width"), icon_h = in.integer("icon height");
  in.separator("icon");
  if (icon_w < 0 || icon_h < 0) throw Error(path, "bad SLC header: negative icon size");
  in.take(std::uint64_t(icon_w) * std::uint64_t(icon_h) * 3, "icon");
  const std::uint64_t count = checked_payload(path, dims, VoxelType::UInt8, path, in.left(),
                                              compression == 1 ? Payload::Compressed : Payload::Raw);

  image.dims = {int(dims[0]), int(dims[1]), int(dims[2])};
  Bytes voxels(count);
  const std::uint64_t plane = std::uint64_t(dims[0]) * std::uint64_t(dims[1]);
  for (long long z = 0; z < dims[2]; ++z) {
    std::uint8_t* out = voxels.data() + std::uint64_t(z) * plane;
    const std::string what = "plane " + std::to_string(z);
    if (compression == 0) {
      const std::uint8_t* p = in.take(plane, what);
      std::copy(p, p + plane, out);
    } else {
      const long long size = in.integer("plane size");
      in.separator("plane size");
      if (size < 0) throw Error(path, "bad SLC header: negative plane size");
      decode_plane(in.take(std::uint64_t(size), what), std::uint64_t(size), out, plane, path, z);
    }
  }
  decode_into(image, std::move(voxels), 0, count, VoxelType::UInt8, false);
  return finish_dense(std::move(image), path, "slc", options);
}

}  // namespace isocurv::volume
