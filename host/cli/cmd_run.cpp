// `spreadmap run WORKFLOW`: the whole workflow here, or its cases spread over MPI ranks or Slurm tasks.
#include <boost/program_options.hpp>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "workflow/runner.hpp"
#include "cli/program_commands.hpp"
#include "cluster/cluster_run.hpp"
#include "core/error.hpp"
#include "core/suggest.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/spreading/scene_model.hpp"
#include "workflow/stage_table.hpp"

namespace spreadmap::cli {
namespace {

namespace po = boost::program_options;
namespace sm = spreadmap;

// The options that spread the cases over a cluster must make sense together before anything runs.
void check_cluster_options(const sm::cluster::ClusterOptions &cl, const sm::RunOptions &opt,
                           const po::variables_map &vm) {
  const auto names = sm::cluster::executor_names();
  if (std::find(names.begin(), names.end(), cl.executor) == names.end()) {
    const std::string near = sm::closest(cl.executor, names);
    throw sm::InputError("--executor " + cl.executor + ": not an executor (" + sm::join(names) + ")" +
                         (near.empty() ? "" : "; did you mean '" + near + "'?"));
  }
  if (cl.dry_run && cl.executor != "slurm")
    throw sm::InputError(
        "--dry-run writes the Slurm scripts without submitting them: use it with --executor slurm");
  if (vm.count("threads-per-rank") && cl.threads_per_rank < 1)
    throw sm::InputError("--threads-per-rank must be at least 1");
  if (vm.count("threads-per-rank") && cl.executor == "local" && !opt.only_case)
    throw sm::InputError(
        "--threads-per-rank is for --executor mpi or slurm (or --case); a local run takes "
        "scene.threads and --jobs");
  if (opt.jobs > 1 && cl.executor != "local")
    throw sm::InputError("--jobs is for the local executor; with --executor " + cl.executor +
                         " each rank or array task runs one case at a time (see --threads-per-rank)");
  if (opt.only_case && cl.executor != "local")
    throw sm::InputError("--case runs one case here; it does not go with --executor " + cl.executor);
  if (opt.only_case && opt.jobs > 1) throw sm::InputError("--case runs one case: --jobs does not apply");
  // mpirun -n N without --executor mpi: N copies of the whole run would fill one folder at once
  for (const char *size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char *n = std::getenv(size); n && std::atoi(n) > 1 && cl.executor != "mpi")
      throw sm::InputError(std::string("this is one of ") + n + " MPI ranks, but --executor is " + cl.executor +
                           ": every rank would run every case. Add --executor mpi");
  if (opt.only_case)
    for (const auto &s : opt.only)
      if (s != "simulate")
        throw sm::InputError("--case runs one case of the simulate stage; --only " + s + " does not go with it");
}

}  // namespace

int cmd_run(int argc, char **argv) {
  po::options_description d("run options");
  std::string file, only, out;
  sm::RunOptions opt;
  sm::cluster::ClusterOptions cluster;
  std::size_t one_case = 0;
  Common c;
  const char *jobs_help = "cases run at once (default: 1; when they step on a GPU, one per CPU core: they share it)";
  const std::string only_help = "run only these stages, comma-separated (of " + sm::join(stage_names()) + ")";
  d.add_options()("workflow", po::value(&file)->required(), "workflow file")(
      "only", po::value(&only), only_help.c_str())(
      "force", po::bool_switch(&opt.force), "recompute finished cases and stages")(
      "out", po::value(&out), "run directory (default runs/<workflow name>)")(
      "jobs,j", po::value(&opt.jobs)->value_name("N"), jobs_help)(
      "executor", po::value(&cluster.executor)->default_value("local"),
      "where the simulate stage's cases run: local (here, --jobs at once) | mpi (under mpirun: rank 0 hands the "
      "cases to the other ranks) | slurm (a job array per case and a job for the later stages)")(
      "threads-per-rank", po::value(&cluster.threads_per_rank),
      "OpenMP threads of each case on an MPI rank or Slurm task (default: scene.threads, else the rank's share of "
      "its node's CPUs; Slurm: 1)")("dry-run", po::bool_switch(&cluster.dry_run),
                                    "with --executor slurm: write the scripts and print the path of "
                                    "submit.sh, submit nothing")(
      "case", cli::whole_number("case", &one_case, "a case number; cases are numbered from 0 (case 7 is c007)"),
      "run only case N of the design (case 7 is c007), leaving manifest.json alone: what one "
      "Slurm array task runs; implies --only simulate");
  c.add(d);
  po::positional_options_description p;
  p.add("workflow", 1);
  po::variables_map vm;
  if (!parse(argc, argv, d, p, vm,
             "run WORKFLOW [--only STAGE[,STAGE...]] [--force] [--out DIR] [--jobs N]\n"
             "                     [--executor local|mpi|slurm] [--threads-per-rank N] [--dry-run] [--case N]"))
    return 0;
  c.apply();
  opt.quiet = c.quiet;
  if (vm.count("jobs") && opt.jobs < 1) throw sm::InputError("--jobs must be at least 1");
  if (vm.count("case")) {
    opt.only_case = one_case;
    opt.case_threads = cluster.threads_per_rank;
  }
  for (const auto &s : sm::split(only, ','))
    if (!s.empty()) opt.only.insert(sm::lower(s));
  opt.out = out;
  check_cluster_options(cluster, opt, vm);
  if (opt.only_case) opt.only = {"simulate"};
  if (cluster.executor == "local") return sm::run_workflow(file, opt, sm::PluginRegistry::global());
  return sm::cluster::run_distributed(file, opt, cluster, sm::PluginRegistry::global());
}

}  // namespace spreadmap::cli
