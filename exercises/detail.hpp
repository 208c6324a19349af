// Internal to exercises/: the statement of an exercise and its numbers, written once for
// LaTeX and HTML.
#pragma once

#include "exercises/exercises.hpp"
#include "print/explain.hpp"

#include <optional>

#include <string>
#include <vector>

namespace impactgen::exercises::detail
{

enum class format { tex, html };

/// Running text in one format: words escaped, numbers and vectors set as mathematics.
class text
{
public:
    explicit text(format f) : f_(f) {}
    text &w(const std::string &words);                          ///< words (escaped)
    text &raw(const std::string &markup);                       ///< markup of this format, as it is
    text &num(const GiNaC::ex &value);                          ///< an exact number: 3, 0.25, 1/3 (math)
    text &vec(const vec3 &v, int dimension);                    ///< (x, y) or (x, y, z) (math)
    text &sym(const std::string &tex, const std::string &html); ///< a symbol (math)
    text &unit(const std::string &u);                           ///< " kg" etc., or nothing when u is empty
    text &approx(const GiNaC::ex &value); ///< an answer: exact, and its decimal when not exact in 4 digits
    const std::string &str() const { return s_; }

private:
    std::string number(const GiNaC::ex &value) const; ///< the number's markup, without $...$
    format f_;
    std::string s_;
};

/// A contact's point and its normal, in words after "at the point ": "(x, y) m; <normal>, from
/// <body 1> into <body 2>, is (nx, ny)".
text &contact_geometry(text &t, const problem &p, const contact_spec &c, const std::string &normal, bool si);

/// The statement: one item per body, then the contact and the coefficients.
std::vector<std::string> statement(const problem &p, format f, bool units);
/// What is asked, as one sentence.
std::string find_sentence(const problem &p, format f);
/// A value a person would not write exactly: a root, or a fraction of many digits.
bool long_number(const GiNaC::ex &value);
/// The short answers of an exercise, one item each ("quantity = value unit").
std::vector<std::string> short_answers(const exercise &e, format f);
/// The decimal of an exact value, 4 significant digits ("-0.1429").
std::string decimal4(const GiNaC::ex &value);

/// RFC 6901: s as a reference token of a JSON pointer ("~" as "~0", "/" as "~1").
std::string json_pointer_token(const std::string &s);

/// Digits after the point of q when q is a terminating decimal (denominator 2^a 5^b), else -1.
int decimal_places(const GiNaC::numeric &q);
/// The figure of an exercise: TikZ or SVG.
std::string figure_of(const problem &p, format f);

/// A variant solved: `key` names its regime or set of regimes exactly (a slide with its sense),
/// `regime` says it for the sheet ("stick"; a system: its set, "{0 stick, 1 open}"), what is
/// asked, and the answer object as `solve --json` writes it.
struct outcome {
    std::string key, regime;
    std::vector<quantity> asked;
    nlohmann::ordered_json answer;
};

/// A system (exercises/systems.cpp): solved by its law, refused draws giving nothing.
std::optional<outcome> system_outcome(const problem &q);
/// The items of a system's statement after its bodies: each joint, each contact, the model of impacts.
std::vector<std::string> system_statement_items(const problem &p, format f, bool si);
/// What a system's exercise asks, as one sentence.
std::string system_find_sentence(const problem &p, format f);
/// Which contacts act in a system's answer, in words (the first short answer).
std::string system_regimes_in_words(const exercise &e, format f);
/// The worked solution of an exercise: the explain document of its numbers, system or not.
print::document worked_solution(const problem &p);

std::string sheet_latex(const sheet &s);
std::string sheet_html(const sheet &s);
std::string quiz_xml(const sheet &s);

} // namespace impactgen::exercises::detail
