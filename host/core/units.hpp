// Physical quantities as users write them: "250 um", "250um", "100 mm/s", "-20 rad/s",
// "4430 kg/m^3", "9.81 m/s^2". Bare numbers are SI. Angles are dimensionless (rad = 1).
#pragma once
#include <array>
#include <optional>
#include <string>

namespace spreadmap {

// Exponents of length, mass and time.
struct Dimension {
  std::array<int, 3> e{0, 0, 0};
  bool operator==(const Dimension &) const = default;
  std::string str() const;  // "m/s", "kg/m^3", "1" for dimensionless
};

// To SI: value * 10^pow10 * factor. Decimal prefixes and g, t, % live in pow10 so that "2.5 um" is
// computed as 2.5 / 1e6, one correctly rounded division, and equals the double of "2.5e-6" exactly.
struct Unit {
  double factor = 1.0;  // the non-decimal part (deg, rpm, min, h)
  int pow10 = 0;
  Dimension dim;
  double to_si(double value) const;
};

// Parses a unit expression ("mm/s", "kg/m^3", "1/s", "-"); nullopt when unknown. `why` says which
// part was not understood.
std::optional<Unit> parse_unit(const std::string &text, std::string *why = nullptr);

struct Quantity {
  double value = 0;  // in SI
  bool has_unit = false;
  Unit unit;
};

// "250 um" → 2.5e-4. Throws std::invalid_argument with a sentence on malformed input, unknown unit,
// NaN or infinity.
Quantity parse_quantity(const std::string &text);

// Convenience: parses and converts to the SI unit `si_unit`, checking the dimension; bare numbers
// are taken as SI. Throws std::invalid_argument naming both units on a dimension mismatch.
double parse_in(const std::string &text, const std::string &si_unit);

// A value with its SI unit in the form spreading is read in: 3.3e-05 m^2/s -> "33 mm^2/s",
// 1.1e-4 m -> "110 um" (4 significant digits).
std::string display(double value, const std::string &unit);

}  // namespace spreadmap
