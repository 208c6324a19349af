// The symbolic engine as a C++ library (impactgen::symbolic, impactgen::print):
// derive the equations of an impact, solve them in closed form, print the
// formulas, check the physics symbolically, and (impactgen::codegen) make the
// C++ solver in-process, as `impactgen codegen` does.
//
//   derive [ball-on-ground.json]
#include "codegen/codegen.hpp"
#include "print/formulas.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/solution.hpp"

#include <cstdio>
#include <iostream>
#include <string>

using namespace impactgen;

namespace {

int failures = 0;

void expect_zero(const GiNaC::ex& e, const std::string& what)
{
    const bool ok = GiNaC::normal(e).is_zero();
    std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
    if (!ok) {
        std::cout << "      left over: " << GiNaC::normal(e) << "\n";
        ++failures;
    }
}

/// The closed form satisfies every equation it was derived from.
void expect_residuals_vanish(const derivation& d, const solution& s, const std::string& what)
{
    bool all = true;
    for (const ex& r : residuals(d, s))
        all = all && GiNaC::normal(r).is_zero();
    std::printf("%s: %s: %zu equations hold\n", all ? "ok  " : "FAIL", what.c_str(), d.count_equations());
    if (!all)
        ++failures;
}

} // namespace

int main(int argc, char** argv)
{
    // A named class of the lecture notes.
    const named_class* c = find_named_class("pinned-planar");
    if (!c) {
        std::printf("FAIL: named class pinned-planar not found\n");
        return 1;
    }
    derivation d = derive(c->build());
    solution s = solve(d);
    std::cout << "== " << c->name << ": " << c->description << "\n" << print::formulas_text(d, s) << "\n";
    expect_residuals_vanish(d, s, c->name);

    // The consumer's own problem: a ball bouncing on the ground.
    if (argc > 1) {
        problem p = load_problem_file(argv[1]);
        derivation db = derive(p);
        solution sb = solve(db);
        std::cout << "\n== " << argv[1] << "\n" << print::formulas_text(db, sb) << "\n";
        expect_residuals_vanish(db, sb, "ball on ground");

        const GiNaC::symbol e = symbol_named("e"), vx = symbol_named("vx"), vy = symbol_named("vy");
        const vec3& v_after = sb.after[1].velocity;
        // Newton's law against a wall of infinite mass: v'_n = -e v_n; smooth: v'_t = v_t.
        expect_zero(sb.expand_steps(v_after[1]) + e * vy, "rebound speed is e times the impact speed");
        expect_zero(sb.expand_steps(v_after[0]) - vx, "tangential velocity is unchanged");
        // The ground takes -(1 + e) m vy; the energy lost is (1 - e^2) m vy^2 / 2.
        const ex m = p.bodies[1].mass;
        expect_zero(sb.expand_steps(sb.normal_impulse) + (1 + e) * m * vy, "normal impulse is -(1 + e) m vy");
        expect_zero(sb.expand_steps(sb.energy_lost) - (1 - e * e) * m * vy * vy / 2,
                    "energy lost is (1 - e^2) m vy^2 / 2");

        codegen::options o;
        o.name = "ball_hits_ground";
        o.ns = "consumer";
        o.source = argv[1];
        o.params_given = true;
        o.params = {"e", "vx", "vy"};
        const codegen::header h = codegen::generate(p, o);
        const bool made = h.text.find("impact_status ball_hits_ground(T e, T vx, T vy,") != std::string::npos;
        std::printf("%s: codegen: %zu inputs, %zu outputs, %d add/sub, %d mul, %d div per call\n", made ? "ok  " : "FAIL",
                    h.inputs.size(), h.outputs.size(), h.formula.add, h.formula.mul, h.formula.div);
        if (!made)
            ++failures;
    }
    return failures == 0 ? 0 : 1;
}
