// Tools for the tests that compile explain's LaTeX: run a command, read a file,
// compile a document with pdflatex and read its log. Header-only; everything is
// inline in latex_tools so that several test files can include it.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace impactgen::print::layout {
// The width model of the LaTeX layout (print/explain_print.cpp), declared here
// only: the printers need no header for it, the tests check against it.
double estimated_width_em(const std::string& tex); ///< the estimated width of math TeX, em of the 10pt body font
double row_budget_em();                            ///< what a displayed line may fill, em
} // namespace impactgen::print::layout

namespace latex_tools {

namespace fs = std::filesystem;

/// The standard output of a shell command; `status` as pclose returns it.
inline std::string run(const std::string& command, int& status)
{
    std::string out;
    FILE* f = popen(command.c_str(), "r");
    if (!f) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0)
        out.append(buf.data(), n);
    status = pclose(f);
    return out;
}

inline std::string read_file(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream os;
    os << in.rdbuf();
    return os.str();
}

inline bool have_pdflatex() { return std::system("command -v pdflatex > /dev/null 2>&1") == 0; }

/// The message a test skips with when pdflatex is absent: loud, with the fix.
inline const char* no_pdflatex_message()
{
    return "\n*** pdflatex NOT FOUND: the LaTeX output of explain is NOT CHECKED. "
           "Install it with: bash scripts/install-deps.sh --tests ***\n";
}

/// How many times `needle` occurs in `hay`.
inline int count(const std::string& hay, const std::string& needle)
{
    int n = 0;
    for (std::size_t at = hay.find(needle); at != std::string::npos; at = hay.find(needle, at + needle.size()))
        ++n;
    return n;
}

/// One document compiled: the exit status of the last run, its log, its pages.
struct compiled {
    int status = -1;
    std::string log;
    int pages = 0;
    int overfull_hbox = 0, overfull_vbox = 0, undefined_refs = 0, multiply_defined = 0;
};

/// Compiles `tex` with pdflatex in a fresh directory, `runs` times (2: references
/// resolved), and reads the last log. The directory is removed afterwards.
inline compiled compile(const std::string& tex, const std::string& name, int runs = 2)
{
    compiled out;
    fs::path dir = fs::temp_directory_path() / ("impactgen-latex-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "doc.tex", std::ios::binary) << tex;
    for (int k = 0; k < runs; ++k) {
        run("cd '" + dir.string() + "' && pdflatex -interaction=nonstopmode -halt-on-error doc.tex > /dev/null 2>&1",
            out.status);
        if (out.status != 0)
            break;
    }
    out.log = read_file(dir / "doc.log");
    out.overfull_hbox = count(out.log, "Overfull \\hbox");
    out.overfull_vbox = count(out.log, "Overfull \\vbox");
    out.undefined_refs = count(out.log, "LaTeX Warning: Reference");
    out.multiply_defined = count(out.log, "multiply defined");
    // "Output written on doc.pdf (7 pages, 123456 bytes)."
    std::size_t at = out.log.find("Output written on doc.pdf (");
    if (at != std::string::npos)
        out.pages = std::atoi(out.log.c_str() + at + std::string("Output written on doc.pdf (").size());
    fs::remove_all(dir);
    return out;
}

/// The lines of the log around its first `needle`, for a failure message.
inline std::string around(const std::string& log, const std::string& needle)
{
    std::size_t at = log.find(needle);
    if (at == std::string::npos)
        return log.substr(log.size() > 2000 ? log.size() - 2000 : 0);
    return log.substr(at, 1200);
}

} // namespace latex_tools
