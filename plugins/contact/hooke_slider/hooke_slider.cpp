// contact/hooke_slider: registration only; the law and its documentation are in hooke_slider.hpp.
#include "hooke_slider.hpp"

SPREADMAP_CONTACT_PLUGIN(
    spreadmap::HookeSlider, "hooke_slider", "1.0.0",
    "the study's law: linear spring-dashpot normal (K_n = m_eq V_max^2/Delta_max^2) + Coulomb slider")
