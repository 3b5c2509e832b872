// What every sub-command shares: --quiet/--verbose and the parse-or-print-help step.
#pragma once
#include <spdlog/spdlog.h>

#include <boost/program_options.hpp>
#include <cctype>
#include <iostream>
#include <limits>
#include <string>

#include "core/error.hpp"

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

// An unsigned option read as what it is: boost reads "-1" into an unsigned as 2^64 - 1 and goes on.
// `what` ends "--<option> <text>: not <what>".
template <class T>
po::typed_value<std::string> *whole_number(const std::string &option, T *target, const std::string &what) {
  return po::value<std::string>()->notifier([=](const std::string &text) {
    std::size_t used = 0;
    unsigned long long v = 0;
    if (!text.empty() && std::isdigit(static_cast<unsigned char>(text[0]))) try {
        v = std::stoull(text, &used);
      } catch (const std::out_of_range &) {
        used = 0;
      }
    if (used == 0 || used != text.size() || v > std::numeric_limits<T>::max())
      throw InputError("--" + option + " " + text + ": not " + what);
    *target = T(v);
  });
}

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
