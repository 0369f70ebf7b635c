// The printf-style formats of common/number_format.h that tables, pictures and messages share.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "common/number_format.h"

namespace nmm {
namespace {

TEST(NumberFormat, FixedSignedAndScientificAsPrintf) {
  EXPECT_EQ(format_fixed(0.041349, 4), "0.0413");
  EXPECT_EQ(format_fixed(2.5, 0), "2");  // round half to even, as printf
  EXPECT_EQ(format_fixed(-0.1, 2), "-0.10");
  EXPECT_EQ(format_signed(0.636, 2), "+0.64");
  EXPECT_EQ(format_signed(-2.43, 3), "-2.430");
  EXPECT_EQ(format_scientific(0.08894473, 7), "8.894473e-02");
  EXPECT_EQ(format_scientific(12345, 1), "1e+04");
  EXPECT_EQ(format_scientific(std::numeric_limits<double>::infinity(), 3), "inf");
  // Every integer digit, not a truncated buffer: 309 digits, the point and two decimals.
  EXPECT_EQ(format_fixed(std::numeric_limits<double>::max(), 2).size(), 312u);
}

TEST(NumberFormat, ShortestAndRough) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(-0.0), "-0");
  EXPECT_EQ(format_rough(1e-6, 6), "1e-06");
  EXPECT_EQ(format_rough(0.25, 6), "0.25");
}

}  // namespace
}  // namespace nmm
