// The device exclusive scan and radix sort against their plain C++ references
// (std::exclusive_scan, std::stable_sort), at sizes around their chunk boundaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/cl_device.h"
#include "core/cl_radix_sort.h"
#include "core/cl_scan.h"

namespace isocurv {
namespace {

std::vector<std::uint32_t> random_values(std::size_t n, std::uint32_t mask, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> v(n);
  for (auto& x : v) x = rng() & mask;
  return v;
}

cl::Buffer upload(Device& dev, const std::vector<std::uint32_t>& v) {
  cl::Buffer b(dev.context(), CL_MEM_READ_WRITE, std::max<std::size_t>(v.size(), 1) * sizeof(std::uint32_t));
  if (!v.empty()) dev.queue().enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(std::uint32_t), v.data());
  return b;
}

std::vector<std::uint32_t> download(Device& dev, const cl::Buffer& b, std::size_t n) {
  std::vector<std::uint32_t> v(n);
  if (n) dev.queue().enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(std::uint32_t), v.data());
  return v;
}

class ScanSortSizes : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ScanSortSizes, ExclusiveScanMatchesStd) {
  Device& dev = Device::default_device();
  const std::size_t n = GetParam();
  const auto in = random_values(n, 0xff, 7u + unsigned(n));
  std::vector<std::uint32_t> want(n);
  std::exclusive_scan(in.begin(), in.end(), want.begin(), std::uint32_t(0));
  const std::uint32_t want_total = std::accumulate(in.begin(), in.end(), std::uint32_t(0));
  cl::Buffer b = upload(dev, in);
  const std::uint32_t total = exclusive_scan(dev, b, b, static_cast<std::uint32_t>(n));  // in place
  EXPECT_EQ(total, want_total);
  EXPECT_EQ(download(dev, b, n), want);
}

TEST_P(ScanSortSizes, RadixSortIsAStableSortByTheKey) {
  Device& dev = Device::default_device();
  const std::size_t n = GetParam();
  for (int bits : {5, 11, 16, 22, 23, 32}) {  // one, two and three passes of 5 to 11 bits
    const std::uint32_t mask = bits == 32 ? 0xffffffffu : (1u << bits) - 1u;
    // Few distinct keys for narrow widths: many ties, so stability is tested.
    const auto keys = random_values(n, mask, 11u + unsigned(n) + unsigned(bits));
    std::vector<std::uint32_t> values(n);
    std::iota(values.begin(), values.end(), 0u);
    std::vector<std::uint32_t> order = values;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    std::vector<std::uint32_t> want_keys(n);
    for (std::size_t i = 0; i < n; ++i) want_keys[i] = keys[order[i]];
    cl::Buffer k = upload(dev, keys), v = upload(dev, values);
    enqueue_radix_sort_pairs(dev, k, v, static_cast<std::uint32_t>(n), bits);
    EXPECT_EQ(download(dev, k, n), want_keys) << bits << " bits";
    EXPECT_EQ(download(dev, v, n), order) << bits << " bits";
  }
}

INSTANTIATE_TEST_SUITE_P(Core, ScanSortSizes, ::testing::Values(0, 1, 2, 511, 512, 513, 8191, 8192, 16383, 16385, 70001, 600000));

TEST(ExclusiveScan, MoreElementsThanItsChunksHoldAtTheMinimumChunkSize) {
  // Past 4096 chunks of 512 the chunks grow; the last ones may be empty.
  Device& dev = Device::default_device();
  const std::size_t n = 3'000'001;
  const auto in = random_values(n, 0x3, 5);
  std::vector<std::uint32_t> want(n);
  std::exclusive_scan(in.begin(), in.end(), want.begin(), std::uint32_t(0));
  cl::Buffer b = upload(dev, in), out(dev.context(), CL_MEM_READ_WRITE, n * sizeof(std::uint32_t));
  EXPECT_EQ(exclusive_scan(dev, b, out, static_cast<std::uint32_t>(n)), want.back() + in.back());
  EXPECT_EQ(download(dev, out, n), want);
}

TEST(ExclusiveScan, EnqueuedScansOfDifferentSizesLeaveTheirTotalsInOneBuffer) {
  // Queued back to back (sizes that need different chunk counts, and an empty one), each total
  // lands in its own slot of the result buffer; the slots around them are left alone.
  Device& dev = Device::default_device();
  const std::vector<std::size_t> sizes{70001, 0, 513, 600000};
  std::vector<std::vector<std::uint32_t>> in;
  std::vector<cl::Buffer> buffers;
  cl::Buffer totals = upload(dev, std::vector<std::uint32_t>(sizes.size() + 2, 0xdeadbeefu));
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    in.push_back(random_values(sizes[i], 0xff, 40u + unsigned(i)));
    buffers.push_back(upload(dev, in.back()));
    enqueue_exclusive_scan(dev, buffers.back(), buffers.back(), static_cast<std::uint32_t>(sizes[i]), &totals,
                           static_cast<std::uint32_t>(i + 1));
  }
  const auto got = download(dev, totals, sizes.size() + 2);
  EXPECT_EQ(got.front(), 0xdeadbeefu);
  EXPECT_EQ(got.back(), 0xdeadbeefu);
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(got[i + 1], std::accumulate(in[i].begin(), in[i].end(), std::uint32_t(0))) << sizes[i];
    std::vector<std::uint32_t> want(sizes[i]);
    std::exclusive_scan(in[i].begin(), in[i].end(), want.begin(), std::uint32_t(0));
    EXPECT_EQ(download(dev, buffers[i], sizes[i]), want) << sizes[i];
  }
}

TEST(RadixSort, RejectsKeyWidthsOutside1To32) {
  Device& dev = Device::default_device();
  cl::Buffer k = upload(dev, {3, 1, 2}), v = upload(dev, {0, 1, 2});
  EXPECT_ANY_THROW(enqueue_radix_sort_pairs(dev, k, v, 3, 0));
  EXPECT_ANY_THROW(enqueue_radix_sort_pairs(dev, k, v, 3, 33));
}

}  // namespace
}  // namespace isocurv
