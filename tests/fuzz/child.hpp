// Running one command in a child process, the way a user's shell would, with
// its output captured and a deadline: the fuzzer must survive a child that
// crashes, hangs, floods its output or stops reading its input, and tell
// those apart (signal, timeout, exit code).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace impactgen::fuzz {

struct run_result {
    bool timed_out = false;   ///< killed with SIGKILL at the deadline
    int signal = 0;           ///< the signal that ended the child, 0 when it exited
    int exit_code = -1;       ///< when it exited
    std::string out, err;     ///< captured stdout and stderr (cut at output_cap bytes each)
    bool out_cut = false, err_cut = false;
    double seconds = 0;       ///< wall-clock time from fork to reaping
};

struct run_limits {
    double timeout_seconds = 10;
    std::size_t output_cap = 32u << 20;  ///< bytes kept of each stream; the rest is read and dropped
    std::size_t memory_mb = 0;           ///< RLIMIT_AS of the child, 0 for none
};

/// Runs argv[0] (looked up in PATH when it has no slash) with argv, stdin fed
/// from `input` (then closed), stdout and stderr captured through pipes.
run_result run_child(const std::vector<std::string>& argv, const std::string& input, const run_limits& limits);

} // namespace impactgen::fuzz
