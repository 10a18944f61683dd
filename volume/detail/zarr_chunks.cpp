// Zarr chunk decoding and the parallel region read (zarr_chunks.h).
#include "volume/detail/zarr_chunks.h"

#include <blosc.h>
#include <tbb/parallel_for.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <type_traits>

#include "core/error.h"
#include "volume/file_bytes.h"
#include "volume/large_buffer.h"

namespace isocurv::volume::zarr_detail {
namespace {

using Kind = Codec::Kind;

/// A byte span, owning its storage when a codec produced it.
struct ZarrSpan {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::shared_ptr<Bytes> owner;
};

ZarrSpan zarr_own(Bytes&& b, std::size_t used) {
  auto owner = std::make_shared<Bytes>(std::move(b));
  return ZarrSpan{owner->data(), used, owner};
}

std::string zarr_bytes_text(std::uint64_t n) { return std::to_string(n) + " bytes"; }

ZarrSpan zarr_inflate(const ZarrSpan& in, std::size_t cap, const std::string& name, bool gzip) {
  Bytes out(cap + 1);
  z_stream zs{};
  if (inflateInit2(&zs, gzip ? 15 + 16 : 15) != Z_OK) throw Error(name, "zlib initialisation failed");
  zs.next_in = const_cast<Bytef*>(in.data);
  zs.avail_in = uInt(std::min<std::size_t>(in.size, std::numeric_limits<uInt>::max()));
  zs.next_out = out.data();
  zs.avail_out = uInt(std::min<std::size_t>(out.size(), std::numeric_limits<uInt>::max()));
  int rc = Z_OK;
  while (rc == Z_OK) {
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc == Z_OK && zs.avail_out == 0) break;
    if (rc == Z_OK && zs.avail_in == 0) break;
  }
  const std::size_t produced = zs.total_out;
  inflateEnd(&zs);
  if (produced > cap) throw Error(name, "decoded chunk is larger than the expected " + zarr_bytes_text(cap));
  if (rc != Z_STREAM_END)
    throw Error(name, std::string(gzip ? "gzip" : "zlib") + " data is " + (rc == Z_OK || rc == Z_BUF_ERROR ? "truncated" : "corrupt"));
  return zarr_own(std::move(out), produced);
}

ZarrSpan zarr_unzstd(const ZarrSpan& in, std::size_t cap, const std::string& name) {
  Bytes out(cap + 1);
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  if (!ctx) throw Error(name, "zstd initialisation failed");
  ZSTD_inBuffer src{in.data, in.size, 0};
  ZSTD_outBuffer dst{out.data(), out.size(), 0};
  std::size_t rc = 1;
  while (src.pos < src.size || rc != 0) {
    rc = ZSTD_decompressStream(ctx.get(), &dst, &src);
    if (ZSTD_isError(rc)) throw Error(name, std::string("zstd data is corrupt (") + ZSTD_getErrorName(rc) + ")");
    if (dst.pos > cap) throw Error(name, "decoded chunk is larger than the expected " + zarr_bytes_text(cap));
    if (rc != 0 && src.pos == src.size && dst.pos < dst.size) {
      // All input consumed, the frame not finished, room left: the data is cut short.
      throw Error(name, "zstd data is truncated");
    }
  }
  return zarr_own(std::move(out), dst.pos);
}

ZarrSpan zarr_unblosc(const ZarrSpan& in, std::size_t cap, const std::string& name) {
  std::size_t nbytes = 0;
  if (in.size < 16 || blosc_cbuffer_validate(in.data, in.size, &nbytes) != 0)
    throw Error(name, "blosc data is corrupt or truncated");
  if (nbytes > cap) throw Error(name, "decoded chunk is larger than the expected " + zarr_bytes_text(cap));
  Bytes out(std::max<std::size_t>(nbytes, 1));
  if (nbytes == 0) return zarr_own(std::move(out), 0);
  const int got = blosc_decompress_ctx(in.data, out.data(), nbytes, 1);
  if (got < 0 || std::size_t(got) != nbytes) throw Error(name, "blosc data is corrupt");
  return zarr_own(std::move(out), nbytes);
}

ZarrSpan zarr_check_crc(const ZarrSpan& in, const std::string& name) {
  if (in.size < 4) throw Error(name, "data is shorter than its crc32c checksum");
  std::uint32_t stored = 0;
  for (int i = 0; i < 4; ++i) stored |= std::uint32_t(in.data[in.size - 4 + std::size_t(i)]) << (8 * i);
  if (crc32c(in.data, in.size - 4) != stored) throw Error(name, "crc32c checksum mismatch");
  return ZarrSpan{in.data, in.size - 4, in.owner};
}

/// Undoes the bytes -> bytes codecs after index `first` (in reverse). `expected`: the size the
/// last one must produce (0: unknown, capped at `cap`).
ZarrSpan zarr_undo_bytes_codecs(ZarrSpan data, const std::vector<Codec>& codecs, std::size_t first,
                                std::size_t expected, std::size_t cap, const std::string& name) {
  for (std::size_t i = codecs.size(); i-- > first;) {
    const Codec& c = codecs[i];
    // The size this codec's output must have: known when only checksums lie between it and the
    // array -> bytes codec.
    std::size_t want = expected;
    for (std::size_t k = first; want && k < i; ++k) want = codecs[k].kind == Kind::Crc32c ? want + 4 : 0;
    const std::size_t limit = want ? want : cap;
    switch (c.kind) {
      case Kind::Crc32c: data = zarr_check_crc(data, name); break;
      case Kind::Gzip: data = zarr_inflate(data, limit, name, true); break;
      case Kind::Zlib: data = zarr_inflate(data, limit, name, false); break;
      case Kind::Zstd: data = zarr_unzstd(data, limit, name); break;
      case Kind::Blosc: data = zarr_unblosc(data, limit, name); break;
      default: throw Error(name, "codec '" + c.name + "' in the wrong place");
    }
  }
  return data;
}

struct ZarrCtx {
  const ArrayMeta& meta;
  const Region& region;
  float* out;
};

template <class T>
T zarr_load(const std::uint8_t* p, bool swap) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

/// Copies the elements of a decoded chunk (`shape` at array position `origin`, element i of
/// dimension d at byte offset i * stride[d] * sizeof(T)) that fall in the region to the output.
template <class T>
void zarr_scatter(const ZarrCtx& c, const std::uint8_t* data, bool swap, const std::vector<long long>& shape,
                  const std::vector<long long>& origin, const std::vector<std::int64_t>& stride) {
  const std::size_t n = shape.size();
  std::vector<long long> a(n), b(n);
  for (std::size_t d = 0; d < n; ++d) {
    a[d] = std::max(origin[d], c.region.lo[d]);
    b[d] = std::min(origin[d] + shape[d], c.region.hi[d]);
    if (a[d] >= b[d]) return;
  }
  const std::size_t last = n - 1;
  std::vector<long long> idx(a);
  const std::int64_t ostep = c.region.out_stride[last], sstep = stride[last];
  const long long len = b[last] - a[last];
  while (true) {
    std::int64_t o = 0, s = 0;
    for (std::size_t d = 0; d < n; ++d) {
      o += (idx[d] - c.region.lo[d]) * c.region.out_stride[d];
      s += (idx[d] - origin[d]) * stride[d];
    }
    float* dst = c.out + o;
    const std::uint8_t* src = data + std::size_t(s) * sizeof(T);
    if (!swap && std::is_same<T, float>::value && sstep == 1 && ostep == 1) {
      std::memcpy(dst, src, std::size_t(len) * sizeof(float));
    } else {
      for (long long i = 0; i < len; ++i)
        dst[i * ostep] = float(zarr_load<T>(src + std::size_t(i * sstep) * sizeof(T), swap));
    }
    // Next row: the odometer over every dimension but the last.
    std::size_t d = last;
    while (d-- > 0) {
      if (++idx[d] < b[d]) break;
      idx[d] = a[d];
    }
    if (d == std::size_t(-1)) return;
  }
}

bool zarr_overlaps(const Region& r, const std::vector<long long>& origin, const std::vector<long long>& shape) {
  for (std::size_t d = 0; d < shape.size(); ++d)
    if (origin[d] + shape[d] <= r.lo[d] || origin[d] >= r.hi[d]) return false;
  return true;
}

void zarr_decode(const ZarrCtx& c, ZarrSpan data, const std::vector<Codec>& codecs, const std::vector<long long>& shape,
                 const std::vector<long long>& origin, const std::string& name);

void zarr_decode_shard(const ZarrCtx& c, const ZarrSpan& data, const Codec& sh, const std::vector<long long>& shape,
                       const std::vector<long long>& origin, const std::string& name) {
  const std::size_t n = shape.size();
  std::vector<long long> counts(n);
  std::size_t inner = 1;
  for (std::size_t d = 0; d < n; ++d) {
    counts[d] = shape[d] / sh.inner_chunks[d];
    inner *= std::size_t(counts[d]);
  }
  std::size_t index_size = inner * 16;
  for (const Codec& ic : sh.index_codecs)
    if (ic.kind == Kind::Crc32c) index_size += 4;
  if (data.size < index_size)
    throw Error(name, "shard has " + zarr_bytes_text(data.size) + ", less than its index's " + zarr_bytes_text(index_size));
  ZarrSpan index{data.data + (sh.index_at_end ? data.size - index_size : 0), index_size, data.owner};
  bool big = false;
  std::size_t ab = 0;
  for (std::size_t i = 0; i < sh.index_codecs.size(); ++i)
    if (sh.index_codecs[i].kind == Kind::Bytes) big = sh.index_codecs[i].big_endian, ab = i;
  index = zarr_undo_bytes_codecs(index, sh.index_codecs, ab + 1, inner * 16, inner * 16, name + " (shard index)");
  if (index.size != inner * 16) throw Error(name, "shard index has the wrong size");
  tbb::parallel_for(std::size_t(0), inner, [&](std::size_t k) {
    const std::uint64_t off = zarr_load<std::uint64_t>(index.data + 16 * k, big);
    const std::uint64_t len = zarr_load<std::uint64_t>(index.data + 16 * k + 8, big);
    if (off == ~std::uint64_t(0) && len == ~std::uint64_t(0)) return;  // empty: the fill value
    std::vector<long long> at(n), pos(n);
    std::size_t r = k;
    for (std::size_t d = n; d-- > 0;) {
      at[d] = (long long)(r % std::size_t(counts[d]));
      r /= std::size_t(counts[d]);
      pos[d] = origin[d] + at[d] * sh.inner_chunks[d];
    }
    if (!zarr_overlaps(c.region, pos, sh.inner_chunks)) return;
    std::string inner_name = name + " (inner chunk ";
    for (std::size_t d = 0; d < n; ++d) inner_name += (d ? "," : "") + std::to_string(at[d]);
    inner_name += ")";
    if (off > data.size || len > data.size - off) throw Error(inner_name, "shard index points outside the shard");
    zarr_decode(c, ZarrSpan{data.data + off, std::size_t(len), data.owner}, sh.inner, sh.inner_chunks, pos, inner_name);
  });
}

void zarr_decode(const ZarrCtx& c, ZarrSpan data, const std::vector<Codec>& codecs, const std::vector<long long>& shape,
                 const std::vector<long long>& origin, const std::string& name) {
  std::size_t ab = 0;
  while (ab < codecs.size() && codecs[ab].kind == Kind::Transpose) ++ab;
  const std::size_t item = voxel_size(c.meta.type);
  std::size_t count = 1;
  for (const long long s : shape) count *= std::size_t(s);
  const std::size_t expected = count * item;
  const bool sharded = codecs[ab].kind == Kind::Sharding;
  data = zarr_undo_bytes_codecs(std::move(data), codecs, ab + 1, sharded ? 0 : expected,
                                2 * expected + (std::size_t(1) << 20), name);
  if (sharded) return zarr_decode_shard(c, data, codecs[ab], shape, origin, name);
  if (data.size != expected)
    throw Error(name, "decoded chunk has " + zarr_bytes_text(data.size) + ", expected " + zarr_bytes_text(expected));
  // Strides of the decoded dimensions in the stored (transposed) C-order buffer.
  const std::size_t n = shape.size();
  std::vector<std::vector<long long>> shapes{shape};
  for (std::size_t t = 0; t < ab; ++t) {
    std::vector<long long> next(n);
    for (std::size_t k = 0; k < n; ++k) next[k] = shapes.back()[std::size_t(codecs[t].order[k])];
    shapes.push_back(next);
  }
  std::vector<std::int64_t> stride(n);
  std::int64_t s = 1;
  for (std::size_t k = n; k-- > 0;) {
    stride[k] = s;
    s *= shapes.back()[k];
  }
  for (std::size_t t = ab; t-- > 0;) {  // back through the transposes: dim order[k] of the input is dim k
    std::vector<std::int64_t> prev(n);
    for (std::size_t k = 0; k < n; ++k) prev[std::size_t(codecs[t].order[k])] = stride[k];
    stride = prev;
  }
  const bool swap = item > 1 && codecs[ab].big_endian;  // this machine is little-endian (as OpenVDB's files)
  switch (c.meta.type) {
    case VoxelType::UInt8: zarr_scatter<std::uint8_t>(c, data.data, false, shape, origin, stride); break;
    case VoxelType::Int8: zarr_scatter<std::int8_t>(c, data.data, false, shape, origin, stride); break;
    case VoxelType::UInt16: zarr_scatter<std::uint16_t>(c, data.data, swap, shape, origin, stride); break;
    case VoxelType::Int16: zarr_scatter<std::int16_t>(c, data.data, swap, shape, origin, stride); break;
    case VoxelType::UInt32: zarr_scatter<std::uint32_t>(c, data.data, swap, shape, origin, stride); break;
    case VoxelType::Int32: zarr_scatter<std::int32_t>(c, data.data, swap, shape, origin, stride); break;
    case VoxelType::Float32: zarr_scatter<float>(c, data.data, swap, shape, origin, stride); break;
    case VoxelType::Float64: zarr_scatter<double>(c, data.data, swap, shape, origin, stride); break;
  }
}

}  // namespace

std::uint32_t crc32c(const std::uint8_t* data, std::size_t size) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

std::string chunk_key(const ArrayMeta& meta, const std::vector<long long>& index) {
  std::string key = meta.c_prefix ? "c" : "";
  for (std::size_t d = 0; d < index.size(); ++d) {
    if (!key.empty()) key += meta.separator;
    key += std::to_string(index[d]);
  }
  return key;
}

std::size_t read_region(const ArrayMeta& meta, const Region& region, float* out, std::size_t out_count) {
  std::fill(out, out + out_count, float(meta.fill));
  const std::size_t n = meta.shape.size();
  std::vector<long long> first(n), counts(n);
  std::size_t total = 1;
  for (std::size_t d = 0; d < n; ++d) {
    if (region.hi[d] <= region.lo[d]) return 0;
    first[d] = region.lo[d] / meta.chunks[d];
    counts[d] = (region.hi[d] - 1) / meta.chunks[d] - first[d] + 1;
    total *= std::size_t(counts[d]);
  }
  // No codec here makes a chunk much larger than its decoded bytes (plus a shard's index): a file
  // beyond that is refused before it is read, not allocated.
  std::size_t chunk_elements = 1;
  for (const long long c : meta.chunks) chunk_elements *= std::size_t(c);
  const std::uint64_t largest_file =
      2 * std::uint64_t(chunk_elements) * voxel_size(meta.type) + 16 * std::uint64_t(chunk_elements) + (1u << 20);
  const ZarrCtx ctx{meta, region, out};
  std::atomic<std::size_t> read{0};
  tbb::parallel_for(std::size_t(0), total, [&](std::size_t k) {
    std::vector<long long> index(n), origin(n);
    std::size_t r = k;
    for (std::size_t d = n; d-- > 0;) {
      index[d] = first[d] + (long long)(r % std::size_t(counts[d]));
      r /= std::size_t(counts[d]);
      origin[d] = index[d] * meta.chunks[d];
    }
    const std::string file = meta.dir + "/" + chunk_key(meta, index);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return;  // missing: the fill value
    const std::uint64_t size_on_disk = file_size(file);
    if (size_on_disk > largest_file)
      throw Error(file, "chunk file has " + zarr_bytes_text(size_on_disk) + ", more than a chunk of " +
                            zarr_bytes_text(std::uint64_t(chunk_elements) * voxel_size(meta.type)) + " can take");
    Bytes bytes = read_bytes(file, 0, size_on_disk);
    const std::size_t size = bytes.size();
    read.fetch_add(1, std::memory_order_relaxed);
    zarr_decode(ctx, zarr_own(std::move(bytes), size), meta.codecs, meta.chunks, origin, file);
  });
  return read.load();
}

}  // namespace isocurv::volume::zarr_detail
