// impactgen exercises CLASS|PROBLEM.json --count N --seed S [--regime R] --out DIR: an
// exercise sheet of N variants with simple numbers (exercises/exercises.hpp), written to DIR:
// sheet.tex and sheet.html (statement, figure, short answers), solutions/NN.tex and .html
// (the worked solution of each), problems/NN.json, answers/NN.json (solve --json) and quiz.xml
// (Moodle). The same seed writes the same files byte for byte: the search for short answers is
// bounded by a count of draws, never by the clock; --time-limit is its only safety net.
#include "cli/commands.hpp"
#include "exercises/exercises.hpp"
#include "names/escape.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <system_error>

namespace impactgen::cli
{

namespace
{

void write_all(const std::string &dir, const std::map<std::string, std::string> &files)
{
    namespace fs = std::filesystem;
    const std::string shown = names::display_text(dir, 120);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw input_error("--out " + shown + ": cannot create the folder" + (ec ? " (" + ec.message() + ")" : ""));
    for (const auto &[name, content] : files) {
        const fs::path path = fs::path(dir) / name;
        fs::create_directories(path.parent_path(), ec);
        if (fs::exists(path) && !fs::is_regular_file(path))
            throw input_error("--out " + shown + ": " + name + " exists and is not a regular file");
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << content;
        out.flush();
        if (!out)
            throw input_error("--out " + shown + ": cannot write " + name);
    }
}

} // namespace

void register_exercises(CLI::App &app, std::function<int()> &action)
{
    struct options {
        std::string what, out, regime;
        int count = 10;
        std::uint64_t seed = 1;
    };
    auto opt = std::make_shared<options>();
    auto *cmd = app.add_subcommand(
        "exercises", "Exercise sheet of variants with simple numbers: answers, worked solutions, Moodle quiz");
    cmd->add_option("problem", opt->what, "CLASS (see 'impactgen list') or PROBLEM.json")->required();
    cmd->add_option("--count", opt->count, "number of exercises, 1 to 99 (default 10)");
    cmd->add_option(
        "--seed", opt->seed,
        "seed of the variants (default 1): the same seed, the same files however fast or loaded the machine (the "
        "search for short answers makes a number of draws sized for the problem, never cut by "
        "the clock; a search past --time-limit is an error, no sheet)");
    cmd->add_option("--regime", opt->regime,
                    "keep every variant in this regime: smooth, stick or slide (default: any, away from boundaries)");
    cmd->add_option("--out", opt->out,
                    "folder to write: sheet.tex, sheet.html, quiz.xml, problems/NN.json, answers/NN.json, "
                    "solutions/NN.tex and .html")
        ->required();
    cmd->callback([opt, &action] {
        action = [opt] {
            exercises::options o;
            o.count = opt->count;
            o.seed = opt->seed;
            o.regime = opt->regime;
            o.seconds = 0; // the command's --time-limit is the safety net
            const exercises::sheet s = exercises::make_sheet(load(opt->what), o);
            write_all(opt->out, exercises::sheet_files(s));
            std::cout << "impactgen: " << s.exercises.size() << " exercise" << (s.exercises.size() == 1 ? "" : "s")
                      << " written to " << names::display_text(opt->out, 120)
                      << " (sheet.tex, sheet.html, quiz.xml, problems/, answers/, solutions/)\n";
            return 0;
        };
    });
}

} // namespace impactgen::cli
