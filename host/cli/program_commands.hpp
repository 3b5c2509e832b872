// The commands of the program itself, beside those of the workflow library (workflow/commands.hpp).
#pragma once

namespace spreadmap::cli {

int cmd_run(int argc, char **argv);
int cmd_validate(int argc, char **argv);
int cmd_plugins(int argc, char **argv);
int cmd_stages(int argc, char **argv);

}  // namespace spreadmap::cli
