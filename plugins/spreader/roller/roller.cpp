// Registers spreader/roller (the functor lives in roller.hpp so that tests can call it directly).
#include "roller.hpp"

SPREADMAP_SPREADER_PLUGIN(spreadmap::spreader::Roller, "roller", "1.0.0",
                          "cylinder along y translating at U along +x and turning at omega about +y")
