// Stand-alone stage commands (`spreadmap characterise STATE ...`, `train TABLE ...`, ...): each
// stage can run on user files without a workflow. A command gets argv from its own name on.
#pragma once
#include <functional>
#include <string>

namespace spreadmap {
using Command = std::function<int(int argc, char **argv)>;
// The command of that name, or an empty function.
Command find_command(const std::string &name);
}  // namespace spreadmap
