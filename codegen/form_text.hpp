// The helpers both header writers (codegen.cpp, friction*.cpp) share: operation counts,
// wrapped comments, balanced sums, the positive-definiteness minors of an inertia tensor,
// and the one flag of a branchless form (its finiteness sum ordered by when each value is
// ready, its minimums and comparisons). Private to the codegen library.
#pragma once

#include "codegen.hpp"
#include "program.hpp"
#include "symbolic/vector_algebra.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace impactgen::codegen::form_text
{

std::string counts_text(const op_counts &c);
/// The command that regenerates a header ("impactgen codegen SOURCE --name ... --flags"),
/// as its banner writes it.
std::string command_line(const options &o);
/// Refuses (option_error) a function name that is not a usable C++ identifier or a
/// namespace that cannot be one.
void check_names(const options &o);
std::string wrap_comment(const std::string &lhs, const std::string &rhs);
/// The names of values summed as a balanced tree, ((a + b) + (c + d)) + e: each partial sum
/// parenthesised as an operand of the next (by its structure: it is a sum).
std::string balanced_sum(const std::vector<std::string> &names);
/// The leading principal minors that make a symmetric tensor positive definite, block by
/// block (with the determinant of a block of all three axes only when with_determinant).
std::vector<std::pair<GiNaC::ex, std::string>>
positive_definite_minors(const mat3 &J, const std::array<std::string, 3> &axes, bool with_determinant);
/// Every principal minor of each block, each >= 0: a symmetric tensor positive semidefinite
/// (an inverse inertia tensor of the engine convention: 0 for a static body, singular for
/// one whose rotation is locked about some axes).
std::vector<std::pair<GiNaC::ex, std::string>> positive_semidefinite_minors(const mat3 &J,
                                                                            const std::array<std::string, 3> &axes);

// A term of the finiteness sum of a branchless form: its text, when its value is ready
// (an estimate of the latency from the inputs, in cycles), whether the form may leave
// it 0 (energy_lost under with_energy_lost = false: then it is not added at all), and the
// precedence of its top operation (code_term: 4 for a name).
struct sum_term {
    std::string text;
    int ready = 0;
    bool optional = false;
    int precedence = 4;
};
std::string timed_sum(const std::vector<sum_term> &terms);
std::size_t mins(const emitted &em);
std::pair<std::vector<sum_term>, std::vector<sum_term>> split_by_time(const std::vector<sum_term> &finite_terms);
std::pair<std::size_t, std::size_t> flag_counts(const emitted &form, const std::vector<sum_term> &finite_terms);
std::string ok_flag(const std::string &ind, const emitted &form, const std::vector<sum_term> &finite_terms,
                    bool scalar);
emit_options branchless_form(bool share_divisions, int optional_output);

} // namespace impactgen::codegen::form_text
