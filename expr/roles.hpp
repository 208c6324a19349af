// The roles of symbols, set by the model where it creates them (the derivation's unknowns, the
// named classes' inputs, the documents' renamed components), read by the printers. A role is
// what a symbol stands for, never guessed from its name: a symbol the reader of a problem file
// creates for a name the user wrote has none, so it prints as the user wrote it ("w" is w, not
// ω, whatever it stands for).
//   angular_velocity   its leading w prints as ω in text (w′_z1 -> ω′_z1); LaTeX shows the
//                      TeX name the creator gave (\omega_{z1}).
// The registry is keyed by the symbol's identity (GiNaC's serial number, unique in a process),
// not by its name, and holds no reference to the symbol.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace impactgen::expr
{

enum class symbol_role { none, angular_velocity };

/// Records the symbol's role (thread-safe); returns the symbol.
const GiNaC::symbol &set_role(const GiNaC::symbol &s, symbol_role role);
/// The symbol's role, none unless set_role gave it one.
symbol_role role_of(const GiNaC::symbol &s);
/// A new symbol with the role (tex_name empty: GiNaC's TeX form of the name).
GiNaC::symbol symbol_with_role(const std::string &name, const std::string &tex_name, symbol_role role);

} // namespace impactgen::expr
