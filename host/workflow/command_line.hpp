// What every sub-command shares: --quiet/--verbose and the parse-or-print-help step.
#pragma once
#include <spdlog/spdlog.h>

#include <boost/program_options.hpp>
#include <iostream>
#include <string>

namespace spreadmap::cli {

namespace po = boost::program_options;

struct Common {
  bool quiet = false, verbose = false;
  void add(po::options_description &d) {
    d.add_options()("quiet,q", po::bool_switch(&quiet), "only warnings and errors")(
        "verbose,v", po::bool_switch(&verbose), "debug messages");
  }
  void apply() const {
    spdlog::set_level(quiet ? spdlog::level::warn : verbose ? spdlog::level::debug : spdlog::level::info);
  }
};

// Parses argv[1..] (argv[0] is the command's name); returns false when --help was printed.
inline bool parse(int argc, char **argv, po::options_description &desc, po::positional_options_description &pos,
                  po::variables_map &vm, const std::string &synopsis) {
  desc.add_options()("help,h", "this help");
  po::store(po::command_line_parser(argc, argv).options(desc).positional(pos).run(), vm);
  if (vm.count("help")) {
    std::cout << "usage: spreadmap " << synopsis << "\n\n" << desc << "\n";
    return false;
  }
  po::notify(vm);
  return true;
}

}  // namespace spreadmap::cli
