// `spreadmap validate FILE...`: a workflow, scene or calibration file checked completely, nothing run.
#include <boost/program_options.hpp>
#include <iostream>
#include <yaml-cpp/yaml.h>

#include "workflow/runner.hpp"
#include "cli/program_commands.hpp"
#include "core/error.hpp"
#include "workflow/calibrate/calibration_file.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/scene/scene_build.hpp"
#include "workflow/stage/stage.hpp"
#include "workflow/run/run_dir.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap::cli {

namespace po = boost::program_options;
namespace sm = spreadmap;

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
      if (sm::scene::is_scene_document(root)) {
        const auto loaded = sm::scene::load_scene(f, sm::PluginRegistry::global());
        std::cout << f << ": ok (scene file: " << loaded.particles.set.size() << " particles, "
                  << loaded.scene.walls.size() << " walls)\n";
        continue;
      }
      auto v = sm::validate_workflow(f, sm::PluginRegistry::global());
      std::cout << f << ": ok (" << v.wf.stages.size() << " stages)\n";
    } catch (const sm::Error &e) {
      std::cerr << sm::printed(e);
      ++failures;
    }
  }
  return failures ? sm::exit_input : 0;
}

}  // namespace spreadmap::cli
