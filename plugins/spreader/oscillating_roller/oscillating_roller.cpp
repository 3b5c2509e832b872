// Registers spreader/oscillating_roller (the functor lives in oscillating_roller.hpp so that its
// tests can call it directly).
#include "oscillating_roller.hpp"

SPREADMAP_SPREADER_PLUGIN(
    spreadmap::spreader::OscillatingRoller, "oscillating_roller", "1.0.0",
    "roller along y translating at U along +x, turning at omega + A 2 pi f sin(2 pi f t) about +y")
