#include "core/cl_radix_sort.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/cl_launch.h"
#include "core/cl_scan.h"
#include "core/cl_scratch.h"
#include "core/error.h"

namespace isocurv {
namespace kernels {
extern const char* const radix_sort_cl;
}

namespace {
constexpr std::size_t kSortChunkGroup = 1;  // a chunk per work group: PoCL runs a group on one thread
constexpr int kMaxRadixBits = 11;       // widest digit, radix_sort.cl's MAX_RADIX_BITS
}  // namespace

void enqueue_radix_sort_pairs(Device& dev, cl::Buffer& keys, cl::Buffer& values, std::uint32_t n, int key_bits) {
  if (key_bits < 1 || key_bits > 32) throw Error("radix sort: key_bits must be 1..32");
  if (n < 2) return;
  cl::Program& prog =
      dev.program("radix_sort", kernels::radix_sort_cl, "-DMAX_RADIX_BITS=" + std::to_string(kMaxRadixBits));
  // As few passes as digits of up to kMaxRadixBits allow, the bits shared evenly between them.
  const int passes = (key_bits + kMaxRadixBits - 1) / kMaxRadixBits;
  const int digit_bits = (key_bits + passes - 1) / passes;
  const std::uint32_t radix = 1u << digit_bits;
  // Chunks of 16k keys or more (up to 64 chunks): the histograms cost less than the keys.
  const std::uint32_t p = std::clamp<std::uint32_t>(n / 16384, 1, 64);
  const std::uint32_t chunk = (n + p - 1) / p;
  cl::Buffer& hist = dev.scratch().get(kRadixHistogram, sizeof(std::uint32_t) * radix * p);
  cl::Buffer& keys2 = dev.scratch().get(kRadixKeys, sizeof(std::uint32_t) * n);
  cl::Buffer& values2 = dev.scratch().get(kRadixValues, sizeof(std::uint32_t) * n);
  cl::Kernel &kh = dev.kernel(prog, "radix_histogram"), &ks = dev.kernel(prog, "radix_scatter");
  cl::Buffer *src_k = &keys, *src_v = &values, *dst_k = &keys2, *dst_v = &values2;
  const cl_uint bits = static_cast<cl_uint>(digit_bits);
  for (int pass = 0; pass < passes; ++pass) {
    const std::uint32_t shift = digit_bits * pass;
    set_args(kh, *src_k, n, chunk, shift, bits, p, hist);
    launch(dev.queue(), kh, p, kSortChunkGroup);
    enqueue_exclusive_scan(dev, hist, hist, radix * p);
    set_args(ks, *src_k, *src_v, n, chunk, shift, bits, p, hist, *dst_k, *dst_v);
    launch(dev.queue(), ks, p, kSortChunkGroup);
    std::swap(src_k, dst_k);
    std::swap(src_v, dst_v);
  }
  if (src_k != &keys) {  // odd number of passes: copy the result home
    dev.queue().enqueueCopyBuffer(*src_k, keys, 0, 0, sizeof(std::uint32_t) * n);
    dev.queue().enqueueCopyBuffer(*src_v, values, 0, 0, sizeof(std::uint32_t) * n);
  }
}

}  // namespace isocurv
