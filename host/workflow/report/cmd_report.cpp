// spreadmap report RUN_DIR: rebuilds RUN_DIR/report.html from the run directory's files.
#include <iostream>

#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/report/run_report.hpp"

namespace spreadmap {

int cmd_report(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("report options");
  std::string run;
  cli::Common c;
  d.add_options()("run", po::value(&run)->required(), "the run directory a workflow wrote, e.g. runs/quickstart");
  c.add(d);
  po::positional_options_description p;
  p.add("run", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "report RUN_DIR")) return 0;
  c.apply();
  std::cout << write_run_report(run).string() << "\n";
  return 0;
}

}  // namespace spreadmap
