// spreadmap: which spreader settings give the powder layer you want, as fast as possible.
// The commands are in host/cli/command_table.cpp.
#include "cli/command_table.hpp"

int main(int argc, char **argv) { return spreadmap::cli::run_command_line(argc, argv); }
