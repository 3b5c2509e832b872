// Particle size distributions for heap insertion: monodisperse, truncated lognormal, truncated
// normal, or a table of sizes or size classes.
//
// Basis. A distribution is stated by number or by volume (= by mass, one density): D50 by volume
// is the diameter below which half the powder's volume lies (what laser diffraction and sieves
// report); by number, half the particles. The heap always samples particles, i.e. by number: a
// volume density n_v(d) becomes the number density n_v(d) / d^3.
//
// Lognormal: ln d is normal with standard deviation `sigma` around ln(d50) in the stated basis. By
// number and by volume it is lognormal with the same sigma, the medians differing by exp(3 sigma^2)
// (Hatch-Choate): a volume D50 has the number median d50 * exp(-3 sigma^2).
// Normal: d is normal with mean (= median) d50 and standard deviation `standard_deviation` in the
// stated basis; by volume, the number density is that normal divided by d^3.
// Truncation: the distribution is conditioned on [d_min, d_max] (samples outside are redrawn, so
// nothing piles up at the bounds; cdf and quantile below include it). 0 means the default, the
// central 99.73 % in the stated basis: median * exp(-/+3 sigma) (lognormal), d50 -/+ 3 standard
// deviations (normal, whose lower bound must then be > 0). The range must contain d50.
// Table: rows with a fraction each, in the stated basis, normalised here. A row is a size class
// [from, to] within which the stated basis is uniform in ln d (a sieve class), or one diameter
// (from == to). By number a volume class weighs its fraction times its mean of d^-3. A sample of n
// particles gets the classes' counts by largest remainder (deterministic), not by random draws;
// within a class the diameter is drawn.
#pragma once
#include <cstddef>
#include <numbers>
#include <vector>

#include "powder/powder_error.hpp"
#include "spreadmap/random.hpp"
#include "spreadmap/sphere.hpp"

namespace spreadmap::powder {

enum class SizeKind { monodisperse, lognormal, normal, table };
enum class FractionBasis { number, volume };

struct SizeDistribution {
  SizeKind kind = SizeKind::monodisperse;
  double diameter = 250e-6;                     // monodisperse [m]
  double d50 = 250e-6;                          // lognormal median, normal mean [m], by `basis`
  double sigma = 0.0;                           // lognormal: standard deviation of ln d [-]
  double standard_deviation = 0.0;              // normal: standard deviation of d [m]
  double d_min = 0.0, d_max = 0.0;              // truncation [m]; 0 = the default (above)
  FractionBasis basis = FractionBasis::number;  // of d50 or of the table's fractions
  std::vector<double> from, to, fractions;      // table: class edges [m] (equal: one diameter), [-]

  static SizeDistribution monodisperse(double d);
  static SizeDistribution lognormal(double d50, double sigma, FractionBasis basis = FractionBasis::number,
                                    double d_min = 0.0, double d_max = 0.0);
  static SizeDistribution normal(double mean, double standard_deviation, FractionBasis basis = FractionBasis::number,
                                 double d_min = 0.0, double d_max = 0.0);
  static SizeDistribution table(std::vector<double> diameters, std::vector<double> fractions,
                                FractionBasis basis = FractionBasis::number);
  static SizeDistribution classes(std::vector<double> from, std::vector<double> to, std::vector<double> fractions,
                                  FractionBasis basis = FractionBasis::number);

  // Throws PowderError naming the offending value.
  void validate() const;
  double number_median() const;       // lognormal: median by number before truncation [m]
  double lower() const;               // smallest possible diameter [m]
  double upper() const;               // largest possible diameter [m]
  double mean_sphere_volume() const;  // expected pi d^3 / 6 per particle [m^3] (truncation included)
  // Share of the particles (by number) or of their volume (by volume) with a diameter <= d.
  double cdf(double d, FractionBasis by) const;
  // The diameter below which a share p in (0, 1) lies, by number or by volume: quantile(0.5,
  // volume) is D50 by volume of what sample() draws (truncation included).
  double quantile(double p, FractionBasis by) const;
  // n diameters [m] (deterministic for the generator's state).
  std::vector<double> sample(std::size_t n, Random &random) const;
};

}  // namespace spreadmap::powder
