// The program's entry: logging, stop handlers, the command named by argv[1] from the command table,
// and every error it throws printed once and turned into the exit status.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <boost/program_options.hpp>
#include <iostream>

#include "cli/command_table.hpp"
#include "core/error.hpp"
#include "core/plugin_abi.hpp"
#include "core/stop.hpp"
#include "core/suggest.hpp"

namespace spreadmap::cli {

int run_command_line(int argc, char **argv) {
  auto logger = spdlog::stderr_color_mt("spreadmap");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%^%l%$: %v");
  spdlog::set_level(spdlog::level::info);
  install_stop_handlers();
  if (argc < 2) {
    std::cerr << usage();
    return exit_input;
  }
  const std::string name = argv[1];
  try {
    if (name == "--version" || name == "version") {
      std::cout << "spreadmap " << SPREADMAP_VERSION << " (plugin ABI " << host_abi_text() << ")\n";
      return 0;
    }
    if (name == "--help" || name == "-h" || name == "help") {
      std::cout << usage();
      return 0;
    }
    if (const CommandInfo *command = find_command(name)) return command->run(argc - 1, argv + 1);
    const std::string near = closest(name, command_names());
    std::cerr << printed(InputError("unknown command '" + name + "'" +
                                    (near.empty() ? "" : "; did you mean '" + near + "'?")))
              << usage();
    return exit_input;
  } catch (const Error &e) {
    std::cerr << printed(e);
    return e.exit_code;
  } catch (const boost::program_options::error &e) {
    std::cerr << printed(InputError(name + ": " + e.what() + "\n  see: spreadmap " + name + " --help"));
    return exit_input;
  } catch (const std::exception &e) {
    std::cerr << printed(e);
    return exit_failure;
  }
}

}  // namespace spreadmap::cli
