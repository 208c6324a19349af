// impactgen: the command-line face of the library. Each subcommand parses its
// arguments, builds a problem, calls the library and chooses a printer.
#include "cli/address_layout.hpp"
#include "cli/commands.hpp"
#include "exercises/exercises.hpp"
#include "names/escape.hpp"
#include "print/answer.hpp"
#include "print/expression.hpp"
#include "print/formulas.hpp"
#include "symbolic/contact_law.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/named_systems.hpp"
#include "symbolic/system.hpp"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <thread>

using namespace impactgen;

problem impactgen::cli::load(const std::string &what)
{
    if (const named_class *c = find_named_class(what))
        return c->build();
    if (!std::filesystem::exists(what)) {
        std::string names;
        for (const named_class &c : named_classes())
            names += (names.empty() ? "" : ", ") + c.name;
        for (const named_class &c : friction_classes())
            names += ", " + c.name;
        for (const named_class &c : system_classes())
            names += ", " + c.name;
        for (const named_class &c : law_classes())
            names += ", " + c.name;
        throw input_error(what + ": neither a named class (" + names + ") nor an existing problem file");
    }
    problem p = load_problem_file(what);
    for (const std::string &w : p.warnings)
        std::cerr << "impactgen: warning: " << what << ": " << w << "\n";
    return p;
}

namespace
{
using impactgen::cli::load;

int cmd_list()
{
    for (const named_class &c : named_classes()) {
        derivation d = derive(c.build());
        std::printf("%-16s %2zu unknowns  %s\n", c.name.c_str(), d.count_unknowns(), c.description.c_str());
    }
    std::printf("\nwith Coulomb friction (past the notes; regimes stick and slide):\n");
    for (const named_class &c : friction_classes())
        std::printf("%-22s %s\n", c.name.c_str(), c.description.c_str());
    std::printf("\nwith friction, restitution followed through the impact (Routh's process; law in the class):\n");
    for (const named_class &c : law_classes())
        std::printf("%-22s %s\n", c.name.c_str(), c.description.c_str());
    std::printf("\nsystems (past the notes; joints, several contacts, the contacts that act decided exactly):\n");
    for (const named_class &c : system_classes())
        std::printf("%-22s %s\n", c.name.c_str(), c.description.c_str());
    return 0;
}

// solve --set a=1,b=2: every symbol given an exact value; a name the problem does not have,
// or a value that is not exact, is refused naming --set.
problem with_values(const problem &p, const std::string &set)
{
    if (set.empty())
        return p;
    GiNaC::lst values;
    const std::vector<GiNaC::symbol> params = p.parameters();
    std::size_t start = 0;
    while (start <= set.size()) {
        std::size_t comma = set.find(',', start);
        if (comma == std::string::npos)
            comma = set.size();
        const std::string kv = set.substr(start, comma - start);
        start = comma + 1;
        const std::size_t eq = kv.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
            throw input_error("--set " + impactgen::names::display_text(kv, 80) + ": expected SYMBOL=VALUE");
        const std::string name = kv.substr(0, eq);
        const GiNaC::symbol *sym = nullptr;
        for (const GiNaC::symbol &s : params)
            if (s.get_name() == name)
                sym = &s;
        if (!sym)
            throw input_error("--set " + impactgen::names::display_text(name, 80) + ": the problem has no such symbol");
        const GiNaC::ex v = parse_value(kv.substr(eq + 1), true, "--set " + name);
        for (auto i = v.preorder_begin(); i != v.preorder_end(); ++i)
            if (GiNaC::is_a<GiNaC::symbol>(*i))
                throw input_error("--set " + name + ": expected a value without symbols");
        values.append(*sym == v);
    }
    problem q = substitute(p, values);
    validate(q);
    return q;
}

int cmd_solve(const std::string &what, bool json, const std::string &set)
{
    problem p = with_values(load(what), set);
    auto params = p.parameters();
    if (!params.empty()) {
        std::string names;
        for (const auto &s : params)
            names += (names.empty() ? "" : ", ") + s.get_name();
        throw input_error(what + ": solve needs numbers, but the problem has symbols (" +
                          impactgen::names::display_text(names, 120) + "); use 'impactgen formulas' for closed forms");
    }
    if (p.is_system()) { // format version 3: several contacts, joints, sequential impacts
        const system_answer a = solve_system(p);
        std::cout << (json ? print::system_answer_json(p, a).dump(2) + "\n" : print::system_answer_text(p, a));
        return 0;
    }
    derivation d = derive(p);
    const regime_case c = select_candidate(d, solve_impact(d));
    if (json)
        std::cout << print::answer_json(d, c, false).dump(2) << "\n";
    else
        std::cout << print::answer_text(d, c);
    return 0;
}

int cmd_formulas(const std::string &what, const std::string &format, bool jacobian, const std::string &wrt)
{
    problem p = load(what);
    if (p.is_system()) { // format version 3: every candidate of the law with its conditions
        if (jacobian)    // every candidate set's closed form differentiated (symbolic/system_jacobian.hpp)
            return cli::system_jacobian_formulas(p, format, wrt);
        std::cout << (format == "json" ? print::system_formulas_json(p).dump(2) + "\n"
                                       : print::system_formulas_text(p, format == "latex"));
        return 0;
    }
    const jacobian_route route = law_traits_of(p).jacobian; // the contact law's (symbolic/contact_law.hpp)
    if (jacobian && route == jacobian_route::per_phase_sequence)
        return cli::process_jacobian_formulas(p, format, wrt);
    if (jacobian && route == jacobian_route::per_regime)
        return cli::friction_jacobian_formulas(p, format, wrt);
    if (jacobian) { // the closed form and its derivatives, from one plan (the same symbols)
        codegen::plan pl = cli::jacobian_plan_for(p, wrt);
        if (format == "json") {
            nlohmann::ordered_json a = print::answer_json(pl.deriv, pl.sol, true);
            a["jacobian"] = cli::jacobian_json(pl);
            std::cout << a.dump(2) << "\n";
        } else if (format == "latex") {
            std::cout << print::formulas_latex(pl.deriv, pl.sol) << cli::jacobian_latex(pl);
        } else {
            std::cout << print::formulas_text(pl.deriv, pl.sol) << cli::jacobian_text(pl);
        }
        return 0;
    }
    derivation d = derive(p);
    const impact_solution s = solve_impact(d);
    if (format == "json")
        std::cout << print::formulas_json(d, s).dump(2) << "\n";
    else if (format == "latex")
        std::cout << print::formulas_latex(d, s);
    else
        std::cout << print::formulas_text(d, s);
    return 0;
}

int cmd_bench(int repeats)
{
    using clock = std::chrono::steady_clock;
    double total = 0;
    std::printf("%-16s %12s %12s   (best of %d, derivation + closed-form solution)\n", "class", "ms", "steps", repeats);
    for (const named_class &c : named_classes()) {
        double best = 1e300;
        std::size_t steps = 0;
        for (int r = 0; r < repeats; ++r) {
            auto t0 = clock::now();
            derivation d = derive(c.build());
            solution s = solve(d);
            auto t1 = clock::now();
            steps = s.steps.size();
            best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        total += best;
        std::printf("%-16s %12.3f %12zu\n", c.name.c_str(), best, steps);
    }
    std::printf("%-16s %12.3f   (target: < 250 ms for all six)\n", "all classes", total);
    // The systems: derivation + every closed-form candidate of the law (system_candidates).
    std::printf("\n%-22s %12s %12s   (best of %d, derivation + closed-form candidates)\n", "system class", "ms",
                "candidates", repeats);
    double slowest = 0;
    for (const named_class &c : system_classes()) {
        double best = 1e300;
        std::size_t candidates = 0;
        for (int r = 0; r < repeats; ++r) {
            auto t0 = clock::now();
            const problem p = c.build();
            derivation d = derive(p);
            candidates = system_candidates(p).size();
            auto t1 = clock::now();
            best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        slowest = std::max(slowest, best);
        std::printf("%-22s %12.3f %12zu\n", c.name.c_str(), best, candidates);
    }
    std::printf("%-22s %12.3f   (target: <= 500 ms each)\n", "slowest system class", slowest);
    return 0;
}

} // namespace

namespace
{
struct formulas_args {
    bool jacobian = false;
    std::string wrt;
};
int dispatch(const std::function<int()> &extra_action, CLI::App *list, CLI::App *solve_cmd, CLI::App *formulas,
             CLI::App *bench, const std::string &what, bool json, const std::string &format, int repeats,
             const formulas_args &fa, const std::string &set);

// --help and --version print and exit 0; a usage error is one line and exit 2.
int parse_error(CLI::App &app, const CLI::ParseError &e, int argc, char **argv)
{
    if (e.get_exit_code() == 0) { // --help, --version
        app.exit(e);
        std::cout.flush();
        return std::cout ? 0 : 1;
    }
    // A usage error: one line, like every other refusal.
    std::string what = e.what();
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
        std::string known;
        for (const CLI::App *sub : app.get_subcommands({}))
            known += (known.empty() ? "" : ", ") + sub->get_name();
        what = "unknown subcommand \"" + std::string(argv[1]) + "\" (one of " + known + ")";
    }
    std::cerr << "impactgen: error: " << impactgen::names::display_text(what)
              << " (usage: impactgen --help, or impactgen SUBCOMMAND --help)\n";
    return 2;
}

void start_time_budget(CLI::App &app, CLI::App *bench, double time_limit)
{
    // The time budget: every input the reader accepts is done in well under a
    // second; a run past the budget is stopped with a message, never left to hang.
    const bool limited = time_limit > 0 && (!*bench || app.get_option("--time-limit")->count() > 0);
    // A sheet explains every exercise: its default budget grows with --count (2 s each).
    if (CLI::App *sheet = app.get_subcommand("exercises"); *sheet && app.get_option("--time-limit")->count() == 0) {
        const CLI::Option *count = sheet->get_option("--count");
        // --count not given: its default
        time_limit += 2 * (count->count() > 0 ? count->as<double>() : exercises::options{}.count);
    }
    if (limited)
        std::thread([time_limit] {
            std::this_thread::sleep_for(std::chrono::duration<double>(time_limit));
            std::fprintf(stderr, "impactgen: error: stopped after the time budget of %g s (--time-limit)\n",
                         time_limit);
            std::fflush(stderr);
            std::_Exit(1);
        }).detach();
}
} // namespace

int main(int argc, char **argv)
{
    // The same output in every run, whatever the address layout (docs/architecture.md).
    impactgen::cli::fix_address_layout(argv);
    // A closed pipe (impactgen explain ... | head) is a failed write, reported
    // like any other, not a death by SIGPIPE.
    std::signal(SIGPIPE, SIG_IGN);
    CLI::App app{"impactgen: derive, solve, teach and generate code for smooth rigid-body impact"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("impactgen ") + IMPACTGEN_VERSION);

    auto *list = app.add_subcommand("list", "List the named impact classes: name, unknowns, description");

    std::string what;
    bool json = false;
    auto *solve_cmd = app.add_subcommand("solve", "Solve a numeric problem file exactly (rational arithmetic)");
    solve_cmd->add_option("problem", what, "PROBLEM.json in the impact problem format, or CLASS with --set")
        ->required();
    solve_cmd->add_flag("--json", json, "print the answer object of the problem format (decimals)");
    std::string set;
    solve_cmd->add_option("--set", set,
                          "values of the symbols of a named class or a problem file, e.g. m=2,l=1/2 (exact)");

    std::string format = "text";
    auto *formulas = app.add_subcommand("formulas", "Closed-form formulas for a named class or a problem file");
    formulas->add_option("problem", what, "CLASS (see 'impactgen list') or PROBLEM.json")->required();
    formulas->add_option("--format", format, "text, latex or json")->check(CLI::IsMember({"text", "latex", "json"}));
    bool jacobian = false;
    std::string wrt;
    formulas->add_flag("--jacobian", jacobian,
                       "also the derivatives of the impact map d(outputs after impact)/d(inputs), as codegen "
                       "--jacobian computes them; with Coulomb friction, per regime (stick, each slide; the 3-D "
                       "slide without a closed form through the implicit function theorem of its angle equation); "
                       "with friction under \"poisson\" or \"energetic\", per phase sequence of Routh's process; "
                       "for a system, the velocities after impact per candidate set");
    formulas->add_option("--wrt", wrt,
                         "comma-separated inputs to differentiate by (default: every symbol); implies --jacobian");

    int repeats = 5;
    auto *bench = app.add_subcommand("bench", "Time derivation + closed-form solution of every named class");
    bench->add_option("--repeats", repeats, "repetitions per class (best is reported)")->check(CLI::Range(1, 1000));

    double time_limit = 10;
    app.add_option("--time-limit", time_limit,
                   "seconds a command may run before it stops with an error (default 10, exercises 10 + 2 per "
                   "exercise; 0: no limit; bench: no limit unless given)")
        ->check(CLI::Range(0.0, 86400.0));

    std::function<int()> extra_action;
    impactgen::cli::register_explain(app, extra_action);
    impactgen::cli::register_codegen(app, extra_action);
    impactgen::cli::register_exercises(app, extra_action);

    try {
        app.parse(argc, argv);
        if (!std::isfinite(time_limit))
            throw CLI::ValidationError("--time-limit", "must be a finite number of seconds");
    } catch (const CLI::ParseError &e) {
        return parse_error(app, e, argc, argv);
    }
    auto run_command = [&] {
        const bool wrt_given = formulas->get_option("--wrt")->count() > 0;
        if (wrt_given && wrt.empty())
            throw input_error("--wrt: no input named (expected input names separated by commas)");
        return dispatch(extra_action, list, solve_cmd, formulas, bench, what, json, format, repeats,
                        {jacobian || wrt_given, wrt}, set);
    };
    start_time_budget(app, bench, time_limit);
    try {
        int rc = run_command();
        std::cout.flush();
        if (!std::cout)
            throw input_error("cannot write to standard output");
        return rc;
    } catch (const input_error &e) {
        std::cerr << "impactgen: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception &e) {
        std::cerr << "impactgen: error: " << impactgen::names::display_text(e.what()) << "\n";
        return 1;
    }
}

namespace
{
int dispatch(const std::function<int()> &extra_action, CLI::App *list, CLI::App *solve_cmd, CLI::App *formulas,
             CLI::App *bench, const std::string &what, bool json, const std::string &format, int repeats,
             const formulas_args &fa, const std::string &set)
{
    {
        if (*list)
            return cmd_list();
        if (*solve_cmd)
            return cmd_solve(what, json, set);
        if (*formulas)
            return cmd_formulas(what, format, fa.jacobian, fa.wrt);
        if (*bench)
            return cmd_bench(repeats);
        if (extra_action)
            return extra_action();
    }
    return 0;
}
} // namespace
