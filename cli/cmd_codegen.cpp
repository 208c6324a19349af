// impactgen codegen: one dependency-free C++17 header with the specialised
// closed form of a named class or problem file (see codegen/codegen.hpp).
#include "cli/commands.hpp"
#include "codegen/codegen.hpp"
#include "names/identifier.hpp"

#include <filesystem>
#include <iostream>
#include <sstream>

namespace
{

std::vector<std::string> split(const std::string &s, char sep)
{
    std::vector<std::string> r;
    std::string item;
    std::istringstream is(s);
    while (std::getline(is, item, sep))
        if (!item.empty())
            r.push_back(item);
    return r;
}

struct codegen_args {
    std::string what, out_dir, output, name, ns = "impactgen::generated", params, set, wrt;
    bool inverse_inertia = false, inverse_mass = false, unit_normal = false, jacobian = false, rows = false;
};

int run(const codegen_args &a, CLI::Option *params_opt, CLI::Option *wrt_opt)
{
    using namespace impactgen;
    problem p = cli::load(a.what);
    codegen::options o;
    o.source = a.what;
    o.version = IMPACTGEN_VERSION;
    o.ns = a.ns;
    if (a.name.empty()) {
        // The class or file stem made a safe identifier ("9-ball.json" -> x_9_ball).
        o.name = codegen::default_function_name(std::filesystem::path(a.what).stem().string());
    } else {
        o.name = a.name;
    }
    o.params_given = params_opt->count() > 0;
    o.params = split(a.params, ',');
    for (const std::string &kv : split(a.set, ',')) {
        auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
            throw input_error("--set " + kv + ": expected SYMBOL=VALUE");
        o.set.push_back({kv.substr(0, eq), kv.substr(eq + 1)});
    }
    o.inverse_inertia = a.inverse_inertia;
    o.inverse_mass = a.inverse_mass;
    o.unit_normal = a.unit_normal;
    o.jacobian = a.jacobian || wrt_opt->count() > 0;
    o.rows = a.rows;
    if (wrt_opt->count() > 0 && a.wrt.empty())
        throw input_error("--wrt: no input named (expected input names separated by commas)");
    cli::split_wrt(a.wrt, o.wrt);
    codegen::header h;
    try {
        h = codegen::generate(p, o);
    } catch (const codegen::option_error &e) {
        // The library names the option by kind; here it becomes its flag.
        std::string message = std::string("--") + codegen::option_error::option_name(e.which) + ": " + e.what();
        if (e.which == codegen::option_error::params && !e.symbol.empty())
            message += " (add it to --params, or give it a value with --set " + e.symbol + "=VALUE)";
        throw input_error(message);
    }
    std::string path = a.output;
    if (path.empty() && !a.out_dir.empty())
        path = (std::filesystem::path(a.out_dir) / (o.name + ".hpp")).string();
    if (path.empty()) {
        std::cout << h.text;
        std::cout.flush();
        if (!std::cout)
            throw input_error("cannot write the header to standard output");
        return 0;
    }
    auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty())
        std::filesystem::create_directories(parent);
    bool wrote = codegen::write_if_changed(path, h.text);
    std::cerr << "impactgen: " << path << (wrote ? " written" : " unchanged") << " (" << h.formula.add << " add/sub, "
              << h.formula.mul << " mul, " << h.formula.div << " div, " << h.formula.sqrt << " sqrt)\n";
    return 0;
}

} // namespace

void impactgen::cli::register_codegen(CLI::App &app, std::function<int()> &action)
{
    auto args = std::make_shared<codegen_args>();
    auto *cmd =
        app.add_subcommand("codegen", "Generate a dependency-free C++17 header with the specialised closed form");
    cmd->add_option("problem", args->what, "CLASS (see 'impactgen list') or PROBLEM.json")->required();
    cmd->add_option("--out", args->out_dir, "write DIR/NAME.hpp (only when its content changes)");
    cmd->add_option("-o,--output", args->output,
                    "write exactly this file (only when its content changes); overrides --out");
    cmd->add_option(
        "--name", args->name,
        "function name, a C++ identifier (default: the class or file stem made one: '-' -> '_', x_ before a digit)");
    cmd->add_option("--namespace", args->ns, "namespace of the generated code (default impactgen::generated)");
    auto *params =
        cmd->add_option("--params", args->params,
                        "comma-separated symbols (or quantity names such as m1, v_x_ball, I1_tt; of a system also "
                        "e_c0, mu_c0, O_x_c0, n_x_c0 per contact, J_x_j0 per joint) that stay function "
                        "parameters, in this order; every other value is folded in as a constant");
    cmd->add_option("--set", args->set, "values of symbols that are not parameters, e.g. m1=2,l=1/2 (exact)");
    cmd->add_flag("--inverse-inertia", args->inverse_inertia,
                  "inertia inputs of free bodies are inverses: 3-D tensors I^-1, planar 1/I (engine convention)");
    cmd->add_flag("--inverse-mass", args->inverse_mass, "mass inputs are inverse masses 1/m (engine convention)");
    cmd->add_flag("--unit-normal", args->unit_normal,
                  "the normal inputs are a unit vector (engine convention): not normalised, checked to have length 1");
    cmd->add_flag("--rows", args->rows,
                  "also emit NAME_rows: the contact's Jacobian rows, effective masses along the normal and the "
                  "tangents and the bias of restitution, for an iterative (sequential-impulse) solver");
    cmd->add_flag("--jacobian", args->jacobian,
                  "also emit NAME_jacobian: the values and the dense Jacobian d(outputs)/d(inputs), derived exactly "
                  "(of a system: d(velocities after)/d(inputs) of the set that holds; with Coulomb friction under "
                  "Newton's law: d(velocities, impulses after)/d(inputs) of the regime that holds; under the laws "
                  "poisson and energetic: the same of the phase sequence that holds; ambiguous on a boundary; not for "
                  "sequential impacts)");
    auto *wrt = cmd->add_option("--wrt", args->wrt,
                                "comma-separated inputs the Jacobian differentiates by, in this order (default: every "
                                "input); implies --jacobian");
    cmd->parse_complete_callback(
        [args, params, wrt, &action] { action = [args, params, wrt] { return run(*args, params, wrt); }; });
}
