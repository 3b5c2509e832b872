// spreadmap verify WORKFLOW [--out DIR] [--force] [--jobs N]: the workflow's verify stage alone, on
// the run directory its earlier stages filled (the map's optimum, the trained model).
#include "workflow/runner.hpp"
#include "core/error.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/stage/stage.hpp"

namespace spreadmap {

int cmd_verify(int argc, char **argv) {
  cli::po::options_description d("verify options");
  std::string file, out;
  RunOptions opt;
  cli::Common c;
  d.add_options()("workflow", cli::po::value(&file)->required(), "workflow file with a verify stage after its map")(
      "out", cli::po::value(&out), "run directory (default runs/<workflow name>)")(
      "force", cli::po::bool_switch(&opt.force), "simulate and measure the verification runs again")(
      "jobs,j", cli::po::value(&opt.jobs)->default_value(1), "runs at once");
  c.add(d);
  cli::po::positional_options_description p;
  p.add("workflow", 1);
  cli::po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "verify WORKFLOW [--out DIR] [--force] [--jobs N]")) return 0;
  c.apply();
  if (opt.jobs < 1) throw InputError("--jobs must be at least 1");
  opt.quiet = c.quiet;
  opt.out = out;
  opt.only = {"verify"};
  return run_workflow(file, opt, PluginRegistry::global());
}

}  // namespace spreadmap
