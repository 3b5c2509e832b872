// Particle size distributions for heap insertion: monodisperse, truncated lognormal, or a table.
//
// Lognormal: ln d is normal with standard deviation `sigma` around ln(d50). `d50` is the median
// by number (basis number) or by volume (basis volume, the usual laser-diffraction D50); for a
// lognormal the two differ by exp(3 sigma^2) (Hatch-Choate), so the number median is
// d50 * exp(-3 sigma^2) for a volume D50. Samples outside [d_min, d_max] are redrawn; when
// d_min / d_max are 0 they default to (number median) * exp(-/+ 3 sigma), the central 99.73 %.
// Table: diameters with number or volume fractions (normalised here; volume fractions are turned
// into number fractions by dividing by d^3). A sample of n particles gets the table's counts by
// largest remainder (deterministic), not by random draws.
#pragma once
#include <cstddef>
#include <vector>

#include "scene/scene_error.hpp"
#include "spreadmap/random.hpp"

namespace spreadmap::scene {

enum class SizeKind { monodisperse, lognormal, table };
enum class FractionBasis { number, volume };

struct SizeDistribution {
  SizeKind kind = SizeKind::monodisperse;
  double diameter = 250e-6;                     // monodisperse [m]
  double d50 = 250e-6;                          // lognormal median [m], by `basis`
  double sigma = 0.0;                           // lognormal: standard deviation of ln d [-]
  double d_min = 0.0, d_max = 0.0;              // lognormal truncation [m]; 0 = median * exp(-/+3 sigma)
  FractionBasis basis = FractionBasis::number;  // of d50 (lognormal) or of fractions (table)
  std::vector<double> diameters, fractions;     // table [m], [-]

  static SizeDistribution monodisperse(double d);
  static SizeDistribution lognormal(double d50, double sigma, FractionBasis basis = FractionBasis::number,
                                    double d_min = 0.0, double d_max = 0.0);
  static SizeDistribution table(std::vector<double> diameters, std::vector<double> fractions,
                                FractionBasis basis = FractionBasis::number);

  // Throws SceneError naming the offending value.
  void validate() const;
  double number_median() const;       // lognormal: median by number [m]
  double lower() const;               // smallest possible diameter [m]
  double upper() const;               // largest possible diameter [m]
  double mean_sphere_volume() const;  // expected pi d^3 / 6 per particle [m^3] (exact, truncation included)
  // n diameters [m], in draw order (deterministic for the generator's state).
  std::vector<double> sample(std::size_t n, Random &random) const;
};

}  // namespace spreadmap::scene
