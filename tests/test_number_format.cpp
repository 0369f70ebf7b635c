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

TEST(NumberFormat, EngineeringOfEveryDouble) {
  // The SI prefixes as the reports use them.
  EXPECT_EQ(format_engineering(5.576478281, "s"), "5.58 s");
  EXPECT_EQ(format_engineering(999.7, "m"), "1 km");  // the prefix of the rounded value
  EXPECT_EQ(format_engineering(-2.5e-11, "m"), "-25 pm");
  // Beyond p and T the exponent is written out, not a mantissa of 10⁻³⁰⁰ on "p".
  EXPECT_EQ(format_engineering(3e-15, "m"), "3.00e-15 m");
  EXPECT_EQ(format_engineering(4.2e15, "J"), "4.20e+15 J");
  // Subnormal values (below 2.2e-308): std::stod threw std::out_of_range on them.
  const double tiny = std::numeric_limits<double>::denorm_min();  // 4.94e-324
  EXPECT_EQ(format_engineering(tiny, "J/m"), "4.94e-324 J/m");
  EXPECT_EQ(format_engineering(-tiny, "J/m"), "-4.94e-324 J/m");
  EXPECT_EQ(format_engineering(tiny, ""), "4.94e-324");
  EXPECT_EQ(format_engineering(1e-310, "s", 2), "1.0e-310 s");
  EXPECT_EQ(format_engineering(std::numeric_limits<double>::min() / 2, ""), "1.11e-308");
  // Zero, infinities and NaN, with the unit; NaN without a sign, whatever its sign bit.
  EXPECT_EQ(format_engineering(-0.0, "s"), "0 s");
  EXPECT_EQ(format_engineering(std::numeric_limits<double>::infinity(), "s"), "inf s");
  EXPECT_EQ(format_engineering(-std::numeric_limits<double>::infinity(), ""), "-inf");
  EXPECT_EQ(format_engineering(std::numeric_limits<double>::quiet_NaN(), "m"), "nan m");
  EXPECT_EQ(format_engineering(-std::numeric_limits<double>::quiet_NaN(), "m"), "nan m");
}

}  // namespace
}  // namespace nmm
