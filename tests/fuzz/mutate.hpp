// Inputs for the command-line fuzzer: random valid impact problems (the seeds
// that reach the solver and the printers) and the mutations that turn them
// into hostile ones (values, names, structure, bytes). Everything is drawn
// from one seeded engine, so a case is reproduced by its seed alone.
#pragma once

#include <nlohmann/json.hpp>

#include <random>
#include <string>

namespace impactgen::fuzz {

using json = nlohmann::ordered_json;
using engine = std::mt19937_64;

/// A valid problem: 2-D or 3-D; particles, rigid bodies (3-D inertia diagonal
/// or a full symmetric positive-definite tensor), a body of infinite mass, at
/// most one pivot (on a body at rest), sometimes a third body that takes no
/// part, normals off the axes, values written as JSON numbers, decimals or
/// constant expression strings; the contact points approach. Now and then a
/// few values are symbols (solve refuses those; the other subcommands do not):
/// `numbers_only` tells whether the problem has numbers only.
json random_problem(engine& rng, bool* numbers_only = nullptr);

/// Applies `count` mutations of the tree; returns what was done, for the report.
std::string mutate_tree(json& problem, engine& rng, int count);

/// The text of the tree (random indentation and escaping), with the raw
/// number tokens that JSON trees cannot hold (1e400, -0, 30-digit integers)
/// put in place of their placeholders.
std::string serialise(const json& problem, engine& rng);

/// Applies `count` byte-level mutations (bit flips, deletions, insertions,
/// truncation, digit changes); returns what was done.
std::string mutate_bytes(std::string& text, engine& rng, int count);

} // namespace impactgen::fuzz
