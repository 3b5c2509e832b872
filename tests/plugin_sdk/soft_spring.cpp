// contact/soft_spring: the smallest useful contact law, as a user would write one outside the
// spreadmap tree. A linear spring with a viscous dashpot, no friction:
//   F_n = k delta - 2 zeta sqrt(k m_eq) v_n   (v_n < 0 while approaching)
// Only the SDK's headers are used; the registration macro makes the plugin's one exported symbol.
#include <spreadmap/contact.hpp>

#include <cmath>

namespace sm = spreadmap;

struct SoftSpring {
  static constexpr sm_param_v1 params[] = {
      sm::number("stiffness", "N/m", 1e-3, 1e9, 500, "k: normal spring constant"),
      sm::number("damping_ratio", "-", 0, 1, 0.1, "zeta: damping ratio of the normal dashpot"),
  };
  static constexpr int history = 0;

  double k, zeta;

  static SoftSpring bind(const sm::Values &v) { return {v["stiffness"], v["damping_ratio"]}; }
  double natural_frequency(double m_eq, double) const { return std::sqrt(k / m_eq); }
  double damping_ratio(double, double) const { return zeta; }
  bool makes_torque() const { return false; }

  template <class Real> SM_HD sm::ContactForce<Real> operator()(const sm::ContactState<Real> &c, Real *) const {
    sm::ContactForce<Real> f;
    f.normal = Real(k) * c.overlap - Real(2 * zeta) * std::sqrt(Real(k) * c.m_eq) * c.v_n;
    return f;
  }
};

SPREADMAP_CONTACT_PLUGIN(SoftSpring, "soft_spring", "0.1.0", "out-of-tree sample: linear spring-dashpot, no friction")
