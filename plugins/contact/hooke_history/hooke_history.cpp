// contact/hooke_history: registration only; the law and its documentation are in hooke_history.hpp.
#include "hooke_history.hpp"

SPREADMAP_CONTACT_PLUGIN(spreadmap::HookeHistory, "hooke_history", "1.0.0",
                         "linear spring-dashpot normal + Cundall-Strack tangential spring with Coulomb cap")
