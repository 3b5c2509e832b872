// A contact plugin module built the plain way, without spreadmap_add_plugin()'s CUDA hook: what an
// out-of-tree or CPU-only build produces. cuda_plugins_test asks it for GPU kernels.
#include <spreadmap/contact.hpp>

namespace {

struct CpuOnlySpring {
  static constexpr sm_param_v1 params[] = {
      spreadmap::number("stiffness", "N/m", 1e-3, 1e9, 100, "K: linear normal stiffness")};
  static constexpr int history = 0;
  double k;
  static CpuOnlySpring bind(const spreadmap::Values &v) { return {v["stiffness"]}; }
  double natural_frequency(double m_eq, double) const { return std::sqrt(k / m_eq); }
  double damping_ratio(double, double) const { return 0; }
  bool makes_torque() const { return false; }
  template <class Real>
  SM_HD spreadmap::ContactForce<Real> operator()(const spreadmap::ContactState<Real> &c, Real *) const {
    spreadmap::ContactForce<Real> f;
    f.normal = Real(k) * c.overlap;
    return f;
  }
};

}  // namespace

SPREADMAP_CONTACT_PLUGIN(CpuOnlySpring, "cpu_only_spring", "1.0.0", "a linear spring built without CUDA (test)")
