// The quiz in Moodle's question XML format: one numerical question per asked quantity, the
// exercise's statement in its text, the answer with an absolute tolerance of 1% of the
// value (at least 0.005), and the answer file's place in <idnumber> ("03/normal_impulse").
#include "exercises/detail.hpp"

#include "names/escape.hpp"
#include "print/expression.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace impactgen::exercises::detail
{

namespace
{

std::string tolerance_of(const GiNaC::ex &value)
{
    const GiNaC::ex v = value.evalf();
    const double x = GiNaC::is_a<GiNaC::numeric>(v) ? GiNaC::ex_to<GiNaC::numeric>(v).to_double() : 0;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", std::max(0.01 * std::abs(x), 0.005));
    return buf;
}

std::string xml(const std::string &s)
{
    return names::xml_text(s);
}

/// The feedback of an answer: its exact value, or for a root found numerically (3-D sliding) its
/// 15 significant digits: its further digits follow the order of evaluation, not the seed.
std::string feedback_of(const GiNaC::ex &v)
{
    if (GiNaC::is_a<GiNaC::numeric>(v) && !GiNaC::ex_to<GiNaC::numeric>(v).is_rational())
        return "value " + print::decimal(v) + " (a root found numerically)";
    return "exact value " + print::parser_syntax(v);
}

} // namespace

std::string quiz_xml(const sheet &s)
{
    std::ostringstream os;
    os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<quiz>\n"
       << "<question type=\"category\">\n<category><text>$course$/top/" << xml("Exercises: " + s.title)
       << "</text></category>\n</question>\n";
    for (std::size_t k = 0; k < s.exercises.size(); ++k) {
        const exercise &e = s.exercises[k];
        const std::string nn = (k + 1 < 10 ? "0" : "") + std::to_string(k + 1);
        std::string statement_html = "<p>Exercise " + std::to_string(k + 1) + ":</p><ul>";
        for (const std::string &item : statement(e.prob, format::html, s.units))
            statement_html += "<li>" + item + "</li>";
        statement_html += "</ul>";
        for (const quantity &q : e.asked) {
            const std::string ask =
                "<p>Give the " + names::html_text(q.words) +
                (q.unit.empty() ? "" : " in " + names::html_text(q.unit == "N s" ? "N s" : q.unit)) + ".</p>";
            os << "<question type=\"numerical\">\n"
               << "<name><text>" << xml("Exercise " + std::to_string(k + 1) + ": " + q.words) << "</text></name>\n"
               << "<questiontext format=\"html\"><text>" << xml(statement_html + ask) << "</text></questiontext>\n"
               << "<generalfeedback format=\"html\"><text></text></generalfeedback>\n"
               << "<defaultgrade>1.0000000</defaultgrade>\n<penalty>0.3333333</penalty>\n<hidden>0</hidden>\n"
               << "<idnumber>" << xml(nn + q.pointer) << "</idnumber>\n"
               << "<answer fraction=\"100\" format=\"moodle_auto_format\">\n<text>" << print::decimal(q.exact)
               << "</text>\n<feedback format=\"html\"><text>" << xml(feedback_of(q.exact))
               << "</text></feedback>\n<tolerance>" << tolerance_of(q.exact) << "</tolerance>\n</answer>\n"
               << "<unitgradingtype>0</unitgradingtype>\n<unitpenalty>0.1000000</unitpenalty>\n"
               << "<showunits>3</showunits>\n<unitsleft>0</unitsleft>\n</question>\n";
        }
    }
    os << "</quiz>\n";
    return os.str();
}

} // namespace impactgen::exercises::detail
