// Reading and checking the systems of format version 3: joints between bodies, several
// contacts (each with its own restitution and friction, "inf" for a perfectly rough one) and
// sequential impacts. problem.cpp calls these; the messages name the key, like every refusal.
#pragma once

#include "decide.hpp"
#include "problem.hpp"

namespace impactgen
{

/// "joints" (optional): pins (2-D) or ball joints (3-D) between two bodies.
void read_joints(const json_value &root, problem &p);

/// The checks of a system (problem::is_system): every contact (bodies, normal, e, mu), every
/// joint (bodies, "the joint comes apart before impact"), at least one contact approaching, and
/// the systems the solver refuses (several contacts with a finite mu > 0 in 3-D). Throws
/// input_error naming the key.
void validate_system(const problem &p);

/// The reader's helpers, for the systems' reader (problem.cpp defines them).
namespace detail
{
std::size_t body_index_of(const problem &p, const json_value &v, const std::string &where);
vec3 read_vector(const json_value &v, int dim, const std::string &where);
const json_value &required(const json_value &obj, const std::string &key, const std::string &where);
decision decided_sign(const ex &e, const std::string &where, const std::string &what);
bool is_zero_exactly(const ex &e, const std::string &where, const std::string &what);
std::string show_value(const ex &e);
} // namespace detail

} // namespace impactgen
