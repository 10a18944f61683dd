#pragma once
// An uninitialised heap array for voxel payloads. Unlike std::vector it does not zero its memory,
// and arrays of 2 MiB or more are placed on transparent huge pages where the OS offers them
// (Linux madvise): touching fresh memory page by page costs more than decoding into it.
// Tested in tests/volume/test_bad_input.cpp, tests/volume/test_loaders.cpp (through its users).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace isocurv::volume {

/// Raw allocation behind LargeBuffer (huge-page advised when large); throws std::bad_alloc.
void* allocate_large(std::size_t bytes);
void free_large(void* p) noexcept;

template <class T>
class LargeBuffer {
  static_assert(std::is_trivially_copyable_v<T>, "LargeBuffer holds plain values");

 public:
  LargeBuffer() = default;
  explicit LargeBuffer(std::size_t n) : data_(n ? static_cast<T*>(allocate_large(n * sizeof(T))) : nullptr), size_(n) {}
  LargeBuffer(LargeBuffer&& o) noexcept : data_(o.data_), size_(o.size_) { o.data_ = nullptr, o.size_ = 0; }
  LargeBuffer& operator=(LargeBuffer&& o) noexcept {
    if (this != &o) {
      free_large(data_);
      data_ = o.data_, size_ = o.size_;
      o.data_ = nullptr, o.size_ = 0;
    }
    return *this;
  }
  LargeBuffer(const LargeBuffer&) = delete;
  LargeBuffer& operator=(const LargeBuffer&) = delete;
  ~LargeBuffer() { free_large(data_); }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

using Bytes = LargeBuffer<std::uint8_t>;

}  // namespace isocurv::volume
