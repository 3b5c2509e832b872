// spreadmap render STATE --out FILE.png [--scene scene.json] [--title TEXT] [--width PIXELS] [--vector pdf|svg|eps]
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/characterise/layer_eval.hpp"

namespace spreadmap {

int cmd_render(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("render options");
  std::string state, out, scene_file, title, vector;
  int width = 0;
  cli::Common c;
  d.add_options()("state", po::value(&state)->required(), "particle file (.vtp or .csv)")(
      "out", po::value(&out)->required(), "PNG to write")(
      "scene", po::value(&scene_file),
      "the case's scene.json (draws the domain and the spreader; default: beside STATE)")("title", po::value(&title),
                                                                                          "title drawn on the figure")(
      "width", po::value(&width), "image width in pixels (height keeps the 16:9 aspect; default 1600)")(
      "vector", po::value(&vector), "also write a pdf, svg or eps copy beside the PNG");
  c.add(d);
  po::positional_options_description p;
  p.add("state", 1);
  po::variables_map vm;
  if (!cli::parse(
          argc, argv, d, p, vm,
          "render STATE --out FILE.png [--scene scene.json] [--title TEXT] [--width PIXELS] [--vector pdf|svg|eps]"))
    return 0;
  c.apply();
  if (vm.count("width") && (width < 200 || width > 16384))
    throw InputError("--width " + std::to_string(width) + ": use 200 to 16384 pixels");
  if (!vector.empty() && vector != "pdf" && vector != "svg" && vector != "eps")
    throw InputError("--vector " + vector + ": use pdf, svg or eps");
  figures::use_style({true, width, vector, false});
  if (!figures::available())
    throw InputError("render: this build has no VTK (configure with SPREADMAP_ENABLE_VTK=ON)");
  const auto particles = read_particle_file(state);
  if (scene_file.empty() && fs::exists(fs::path(state).parent_path() / "scene.json"))
    scene_file = (fs::path(state).parent_path() / "scene.json").string();
  Scene scene;
  if (!scene_file.empty()) {
    scene = read_scene_file(scene_file);
  } else {
    // no scene: a box around the particles, no spreader
    double hx = 0, hy = 0, hz = 0;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      hx = std::max(hx, particles.x[i] + particles.radius[i]);
      hy = std::max(hy, particles.y[i] + particles.radius[i]);
      hz = std::max(hz, particles.z[i] + particles.radius[i]);
    }
    scene.domain = {hx, hy, hz, false, false};
  }
  // the spreader as the case recorded it (case.json beside the state: its body and where it stopped)
  nlohmann::json record;
  const fs::path case_json = fs::path(state).parent_path() / "case.json";
  if (fs::exists(case_json)) record = nlohmann::json::parse(read_text(case_json));
  figures::snapshot(particles, scene, record, fs::path(out), title);
  if (!fs::exists(out)) throw RunFailure("render: " + out + " was not written (see the warning above)");
  std::cout << out << "\n";
  return 0;
}

}  // namespace spreadmap
