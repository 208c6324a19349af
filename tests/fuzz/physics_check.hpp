// The physics of an answer of `impactgen solve --json`, checked numerically
// from the problem's own values (read with the project's reader): every law of
// shared/problem-format.md, so that an answer that parses but is wrong counts
// as a failure just like a crash.
#pragma once

#include <string>
#include <vector>

namespace impactgen::fuzz {

/// The laws the answer violates, each as one line of text; empty when it satisfies them all.
std::vector<std::string> check_answer(const std::string& problem_text, const std::string& answer_text);

} // namespace impactgen::fuzz
