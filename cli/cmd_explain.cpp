// impactgen explain: not yet implemented (issue 3).
#include "cli/commands.hpp"

void impactgen::cli::register_explain(CLI::App&, std::function<int()>&) {}
