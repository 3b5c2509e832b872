#include "core/stop.hpp"

#include <csignal>

namespace spreadmap {
namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }
}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}
bool stop_requested() { return g_stop != 0; }
void request_stop() { g_stop = 1; }
}  // namespace spreadmap
