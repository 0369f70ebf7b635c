// Numbers in messages: exact where the user typed them, rough where they are estimates.
#pragma once

#include <string>

namespace nmm {

/// Shortest text that reads back as the same double: "0.001", "1e+10", "0.49999999", "inf".
std::string format_number(double v);

/// printf-style "%.<digits>g", for rough figures such as an estimated triangle count.
std::string format_rough(double v, int digits);

/// printf-style "%.<decimals>f", for table columns with a fixed number of decimals ("0.0413").
std::string format_fixed(double v, int decimals);

/// printf-style "%+.<decimals>f": a change or an error, its sign always written ("+0.64").
std::string format_signed(double v, int decimals);

/// printf-style "%.<digits − 1>e": `digits` significant digits, always with an exponent
/// ("8.894473e-02", "1e+04").
std::string format_scientific(double v, int digits);

/// Engineering notation for reports: `digits` significant digits, the exponent a multiple of 3
/// carried by an SI prefix on `unit` ("5.58 s", "120 µm", "10 GN/m"), from p (10⁻¹²) to T
/// (10¹²), the exponent written out beyond them ("4.94e-324 J/m"); without a unit the exponent
/// is written out ("1.23e+09") outside [0.001, 10⁶). Subnormal values too. Zero is "0 unit";
/// "inf", "-inf" and "nan" (whatever its sign bit) as such, with the unit.
std::string format_engineering(double v, const std::string& unit, int digits = 3);

}  // namespace nmm
