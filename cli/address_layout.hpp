// The CLI's guard against run-to-run differences in its output (see docs/architecture.md,
// "Determinism"): GiNaC seeds its hashes from the addresses of its type names, so with
// address-space layout randomisation its term order -- and the form some of its algorithms
// (normal(), factor(), gcd) return -- can change from one run to the next. The library
// chooses between forms by measures that do not see that order (expression_size, the
// canonical tree of expr/); this guard also fixes the layout itself for the command line.
#pragma once

namespace impactgen::cli
{

/// On Linux, when the process runs with address randomisation: re-executes /proc/self/exe
/// with the same arguments and environment once, with personality ADDR_NO_RANDOMIZE, and
/// does not return. Returns (and the command runs as it is) when the layout is already fixed,
/// when IMPACTGEN_NO_REEXEC is set (the re-executed process has it, so there is no loop; set
/// it to 1 to measure the library without the guard), when personality() is not permitted
/// (a container's seccomp filter) or the exec fails. Call it first in main, before any output.
void fix_address_layout(char **argv);

} // namespace impactgen::cli
