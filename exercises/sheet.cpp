// The sheet in LaTeX and HTML, and every file of the output folder.
#include "exercises/detail.hpp"

#include "names/escape.hpp"
#include "print/explain.hpp"

#include <sstream>

namespace impactgen::exercises
{
namespace detail
{

namespace
{

std::string number_of(std::size_t k)
{
    return (k < 10 ? "0" : "") + std::to_string(k);
}

} // namespace

std::string sheet_latex(const sheet &s)
{
    std::ostringstream os;
    // A4, 2.5 cm margins, Computer Modern (Type 1), as explain's documents; every package in
    // texlive-latex-base but tikz (texlive-pictures). Each figure at most 0.6 of the line.
    os << "% Written by impactgen exercises. Compile with pdflatex (amsmath, geometry, tikz).\n"
          "\\documentclass[11pt,a4paper]{article}\n"
          "\\usepackage[margin=2.5cm]{geometry}\n"
          "\\usepackage{amsmath}\n"
          "\\usepackage{tikz}\n"
          "\\newsavebox{\\figurebox}\n"
          "\\setlength{\\parindent}{0pt}\n"
          "\\setlength{\\parskip}{0.5em}\n"
          "\\setlength{\\emergencystretch}{3em}\n"
          "\\begin{document}\n\\begin{center}\n{\\LARGE Exercises: "
       << names::latex_text(s.title) << "}\n\\end{center}\n";
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        const exercise &e = s.exercises[k];
        // one exercise stays on one page: statement, figure and question together
        os << "\n\\noindent\\begin{minipage}{\\linewidth}\n\\setlength{\\parskip}{0.5em}\n\\subsection*{Exercise "
           << k + 1 << "}\n\\begin{itemize}\n";
        for (const std::string &item : statement(e.prob, format::tex, s.units))
            os << "  \\item " << item << "\n";
        os << "\\end{itemize}\n"
           << "\\begin{center}\n\\sbox{\\figurebox}{%\n"
           << figure_of(e.prob, format::tex)
           << "%\n}%\n"
              "\\ifdim\\ht\\figurebox>4.5cm\\sbox{\\figurebox}{\\resizebox{!}{4.5cm}{\\usebox{\\figurebox}}}\\fi\n"
              "\\ifdim\\wd\\figurebox>0.6\\linewidth\\sbox{\\figurebox}{\\resizebox{0.6\\linewidth}{!}{"
              "\\usebox{\\figurebox}}}\\fi\n"
              "\\usebox{\\figurebox}\n\\end{center}\n"
           << find_sentence(e.prob, format::tex) << "\n\\end{minipage}\n\\par\\bigskip\n";
    }
    os << "\n\\newpage\n\\section*{Answers}\n";
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        os << "\n\\subsection*{Exercise " << k + 1 << "}\n\\begin{itemize}\n";
        for (const std::string &a : short_answers(s.exercises[k], format::tex))
            os << "  \\item " << a << "\n";
        os << "\\end{itemize}\n";
    }
    os << "\n\\end{document}\n";
    return os.str();
}

std::string sheet_html(const sheet &s)
{
    std::ostringstream os;
    const std::string title = names::html_text("Exercises: " + s.title);
    os << "<!DOCTYPE html>\n"
          "<!-- Written by impactgen exercises: one self-contained page. -->\n"
          "<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
          "<title>"
       << title
       << "</title>\n<style>\n"
          "  body { max-width: 50em; margin: 2.5em auto 4em; padding: 0 1.5em; color: #1a1a1a;\n"
          "         font-family: \"Latin Modern Roman\", \"STIX Two Text\", Cambria, Georgia, serif; font-size: 17px; "
          "line-height: 1.5; }\n"
          "  h1 { font-size: 1.75em; font-weight: normal; text-align: center; margin: 0 0 1.2em; }\n"
          "  h2 { font-size: 1.3em; margin: 1.8em 0 0.6em; border-bottom: 1px solid #bbb; }\n"
          "  h3 { font-size: 1.1em; margin: 1.2em 0 0.4em; }\n"
          "  figure { margin: 1em 0; text-align: center; }\n"
          "  figure svg { max-width: 60%; height: auto; }\n"
          "  section.answers { break-before: page; }\n"
          "</style>\n</head>\n<body>\n<h1>"
       << title << "</h1>\n";
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        const exercise &e = s.exercises[k];
        os << "\n<section class=\"exercise\" id=\"exercise-" << k + 1 << "\">\n<h2>Exercise " << k + 1
           << "</h2>\n<ul>\n";
        for (const std::string &item : statement(e.prob, format::html, s.units))
            os << "<li>" << item << "</li>\n";
        os << "</ul>\n<figure>\n"
           << figure_of(e.prob, format::html) << "\n</figure>\n<p>" << find_sentence(e.prob, format::html)
           << "</p>\n</section>\n";
    }
    os << "\n<section class=\"answers\">\n<h2>Answers</h2>\n";
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        os << "<h3>Exercise " << k + 1 << "</h3>\n<ul>\n";
        for (const std::string &a : short_answers(s.exercises[k], format::html))
            os << "<li>" << a << "</li>\n";
        os << "</ul>\n";
    }
    os << "</section>\n</body>\n</html>\n";
    return os.str();
}

} // namespace detail

std::map<std::string, std::string> sheet_files(const sheet &s)
{
    std::map<std::string, std::string> out;
    out["sheet.tex"] = detail::sheet_latex(s);
    out["sheet.html"] = detail::sheet_html(s);
    out["quiz.xml"] = detail::quiz_xml(s);
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        const exercise &e = s.exercises[k];
        const std::string nn = detail::number_of(k + 1);
        out["problems/" + nn + ".json"] = problem_json(e.prob).dump(2) + "\n";
        out["answers/" + nn + ".json"] = e.answer.dump(2) + "\n";
        // The full worked solution: the explain document of the exercise's own numbers.
        const print::document doc = detail::worked_solution(e.prob);
        out["solutions/" + nn + ".tex"] = print::explain_latex(doc);
        out["solutions/" + nn + ".html"] = print::explain_html(doc);
    }
    return out;
}

} // namespace impactgen::exercises
