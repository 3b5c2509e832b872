// contact/hertz_mindlin: registration only; the law and its documentation are in hertz_mindlin.hpp.
#include "hertz_mindlin.hpp"

SPREADMAP_CONTACT_PLUGIN(spreadmap::HertzMindlin, "hertz_mindlin", "1.0.0",
                         "Hertz normal + Mindlin tangential spring, restitution-calibrated damping, Coulomb cap")
