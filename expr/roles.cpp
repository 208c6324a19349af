#include "expr/roles.hpp"

#include <mutex>
#include <unordered_map>

namespace impactgen::expr
{

namespace
{

// GiNaC's serial number of a symbol: its identity (two symbols with one name are two symbols).
struct serial_of : GiNaC::symbol {
    static unsigned get(const GiNaC::symbol &s) { return s.*(&serial_of::serial); }
};

struct registry {
    std::mutex lock;
    std::unordered_map<unsigned, symbol_role> roles;
};

registry &the_registry()
{
    static registry r;
    return r;
}

} // namespace

const GiNaC::symbol &set_role(const GiNaC::symbol &s, symbol_role role)
{
    registry &r = the_registry();
    const std::lock_guard<std::mutex> guard(r.lock);
    if (role == symbol_role::none)
        r.roles.erase(serial_of::get(s));
    else
        r.roles[serial_of::get(s)] = role;
    return s;
}

symbol_role role_of(const GiNaC::symbol &s)
{
    registry &r = the_registry();
    const std::lock_guard<std::mutex> guard(r.lock);
    const auto it = r.roles.find(serial_of::get(s));
    return it == r.roles.end() ? symbol_role::none : it->second;
}

GiNaC::symbol symbol_with_role(const std::string &name, const std::string &tex_name, symbol_role role)
{
    const GiNaC::symbol s = tex_name.empty() ? GiNaC::symbol(name) : GiNaC::symbol(name, tex_name);
    set_role(s, role);
    return s;
}

} // namespace impactgen::expr
