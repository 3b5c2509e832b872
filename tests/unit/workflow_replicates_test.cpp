// host/workflow/simulate/replicates: replicate 0 is the case as written; the others get distinct heap
// seeds inside powder.seed's range, the same on every call (a resumed run finds its heaps again).
#include <gtest/gtest.h>

#include <set>

#include "workflow/cases/replicates.hpp"

namespace sm = spreadmap;

TEST(Replicates, SeedsAreDistinctDeterministicAndInRange) {
  for (std::int64_t base : {0ll, 1ll, 42ll, 4294967295ll}) {
    EXPECT_EQ(sm::replicate_seed(base, 0), base);
    std::set<std::int64_t> seen = {base};
    for (std::size_t r = 1; r < sm::max_replicates; ++r) {
      const std::int64_t s = sm::replicate_seed(base, r);
      EXPECT_EQ(s, sm::replicate_seed(base, r));
      EXPECT_GE(s, 0);
      EXPECT_LE(s, 4294967295ll);
      EXPECT_TRUE(seen.insert(s).second) << "seed " << base << " replicate " << r;
    }
  }
  sm::Scene scene;
  scene.powder.seed = 7;
  EXPECT_EQ(sm::replicate_scene(scene, 0).powder.seed, 7);
  EXPECT_EQ(sm::replicate_scene(scene, 3).powder.seed, sm::replicate_seed(7, 3));
  EXPECT_EQ(sm::replicate_id("c004", 0), "c004");
  EXPECT_EQ(sm::replicate_id("c004", 2), "c004_r2");
}
