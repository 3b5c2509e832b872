#include <engine/stability.hpp>

#include <cmath>
#include <limits>

namespace spreadmap::engine {

double stable_omega_dt(double zeta) {
  zeta = zeta > 0 ? zeta : 0;
  // 2 (sqrt(1 + z^2) - z) written without cancellation for large zeta.
  return 2.0 / (std::sqrt(1.0 + zeta * zeta) + zeta);
}

namespace {
double critical_dt(const ContactLaw &law, double m_eq, double r_eff, double factor) {
  const double omega = law.ops->natural_frequency(law.self, m_eq, r_eff);
  if (!(omega > 0)) return std::numeric_limits<double>::infinity();
  return stable_omega_dt(factor * law.ops->damping_ratio(law.self, m_eq, r_eff)) / (factor * omega);
}
}  // namespace

double contact_critical_dt(const ContactLaw &law, double m_eq, double r_eff) {
  return critical_dt(law, m_eq, r_eff, 1);
}

double packing_critical_dt(const ContactLaw &law, double m_eq, double r_eff) {
  return critical_dt(law, m_eq, r_eff, packing_frequency_factor);
}

}  // namespace spreadmap::engine
