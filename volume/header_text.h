#pragma once
// Small strict parsers for the text headers of NRRD, MetaImage and DGtal VOL files.
// Tested through the header readers: tests/volume/test_loaders.cpp,
// tests/volume/test_bad_input.cpp.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "volume/large_buffer.h"

namespace isocurv::volume {

/// `s` without leading and trailing whitespace.
std::string trim(const std::string& s);
/// ASCII lower case.
std::string to_lower(std::string s);
/// Whitespace-separated numbers; nullopt if any token is not a number (or there is none).
std::optional<std::vector<double>> parse_numbers(const std::string& s);
/// Exactly `n` numbers, else throws Error(path, "bad <what> '<s>'").
std::vector<double> parse_numbers_exact(const std::string& path, const std::string& s, std::size_t n,
                                        const std::string& what);
/// Exactly `n` integers, each written as one (digits with an optional sign: "41.0", "4e1" and
/// "0x29" are refused), else throws Error(path, "bad <what> '<s>'").
std::vector<long long> parse_integers_exact(const std::string& path, const std::string& s, std::size_t n,
                                            const std::string& what);
/// Parses `count` whitespace-separated numbers of an ASCII payload; throws when there are fewer
/// or more, a token is not a number, or the last one is not followed by whitespace (a file cut
/// inside its last number would otherwise read as a shorter number).
LargeBuffer<float> parse_ascii_voxels(const std::string& path, const char* begin, const char* end,
                                      std::uint64_t count);
/// Directory of `path` (for data files named relative to their header).
std::string directory_of(const std::string& path);

}  // namespace isocurv::volume
