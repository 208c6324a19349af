// impactgen codegen: not yet implemented (issue 4).
#include "cli/commands.hpp"

void impactgen::cli::register_codegen(CLI::App&, std::function<int()>&) {}
