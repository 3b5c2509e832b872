// The stand-alone commands of the workflow library (`spreadmap characterise STATE ...`, `train
// TABLE ...`): each stage can run on user files without a workflow. A command gets argv from its
// own name on and returns the exit status. Stage commands are registered in stage_table.cpp, the
// others in host/cli/command_table.cpp.
#pragma once

namespace spreadmap {

int cmd_calibrate(int argc, char **argv);
int cmd_simulate(int argc, char **argv);
int cmd_characterise(int argc, char **argv);
int cmd_train(int argc, char **argv);
int cmd_map(int argc, char **argv);
int cmd_verify(int argc, char **argv);
int cmd_query(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_report(int argc, char **argv);

}  // namespace spreadmap
