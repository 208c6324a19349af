// Subcommands that live in files of their own. Each register_* adds its
// subcommand to the app and, from its parse callback, sets `action` to the
// function that runs it. Errors are thrown (impactgen::input_error for bad
// input); main() prints them as one line and exits 1.
#pragma once

#include "symbolic/problem.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace impactgen::cli
{

/// A named class or a problem file (warnings about ignored keys go to stderr).
problem load(const std::string &class_or_file);

void register_explain(CLI::App &app, std::function<int()> &action);
void register_exercises(CLI::App &app, std::function<int()> &action);

} // namespace impactgen::cli

#include "codegen/codegen.hpp"
#include <nlohmann/json.hpp>

namespace impactgen::cli
{

/// formulas --jacobian [--wrt a,b]: the codegen plan with its Jacobian, and its printers.
codegen::plan jacobian_plan_for(const problem &p, const std::string &wrt);
/// The --wrt list "a,b,c" (throws input_error on an empty item: "a,,b", ",").
void split_wrt(const std::string &s, std::vector<std::string> &out);
std::string jacobian_text(const codegen::plan &pl);
std::string jacobian_latex(const codegen::plan &pl);
nlohmann::ordered_json jacobian_json(const codegen::plan &pl);
/// formulas --jacobian of a problem under Routh's process (poisson, energetic with friction): the
/// closed form, then the Jacobian of each phase sequence (symbolic/process_jacobian.hpp).
int process_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt);
/// formulas --jacobian of a problem with Coulomb friction under Newton's law: the closed form, then
/// the Jacobian of each regime candidate (symbolic/friction_jacobian.hpp).
int friction_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt);
/// formulas --jacobian of a system: its candidates, then each set's Jacobian of the velocities
/// after impact by the inputs (every symbol, or those --wrt names).
int system_jacobian_formulas(const problem &p, const std::string &format, const std::string &wrt);

void register_codegen(CLI::App &app, std::function<int()> &action);

} // namespace impactgen::cli
