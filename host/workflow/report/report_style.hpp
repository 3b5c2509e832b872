// The run report's <head>: its title and one stylesheet, for a laptop screen and for A4 paper.
#pragma once
#include <string>

namespace spreadmap::report {

std::string page_head(const std::string &title);

}  // namespace spreadmap::report
