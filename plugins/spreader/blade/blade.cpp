// Registers spreader/blade (the functor lives in blade.hpp so that tests can call it directly).
#include "blade.hpp"

SPREADMAP_SPREADER_PLUGIN(spreadmap::spreader::Blade, "blade", "1.0.0",
                          "vertical slab with rounded lower edges translating at U along +x")
