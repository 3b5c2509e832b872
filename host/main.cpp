// spreadmap: which spreader settings give the powder layer you want, as fast as possible.
// The command line: run, validate, plugins and the stand-alone stage commands.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <boost/program_options.hpp>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "cluster/cluster_run.hpp"
#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/stop.hpp"
#include "core/suggest.hpp"
#include "workflow/calibrate/calibration_file.hpp"
#include "workflow/command_line.hpp"
#include "workflow/commands.hpp"
#include "workflow/scene_file/scene_build.hpp"
#include "workflow/workflow.hpp"
#include "workflow/stage.hpp"

namespace po = boost::program_options;
namespace sm = spreadmap;

namespace {

constexpr const char *usage = R"(usage: spreadmap <command> [options]

commands:
  run WORKFLOW        run a workflow (simulate -> characterise -> train -> map)
  simulate SCENE      run one explicit scene file (particles, walls, outputs; docs/scenes.md)
  calibrate FILE      friction and rolling friction from measured bulk angles (docs/calibration.md)
  validate FILE       check a workflow, scene or calibration file completely without running anything
  plugins [NAME]      list plugins and their parameters (the reference manual)
  characterise STATE  layer metrics of a particle file (.vtp or .csv)
  train TABLE         fit a surrogate to a CSV table
  map MODEL           process map of a trained model
  query MODEL         predictions or the best operating point of a trained model
  render STATE        snapshot of a particle state as PNG
  verify WORKFLOW     simulate the optimum a workflow's map proposes and check it against the prediction
  report RUN_DIR      rebuild RUN_DIR/report.html, the run's answer on one page

  spreadmap <command> --help    options of a command
  spreadmap --version
)";

namespace cli = spreadmap::cli;
using spreadmap::cli::Common;
using spreadmap::cli::parse;

// The options that spread the cases over a cluster must make sense together before anything runs.
void check_cluster_options(const sm::cluster::ClusterOptions &cl, const sm::RunOptions &opt,
                           const po::variables_map &vm) {
  const auto names = sm::cluster::executor_names();
  if (std::find(names.begin(), names.end(), cl.executor) == names.end()) {
    const std::string near = sm::closest(cl.executor, names);
    throw sm::InputError("error: --executor " + cl.executor + ": not an executor (" + sm::join(names) + ")" +
                         (near.empty() ? "" : "; did you mean '" + near + "'?"));
  }
  if (cl.dry_run && cl.executor != "slurm")
    throw sm::InputError(
        "error: --dry-run writes the Slurm scripts without submitting them: use it with --executor slurm");
  if (vm.count("threads-per-rank") && cl.threads_per_rank < 1)
    throw sm::InputError("error: --threads-per-rank must be at least 1");
  if (vm.count("threads-per-rank") && cl.executor == "local" && !opt.only_case)
    throw sm::InputError(
        "error: --threads-per-rank is for --executor mpi or slurm (or --case); a local run takes "
        "scene.threads and --jobs");
  if (opt.jobs != 1 && cl.executor != "local")
    throw sm::InputError("error: --jobs is for the local executor; with --executor " + cl.executor +
                         " each rank or array task runs one case at a time (see --threads-per-rank)");
  if (opt.only_case && cl.executor != "local")
    throw sm::InputError("error: --case runs one case here; it does not go with --executor " + cl.executor);
  if (opt.only_case && opt.jobs != 1) throw sm::InputError("error: --case runs one case: --jobs does not apply");
  // mpirun -n N without --executor mpi: N copies of the whole run would fill one folder at once
  for (const char *size : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char *n = std::getenv(size); n && std::atoi(n) > 1 && cl.executor != "mpi")
      throw sm::InputError(std::string("error: this is one of ") + n + " MPI ranks, but --executor is " + cl.executor +
                           ": every rank would run every case. Add --executor mpi");
  if (opt.only_case)
    for (const auto &s : opt.only)
      if (s != "simulate")
        throw sm::InputError("error: --case runs one case of the simulate stage; --only " + s + " does not go with it");
}

int cmd_run(int argc, char **argv) {
  po::options_description d("run options");
  std::string file, only, out;
  sm::RunOptions opt;
  sm::cluster::ClusterOptions cluster;
  std::size_t one_case = 0;
  Common c;
  d.add_options()("workflow", po::value(&file)->required(), "workflow file")(
      "only", po::value(&only), "run only these stages, comma-separated (simulate,characterise,train,map)")(
      "force", po::bool_switch(&opt.force), "recompute finished cases and stages")(
      "out", po::value(&out), "run directory (default runs/<workflow name>)")(
      "jobs,j", po::value(&opt.jobs)->default_value(1), "cases run at once")(
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
  if (opt.jobs < 1) throw sm::InputError("error: --jobs must be at least 1");
  if (vm.count("case")) {
    opt.only_case = one_case;
    opt.case_threads = cluster.threads_per_rank;
  }
  std::size_t pos = 0;
  while (!only.empty() && pos <= only.size()) {
    const std::size_t comma = only.find(',', pos);
    const std::string s = only.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if (!s.empty()) opt.only.insert(sm::lower(s));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  opt.out = out;
  check_cluster_options(cluster, opt, vm);
  if (opt.only_case) opt.only = {"simulate"};
  if (cluster.executor == "local") return sm::run_workflow(file, opt, sm::PluginRegistry::global());
  return sm::cluster::run_distributed(file, opt, cluster, sm::PluginRegistry::global());
}

int cmd_validate(int argc, char **argv) {
  po::options_description d("validate options");
  std::vector<std::string> files;
  Common c;
  d.add_options()(
      "workflow", po::value(&files)->required()->multitoken(),
      "workflow, scene or calibration file(s): a file with parameters and tests at its top is a calibration "
      "file, one with neither stages nor scene a scene file");
  c.add(d);
  po::positional_options_description p;
  p.add("workflow", -1);
  po::variables_map vm;
  if (!parse(argc, argv, d, p, vm, "validate FILE [FILE...]")) return 0;
  c.apply();
  int failures = 0;
  for (const auto &f : files) {
    try {
      const YAML::Node root = sm::load_yaml(f);
      if (sm::calibrate::is_calibration_document(root)) {
        const auto c = sm::calibrate::read_calibration_file(f, sm::PluginRegistry::global());
        std::cout << f << ": ok (calibration file: " << c.parameters.size() << " parameters, " << c.tests.size()
                  << " bulk tests)\n";
        continue;
      }
      if (sm::scene_file::is_scene_document(root)) {
        const auto loaded = sm::scene_file::load_scene(f, sm::PluginRegistry::global());
        std::cout << f << ": ok (scene file: " << loaded.particles.set.size() << " particles, "
                  << loaded.scene.walls.size() << " walls)\n";
        continue;
      }
      auto v = sm::validate_workflow(f, sm::PluginRegistry::global());
      std::cout << f << ": ok (" << v.wf.stages.size() << " stages)\n";
    } catch (const sm::Error &e) {
      std::cerr << e.what() << "\n";
      ++failures;
    }
  }
  return failures ? sm::exit_input : 0;
}

int cmd_plugins(int argc, char **argv) {
  po::options_description d("plugins options");
  std::string kind, name, format = "table";
  Common c;
  d.add_options()("kind", po::value(&kind), "contact | spreader | metrics | surrogate")(
      "name", po::value(&name), "one plugin: print its parameter schema")(
      "format", po::value(&format)->default_value("table"), "table | json");
  c.add(d);
  po::positional_options_description p;
  p.add("name", 1);
  po::variables_map vm;
  if (!parse(argc, argv, d, p, vm, "plugins [--kind KIND] [NAME] [--format table|json]")) return 0;
  c.apply();
  auto &reg = sm::PluginRegistry::global();
  std::vector<std::string> kinds = sm::plugin_kinds();
  if (!kind.empty()) {
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end())
      throw sm::InputError("error: --kind " + kind + ": not a plugin kind (" + sm::join(kinds) + ")");
    kinds = {kind};
  }
  nlohmann::json all = nlohmann::json::array();
  bool found = false;
  for (const auto &k : kinds) {
    for (const auto &n : reg.names(k)) {
      if (!name.empty() && n != name) continue;
      found = true;
      const sm::LoadedPlugin *loaded = nullptr;
      try {
        loaded = &reg.get(k, n);
      } catch (const sm::PluginError &e) {
        if (!name.empty()) throw;
        spdlog::warn("{} (skipped; the other plugins are listed)", e.what());  // one broken library hides nothing else
        continue;
      }
      const auto &pl = *loaded;
      if (format == "json") {
        auto j = sm::schema_json(*pl.descriptor);
        j["file"] = pl.file.string();
        all.push_back(j);
      } else if (name.empty()) {
        std::printf("%-10s %-16s %-8s %s\n", k.c_str(), n.c_str(), pl.descriptor->version, pl.descriptor->summary);
      } else {
        std::cout << sm::describe_schema(*pl.descriptor) << "  file: " << pl.file.string() << "\n";
      }
    }
  }
  if (!name.empty() && !found) {
    std::vector<std::string> every;
    for (const auto &k : kinds)
      for (const auto &n : reg.names(k)) every.push_back(n);
    const std::string near = sm::closest(name, every);
    throw sm::InputError("error: no plugin named '" + name + "'" +
                         (near.empty() ? "" : "; did you mean '" + near + "'?") + " available: " + sm::join(every));
  }
  if (format == "json") std::cout << all.dump(2) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char **argv) {
  auto logger = spdlog::stderr_color_mt("spreadmap");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%^%l%$: %v");
  spdlog::set_level(spdlog::level::info);
  sm::install_stop_handlers();
  if (argc < 2) {
    std::cerr << usage;
    return sm::exit_input;
  }
  const std::string cmd = argv[1];
  try {
    if (cmd == "--version" || cmd == "version") {
      std::cout << "spreadmap " << SPREADMAP_VERSION << " (plugin ABI " << SPREADMAP_PLUGIN_ABI << ")\n";
      return 0;
    }
    if (cmd == "--help" || cmd == "-h" || cmd == "help") {
      std::cout << usage;
      return 0;
    }
    if (cmd == "run") return cmd_run(argc - 1, argv + 1);
    if (cmd == "validate") return cmd_validate(argc - 1, argv + 1);
    if (cmd == "plugins") return cmd_plugins(argc - 1, argv + 1);
    if (auto sub = sm::find_command(cmd)) return sub(argc - 1, argv + 1);
    const std::vector<std::string> cmds = {"run", "validate", "plugins", "characterise", "train",
                                           "map", "query",    "render",  "simulate",     "verify", "report", "calibrate"};
    const std::string near = sm::closest(cmd, cmds);
    std::cerr << "error: unknown command '" << cmd << "'" << (near.empty() ? "" : "; did you mean '" + near + "'?")
              << "\n"
              << usage;
    return sm::exit_input;
  } catch (const sm::Error &e) {
    std::cerr << e.what() << "\n";
    return e.exit_code;
  } catch (const po::error &e) {
    std::cerr << "error: " << cmd << ": " << e.what() << "\n  see: spreadmap " << cmd << " --help\n";
    return sm::exit_input;
  } catch (const std::exception &e) {
    std::cerr << "error: " << e.what() << "\n";
    return sm::exit_failure;
  }
}
