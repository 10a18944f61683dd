#pragma once
// Device buffers kept between calls, so repeated extractions (the explorer's slider) and repeated
// estimates do not pay for fresh memory each time. On CPU devices they are backed by host memory,
// in huge pages from 128 KiB up (first-touching small pages is slow on virtual machines; below
// that, one huge page's zeroing costs more than the small pages).
// Tested through its users: every device stage (tests/mc/extract_test.cpp reuses one device's
// buffers across extractions).
#include <memory>
#include <vector>

#include "core/cl_device.h"

namespace isocurv {

/// The slots of a device's shared scratch buffers, Device::scratch() (one owner each). Other stages
/// keep a ScratchBuffers of their own, with their own slots, in their Device::state<T>().
enum ScratchSlot : std::size_t {
  kScanTotals, kScanTotal, kRadixHistogram, kRadixKeys, kRadixValues,
  kMcSamples, kMcCounts, kMcOrigins, kMcCases, kMcRowRanks, kMcTriangleOffsets, kMcVertexOffsets,
  kMcSeamOffsets, kMcPositions, kMcKeys, kMcHashes, kMcOrder, kMcSeamVertices, kMcSeamKeys,
  kMcTableHashes, kMcTableVertices, kMcTableKeys, kMcBucketStarts, kMcTriangles, kMcSnapCount,
  kMcSnapEdges, kMcSnapVertices, kMcEmitParams,
  kScratchSlots
};

/// Reusable device buffers by slot. Not thread-safe: like the device's queue, one user at a time.
class ScratchBuffers {
 public:
  /// `slots` buffers, all empty; the default is the shared set of ScratchSlot.
  explicit ScratchBuffers(Device& device, std::size_t slots = kScratchSlots)
      : device_(device), slots_(slots) {}
  ~ScratchBuffers();
  ScratchBuffers(const ScratchBuffers&) = delete;
  ScratchBuffers& operator=(const ScratchBuffers&) = delete;

  /// Buffer `slot` (< the number of slots) with room for at least `bytes` (grown by half again when too small;
  /// contents are not preserved across growth, which first waits for the device's queue to drain).
  /// Valid until the next get() of the same slot.
  cl::Buffer& get(std::size_t slot, std::size_t bytes);

 private:
  struct Slot {
    cl::Buffer buffer;
    void* host = nullptr;
    std::size_t bytes = 0;
  };
  Device& device_;
  std::vector<Slot> slots_;
};

}  // namespace isocurv
