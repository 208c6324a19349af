// The same output in every run. GiNaC seeds its hashes from the addresses of its type names,
// so under address randomisation its term order, and the form normal() and factor() return,
// change from run to run. These outputs differed between runs before the library chose
// between forms by a size that does not see GiNaC's signs (expression_size) and printed every
// formula through the canonical tree (expr/): each is run several times with the CLI's guard
// off (IMPACTGEN_NO_REEXEC=1: each run gets its own layout), then once with it (re-executed
// without randomisation, where the system permits it), and every output must be the same bytes.
// scripts/check-determinism.py runs every command over every class and file the same way.
#include "latex_tools.hpp"

#include <gtest/gtest.h>

#include <string>
#include <sys/wait.h>

using latex_tools::run;

namespace
{

std::string cli(const std::string &args, bool guard)
{
    int status = 0;
    const std::string out = run(std::string(guard ? "" : "IMPACTGEN_NO_REEXEC=1 ") + IMPACTGEN_CLI + " " + args, status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << args;
    return out;
}

} // namespace

TEST(Determinism, FormerlyDifferingOutputsAreTheSameInEveryRun)
{
    const std::string src = IMPACTGEN_SOURCE_DIR;
    // each differed in 2 to 5 of 5 runs before (scripts/check-determinism.py)
    const std::string commands[] = {
        "explain " + src + "/tests/codegen/laws/rod-rough-floor-energetic.json --format text",
        "explain " + src + "/examples/problems/puck-block-34.json --level summary",
        "formulas three-balls --format latex",
        "formulas double-pendulum-struck --format latex",
    };
    constexpr int runs = 6;
    for (const std::string &c : commands) {
        const std::string first = cli(c, false);
        ASSERT_FALSE(first.empty()) << c;
        for (int k = 1; k < runs; ++k)
            EXPECT_EQ(cli(c, false), first) << c << ": run " << k + 1 << " differs from the first";
        EXPECT_EQ(cli(c, true), first) << c << ": with the CLI's re-exec guard";
    }
}
