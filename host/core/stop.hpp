// SIGINT / SIGTERM request a clean stop: long loops poll stop_requested() and unwind with
// Interrupted, leaving only whole files behind.
#pragma once

namespace spreadmap {
void install_stop_handlers();
bool stop_requested();
void request_stop();  // for tests
}  // namespace spreadmap
