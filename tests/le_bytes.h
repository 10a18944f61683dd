#pragma once
// Bytes of a value in the machine's (little-endian) order, for tests that write binary files by
// hand (the readers' honesty tests).
#include <cstring>
#include <string>

namespace isocurv::test {

/// The sizeof(T) bytes of `v` as they lie in memory (little-endian on every machine we build on).
template <class T>
std::string le(T v) {
  std::string out(sizeof(T), '\0');
  std::memcpy(out.data(), &v, sizeof(T));
  return out;
}

}  // namespace isocurv::test
