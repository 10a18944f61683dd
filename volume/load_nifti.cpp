// NIfTI-1 single files (.nii, .nii.gz), either byte order. Geometry: the sform when its code is
// set, else the qform (its quaternion normalised as nifti1_io.c does), else pixdim spacing at the
// origin. scl_slope/scl_inter are applied (when the slope is finite and non-zero and the
// intercept finite, as NIfTI says): scaled values are real values, even where they make the
// integers of an integer-typed file non-integer (Volume::voxel_type stays the type on disk;
// labels::label_map_labels refuses such a map, naming the scaling).
// A plain .nii honours LoadOptions::z_slab: file slice k is always index z k (orientation lives
// in the transform only, and finish_dense's flip of a left-handed frame reverses X alone), and
// the scaling is per voxel. A .nii.gz is read whole.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

constexpr std::size_t kHeaderSize = 348;

/// Reads fields of the 348-byte header in its byte order.
struct HeaderView {
  const std::uint8_t* h;
  bool swap;
  template <class T>
  T get(std::size_t offset) const {
    std::uint8_t b[sizeof(T)];
    std::memcpy(b, h + offset, sizeof(T));
    if (swap)
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  std::int16_t i16(std::size_t o) const { return get<std::int16_t>(o); }
  float f32(std::size_t o) const { return get<float>(o); }
};

std::optional<VoxelType> nifti_type(int code) {
  switch (code) {
    case 2: return VoxelType::UInt8;
    case 4: return VoxelType::Int16;
    case 8: return VoxelType::Int32;
    case 16: return VoxelType::Float32;
    case 64: return VoxelType::Float64;
    case 256: return VoxelType::Int8;
    case 512: return VoxelType::UInt16;
    case 768: return VoxelType::UInt32;
    default: return std::nullopt;
  }
}

}  // namespace

Volume load_nifti(const std::string& path, const LoadOptions& options) {
  const std::uint64_t file_bytes = file_size(path);
  GzipReader in(path);  // reads plain files transparently
  std::uint8_t raw[kHeaderSize];
  in.read_exact(raw, kHeaderSize, "NIfTI header");

  std::int32_t sizeof_hdr;
  std::memcpy(&sizeof_hdr, raw, 4);
  bool swap = false;
  if (sizeof_hdr != 348) {
    HeaderView probe{raw, true};
    if (probe.get<std::int32_t>(0) != 348) throw Error(path, "not a NIfTI-1 file (sizeof_hdr is not 348)");
    swap = true;
  }
  const HeaderView h{raw, swap};
  if (std::memcmp(raw + 344, "n+1", 4) != 0)
    throw Error(path, std::memcmp(raw + 344, "ni1", 4) == 0 ? "NIfTI header/image pairs (.hdr/.img) are not supported"
                                                            : "not a NIfTI-1 single file (magic is not n+1)");
  const int ndim = h.i16(40);
  if (ndim < 3 || ndim > 7) throw Error(path, "only 3-D NIfTI images are supported (dim[0] = " + std::to_string(ndim) + ")");
  for (int i = 4; i <= ndim; ++i)
    if (h.i16(40 + 2 * std::size_t(i)) > 1) throw Error(path, "only 3-D NIfTI images are supported (dim[" + std::to_string(i) + "] > 1)");
  const std::array<long long, 3> dims{h.i16(42), h.i16(44), h.i16(46)};
  const int datatype = h.i16(70);
  const auto type = nifti_type(datatype);
  if (!type) throw Error(path, "unsupported NIfTI datatype " + std::to_string(datatype));
  const float vox_offset_f = h.f32(108);
  if (!(vox_offset_f >= float(kHeaderSize)) || vox_offset_f > 1e9f) throw Error(path, "bad vox_offset");
  const std::uint64_t vox_offset = std::uint64_t(vox_offset_f);
  // The dimensions must fit the data before anything is allocated: a plain file holds the voxels
  // after vox_offset, a gzip one (magic 1f 8b) can inflate to at most ~1000 times its size.
  const Bytes magic = read_bytes(path, 0, 2);
  const bool gz = magic[0] == 0x1f && magic[1] == 0x8b;
  if (!gz && vox_offset > file_bytes)
    throw Error(path, "vox_offset " + std::to_string(vox_offset) + " is past the end of the file (" +
                          std::to_string(file_bytes) + " bytes)");
  const std::uint64_t count = checked_payload(path, dims, *type, path, gz ? file_bytes : file_bytes - vox_offset,
                                              gz ? Payload::Compressed : Payload::Raw);
  const std::uint64_t bytes_needed = count * voxel_size(*type);

  DenseImage image;
  image.dims = {int(dims[0]), int(dims[1]), int(dims[2])};
  const float qfac = h.f32(76) < 0 ? -1.0f : 1.0f;
  const int qform_code = h.i16(252), sform_code = h.i16(254);
  // pixdim[1..3] is the spacing unless the sform gives it: kept as written, so finish_dense
  // refuses 0 and non-finite values (they once became 1) and takes a negative one as a flip
  // (world = ... + index * pixdim * axis), as every format does.
  for (std::size_t i = 0; i < 3; ++i) image.spacing[i] = h.f32(80 + 4 * i);
  if (sform_code > 0) {
    // srow_{x,y,z}: world_r = sum_i srow_r[i] * index_i + srow_r[3]; column i is index axis i.
    double m[3][4];
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t c = 0; c < 4; ++c) m[r][c] = h.f32(280 + 16 * r + 4 * c);
    for (std::size_t i = 0; i < 3; ++i) {
      const double len = std::sqrt(m[0][i] * m[0][i] + m[1][i] * m[1][i] + m[2][i] * m[2][i]);
      if (!(len > 0) || !std::isfinite(len)) throw Error(path, "degenerate sform matrix");
      image.spacing[i] = len;
      for (std::size_t r = 0; r < 3; ++r) image.axes[i][r] = m[r][i] / len;
    }
    image.origin = {m[0][3], m[1][3], m[2][3]};
  } else if (qform_code > 0) {
    double b = h.f32(256), c = h.f32(260), d = h.f32(264);
    if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d))
      throw Error(path, "bad qform quaternion (quatern_b, c or d is not a finite number)");
    // As nifti1_io.c's nifti_quatern_to_mat44: a = sqrt(1 - b^2 - c^2 - d^2), and when that is
    // (nearly) zero or negative, (b, c, d) is normalised and a = 0 (a half turn). Taking a = 0
    // without normalising once gave a matrix of columns |b,c,d|^2 long: pixdim 1 read as 3.
    double a = 1.0 - (b * b + c * c + d * d);
    if (a < 1e-7) {
      const double len = std::sqrt(b * b + c * c + d * d);
      b /= len;
      c /= len;
      d /= len;
      a = 0;
    } else {
      a = std::sqrt(a);
    }
    const double R[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                            {2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b)},
                            {2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b}};
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t r = 0; r < 3; ++r) image.axes[i][r] = R[r][i] * (i == 2 ? qfac : 1.0f);
    image.origin = {h.f32(268), h.f32(272), h.f32(276)};
  }

  const std::uint16_t one = 1;
  std::uint8_t low_byte;
  std::memcpy(&low_byte, &one, 1);
  const bool file_big_endian = swap != (low_byte == 0);  // swapped relative to the host's order
  if (gz) {
    in.skip(std::size_t(vox_offset - kHeaderSize), "NIfTI extension");
    Bytes bytes(bytes_needed);
    in.read_exact(bytes.data(), bytes.size(), "voxel data");
    // Read a .nii.gz to its end, so that zlib checks the gzip trailer (CRC-32 and length): a stream
    // cut before it, or corrupt after the voxels, is refused. Bytes after the voxels are allowed.
    std::vector<char> rest(1 << 16);
    while (in.read(rest.data(), rest.size()) == rest.size()) {
    }
    decode_into(image, std::move(bytes), 0, count, *type, file_big_endian);
  } else {
    // checked_payload saw the whole payload after vox_offset; bytes after the voxels are allowed.
    read_uncompressed(image, path, vox_offset, *type, file_big_endian, options);  // all, or LoadOptions::z_slab
  }

  const float slope = h.f32(112), inter = h.f32(116);
  if (std::isfinite(slope) && slope != 0 && std::isfinite(inter) && !(slope == 1 && inter == 0)) {
    ensure_float(image);
    float* v = image.values.data();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, image.values.size(), 1 << 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) v[i] = slope * v[i] + inter;
                      });
  }
  Volume v = finish_dense(std::move(image), path, "nifti", options);
  v.world_space = "RAS";
  switch (raw[123] & 0x07) {  // xyzt_units, spatial bits (one byte: no byte order)
    case 1: v.length_unit = "m"; break;
    case 2: v.length_unit = "mm"; break;
    case 3: v.length_unit = "um"; break;
    default: break;  // 0: unknown
  }
  return v;
}

}  // namespace isocurv::volume
