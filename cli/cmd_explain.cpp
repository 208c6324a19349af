// impactgen explain CLASS|PROBLEM.json [--format text|markdown|latex|html] [--level summary|full]:
// the derivation walked through the way the lecture notes do it; with Coulomb
// friction, the way textbooks solve it (stick, else slide; every regime).
// html is one self-contained page (inline CSS, MathML, no script) to open in
// a browser or print.
#include "cli/commands.hpp"
#include "print/explain.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/routh.hpp"
#include "symbolic/system.hpp"

#include <iostream>
#include <memory>

namespace impactgen::cli
{

void register_explain(CLI::App &app, std::function<int()> &action)
{
    struct options {
        std::string what;
        std::string format = "text";
        std::string level = "full";
    };
    auto opt = std::make_shared<options>();
    auto *cmd = app.add_subcommand("explain", "Walk through the derivation and solution the way the lecture notes do");
    cmd->add_option("problem", opt->what, "CLASS (see 'impactgen list') or PROBLEM.json")->required();
    cmd->add_option("--format", opt->format,
                    "text (default), markdown, latex (a complete document) or html (one self-contained page, MathML)")
        ->check(CLI::IsMember({"text", "markdown", "latex", "html"}));
    cmd->add_option("--level", opt->level,
                    "full (default): the whole derivation; summary: one page, the set-up, the figure, the "
                    "results in a box and their closed forms")
        ->check(CLI::IsMember({"summary", "full"}));
    cmd->callback([opt, &action] {
        action = [opt] {
            problem p = load(opt->what);
            derivation d = derive(p);
            print::worked_example example;
            const bool has_example = find_named_class(opt->what) && print::notes_example(opt->what, example);
            const print::level depth = opt->level == "summary" ? print::level::summary : print::level::full;
            print::worked_example system_example;
            const bool has_system_example =
                p.is_system() && find_named_class(opt->what) && print::system_example(opt->what, system_example);
            const print::document doc =
                p.is_system() ? print::explain_system(d, has_system_example ? &system_example : nullptr, depth)
                              : print::explain(d, solve_impact(d), has_example ? &example : nullptr, depth);
            if (opt->format == "markdown")
                std::cout << print::explain_markdown(doc);
            else if (opt->format == "latex")
                std::cout << print::explain_latex(doc);
            else if (opt->format == "html")
                std::cout << print::explain_html(doc);
            else
                std::cout << print::explain_text(doc);
            return 0;
        };
    });
}

} // namespace impactgen::cli
