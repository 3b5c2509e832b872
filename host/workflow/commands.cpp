#include "workflow/commands.hpp"

namespace spreadmap {

int cmd_characterise(int argc, char **argv);
int cmd_train(int argc, char **argv);
int cmd_map(int argc, char **argv);
int cmd_query(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_simulate(int argc, char **argv);
int cmd_calibrate(int argc, char **argv);
int cmd_verify(int argc, char **argv);
int cmd_report(int argc, char **argv);

Command find_command(const std::string &name) {
  if (name == "characterise" || name == "characterize") return cmd_characterise;
  if (name == "train") return cmd_train;
  if (name == "map") return cmd_map;
  if (name == "query") return cmd_query;
  if (name == "render") return cmd_render;
  if (name == "simulate") return cmd_simulate;
  if (name == "verify") return cmd_verify;
  if (name == "report") return cmd_report;
  if (name == "calibrate" || name == "calibration") return cmd_calibrate;
  return {};
}

}  // namespace spreadmap
