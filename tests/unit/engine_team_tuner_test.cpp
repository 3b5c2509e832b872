// The team tuner against machines given as step times per thread count: on a quiet machine it stays
// on every thread, beside a busy process it falls back to the threads that are not held back, and
// either way its probes cost a few per cent at most. The measure is the one a user feels: the run's
// time against the best fixed count's.
#include <engine/team_tuner.hpp>
#include <gtest/gtest.h>

#include <functional>
#include <vector>

using spreadmap::engine::TeamTuner;

namespace {

// Runs `steps` steps on a machine whose step takes seconds(threads); returns the run's time and how
// many steps ran at each count.
struct TunedRun {
  double seconds = 0;
  std::vector<long> steps_at;
};
TunedRun simulate(int most, long steps, const std::function<double(int)> &seconds) {
  TeamTuner tuner;
  tuner.reset(most);
  TunedRun run;
  run.steps_at.assign(most + 1, 0);
  for (long k = 0; k < steps; ++k) {
    const int threads = tuner.threads();
    EXPECT_GE(threads, 1);
    EXPECT_LE(threads, most);
    ++run.steps_at[threads];
    run.seconds += seconds(threads);
    tuner.stepped(seconds(threads));
  }
  return run;
}

}  // namespace

TEST(EngineTeamTuner, OnAQuietMachineItStaysOnEveryThreadAndItsProbesCostUnderTwoPercent) {
  // the peers' scene: 1 thread 250 us a step, 2 threads 1.6x faster
  const auto quiet = [](int threads) { return threads == 2 ? 250e-6 / 1.6 : 250e-6; };
  const TunedRun run = simulate(2, 400000, quiet);
  EXPECT_LT(run.seconds, 1.02 * 400000 * quiet(2));
  EXPECT_GT(run.steps_at[2], 98 * run.steps_at[1]);
}

TEST(EngineTeamTuner, BesideABusyProcessTwoThreadsFallBackToOneAndRunAtLeastNinetyPercentOfItsSpeed) {
  // measured on 2 cores beside a busy process: 2 threads at 0.23x one thread
  const auto busy = [](int threads) { return threads == 2 ? 250e-6 / 0.23 : 250e-6; };
  const TunedRun run = simulate(2, 400000, busy);
  EXPECT_LT(run.seconds, 400000 * busy(1) / 0.9) << "at least 0.9x one thread";
  EXPECT_LT(run.seconds, 1.03 * 400000 * busy(1));
}

TEST(EngineTeamTuner, WhenTheBusyProcessEndsItReturnsToEveryThread) {
  long step = 0;
  const auto changing = [&step](int threads) {
    const double speed_up = step < 200000 ? 0.23 : 1.6;  // busy, then quiet
    return threads == 2 ? 250e-6 / speed_up : 250e-6;
  };
  TeamTuner tuner;
  tuner.reset(2);
  long at_two_late = 0;
  for (; step < 400000; ++step) {
    const int threads = tuner.threads();
    if (step >= 300000 && threads == 2) ++at_two_late;
    tuner.stepped(changing(threads));
  }
  EXPECT_GT(at_two_late, 95000) << "back on 2 threads within the following 100,000 steps";
}

TEST(EngineTeamTuner, OnSixteenCoresBesideOneBusyProcessItSettlesOnFifteen) {
  // n threads share the work; at 16 one of them shares its core, and every step waits for it
  const auto machine = [](int threads) { return (threads == 16 ? 4.0 : 1.0) * 4e-3 / threads; };
  const TunedRun run = simulate(16, 100000, machine);
  EXPECT_GT(run.steps_at[15], 90000);
  EXPECT_LT(run.seconds, 1.05 * 100000 * machine(15));
}

TEST(EngineTeamTuner, OneThreadAllowedIsOneThreadAlways) {
  const TunedRun run = simulate(1, 1000, [](int) { return 1e-3; });
  EXPECT_EQ(run.steps_at[1], 1000);
}
