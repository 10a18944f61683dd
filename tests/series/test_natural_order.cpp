// core/natural_order.h: digit runs compare as numbers (frame_2 before frame_10).
#include <gtest/gtest.h>

#include "core/natural_order.h"

namespace isocurv {
namespace {

TEST(NaturalOrder, NumbersCompareByValue) {
  EXPECT_TRUE(natural_less("frame_2.nhdr", "frame_10.nhdr"));
  EXPECT_FALSE(natural_less("frame_10.nhdr", "frame_2.nhdr"));
  EXPECT_TRUE(natural_less("a9b", "a10a"));
  EXPECT_TRUE(natural_less("x1y2", "x1y10"));
  EXPECT_TRUE(natural_less("t99999999999999999999", "t100000000000000000000"));  // beyond 64 bits
  EXPECT_TRUE(natural_less("abc", "abd"));
  EXPECT_TRUE(natural_less("frame", "frame_0"));  // a prefix first
  EXPECT_FALSE(natural_less("same", "same"));
}

TEST(NaturalOrder, ZeroPaddingIsStrictAndTotal) {
  // 7 and 007 are the same number: the plain byte order decides, so neither is equivalent.
  EXPECT_NE(natural_less("f_7", "f_007"), natural_less("f_007", "f_7"));
  EXPECT_TRUE(natural_less("f_007", "f_8"));
  EXPECT_TRUE(natural_less("f_7", "f_08"));
}

TEST(NaturalOrder, SortsASeries) {
  std::vector<std::string> names = {"dir/f_10.vdb", "dir/f_2.vdb",  "dir/f_1.vdb",
                                    "dir/f_0.vdb",  "dir/f_11.vdb", "dir/f_9.vdb"};
  natural_sort(names);
  EXPECT_EQ(names, (std::vector<std::string>{"dir/f_0.vdb", "dir/f_1.vdb", "dir/f_2.vdb",
                                             "dir/f_9.vdb", "dir/f_10.vdb", "dir/f_11.vdb"}));
}

}  // namespace
}  // namespace isocurv
