// tests of figure/: for every named class and every problem file of the
// project, draw() shows every body, O and e_n; the SVG is well-formed,
// self-contained and byte-identical run to run; the TikZ compiles with
// pdflatex inside 0.8\linewidth (skipped loudly without pdflatex or tikz);
// hostile body names come out inert; the geometry is the problem's (e_n along
// n, R at the pivot E, the shapes); degenerate and extreme values give finite
// numbers. IMPACTGEN_FIGURE_DUMP=DIR writes every figure there (.svg, .tex).
#include "figure/figure.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace impactgen;
using namespace impactgen::figure;

namespace {

struct case_t {
    std::string name; // a class name or a file path relative to the source tree
    problem p;
};

/// Every named class (smooth and with friction) and every problem file.
const std::vector<case_t>& cases()
{
    static const std::vector<case_t> all = [] {
        std::vector<case_t> out;
        for (const named_class& c : named_classes())
            out.push_back({c.name, c.build()});
        for (const named_class& c : friction_classes())
            out.push_back({c.name, c.build()});
        std::vector<std::string> files;
        for (const char* dir : {"/examples/problems", "/tests/explain"})
            for (const auto& entry : fs::directory_iterator(std::string(IMPACTGEN_SOURCE_DIR) + dir))
                if (entry.path().extension() == ".json")
                    files.push_back(entry.path().string());
        std::sort(files.begin(), files.end());
        for (const std::string& f : files)
            out.push_back({f.substr(std::string(IMPACTGEN_SOURCE_DIR).size() + 1), load_problem_file(f)});
        return out;
    }();
    return all;
}

std::string file_stem(const std::string& name)
{
    std::string s = fs::path(name).stem().string();
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)))
            c = '-';
    return s;
}

/// Writes the figures to IMPACTGEN_FIGURE_DUMP, when set, for a look.
void dump(const std::string& name, const drawing& g)
{
    const char* dir = std::getenv("IMPACTGEN_FIGURE_DUMP");
    if (!dir)
        return;
    fs::create_directories(dir);
    std::ofstream(fs::path(dir) / (file_stem(name) + ".svg")) << to_svg(g) << "\n";
    std::ofstream(fs::path(dir) / (file_stem(name) + ".tex")) << to_tikz(g) << "\n";
}

// ---------------------------------------------------------------------------
// A small XML checker: one root element <svg>, balanced tags, quoted
// attributes, entities that XML knows, nothing that runs or loads.

struct xml_report {
    bool ok = true;
    std::string why;
    std::vector<std::string> attribute_values; // of every element
    std::set<std::string> elements;
};

// "&amp;", "&lt;", "&gt;", "&quot;", "&apos;", "&#123;" (1-7 digits), "&#x1F;" (1-6 hex
// digits) at i. (Plain code, not <regex>: std::regex costs minutes to compile under ASan.)
bool entity_at(const std::string& s, std::size_t i)
{
    if (i >= s.size() || s[i] != '&')
        return false;
    for (const char* name : {"amp;", "lt;", "gt;", "quot;", "apos;"})
        if (s.compare(i + 1, std::char_traits<char>::length(name), name) == 0)
            return true;
    if (i + 1 >= s.size() || s[i + 1] != '#')
        return false;
    const bool hex = i + 2 < s.size() && s[i + 2] == 'x';
    std::size_t k = i + (hex ? 3 : 2), n = 0;
    while (k < s.size() && (hex ? std::isxdigit(static_cast<unsigned char>(s[k])) : std::isdigit(static_cast<unsigned char>(s[k])))) {
        ++k;
        ++n;
    }
    return n >= 1 && n <= (hex ? 6u : 7u) && k < s.size() && s[k] == ';';
}

xml_report check_xml(const std::string& s)
{
    xml_report r;
    auto fail = [&](const std::string& why, std::size_t at) {
        if (r.ok) {
            r.ok = false;
            r.why = why + " at byte " + std::to_string(at) + ": " + s.substr(at, 60);
        }
    };
    std::vector<std::string> open;
    bool root_done = false;
    std::size_t i = 0;
    while (i < s.size() && r.ok) {
        if (s[i] != '<') {
            if (s[i] == '&' && !entity_at(s, i))
                fail("bare &", i);
            if (s[i] == '>')
                fail("bare >", i);
            if (open.empty() && !std::isspace(static_cast<unsigned char>(s[i])))
                fail("text outside the root", i);
            ++i;
            continue;
        }
        if (s.compare(i, 2, "</") == 0) {
            const std::size_t end = s.find('>', i);
            if (end == std::string::npos)
                return fail("unterminated end tag", i), r;
            const std::string name = s.substr(i + 2, end - i - 2);
            if (open.empty() || open.back() != name)
                fail("end tag </" + name + "> does not match", i);
            else
                open.pop_back();
            if (open.empty())
                root_done = true;
            i = end + 1;
            continue;
        }
        if (root_done)
            return fail("a second root element", i), r;
        std::size_t j = i + 1;
        while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == ':'))
            ++j;
        const std::string name = s.substr(i + 1, j - i - 1);
        if (name.empty())
            return fail("not a tag", i), r;
        if (open.empty() && name != "svg")
            return fail("the root is not <svg>", i), r;
        r.elements.insert(name);
        std::set<std::string> seen;
        bool closed = false;
        while (j < s.size()) {
            while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j])))
                ++j;
            if (s.compare(j, 2, "/>") == 0) {
                closed = true;
                j += 2;
                break;
            }
            if (j < s.size() && s[j] == '>') {
                ++j;
                break;
            }
            std::size_t k = j;
            while (k < s.size() && (std::isalnum(static_cast<unsigned char>(s[k])) || s[k] == '-' || s[k] == ':'))
                ++k;
            const std::string attr = s.substr(j, k - j);
            if (attr.empty() || k + 1 >= s.size() || s[k] != '=' || s[k + 1] != '"')
                return fail("bad attribute", j), r;
            if (!seen.insert(attr).second)
                fail("repeated attribute " + attr, j);
            const std::size_t close = s.find('"', k + 2);
            if (close == std::string::npos)
                return fail("unterminated attribute", j), r;
            const std::string value = s.substr(k + 2, close - k - 2);
            if (value.find('<') != std::string::npos)
                fail("< in an attribute", j);
            for (std::size_t q = value.find('&'); q != std::string::npos; q = value.find('&', q + 1))
                if (!entity_at(value, q))
                    fail("bare & in an attribute", j);
            std::string lower = attr;
            for (char& c : lower)
                c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            if (lower.rfind("on", 0) == 0 || lower.find("href") != std::string::npos)
                fail("an event handler or a reference: " + attr, j);
            if (value.find("url(") != std::string::npos)
                fail("a reference in " + attr, j);
            r.attribute_values.push_back(value);
            j = close + 1;
        }
        if (!closed)
            open.push_back(name);
        else if (open.empty())
            root_done = true;
        i = j;
    }
    if (r.ok && !open.empty())
        fail("unclosed <" + open.back() + ">", s.size() - 1);
    if (r.ok && !root_done)
        fail("no root element", 0);
    for (const char* bad : {"script", "foreignObject", "image", "use", "a", "style", "iframe"})
        if (r.elements.count(bad))
            fail(std::string("element <") + bad + ">", 0);
    return r;
}

/// No "nan" or "inf" in a number an attribute carries.
bool numbers_finite(const xml_report& r)
{
    for (std::string v : r.attribute_values) {
        for (char& c : v)
            c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (v.find("nan") != std::string::npos || v.find("inf") != std::string::npos)
            return false;
    }
    return true;
}

/// Every number in a TikZ picture's coordinates is finite and within a page.
bool tikz_numbers_sane(const std::string& t)
{
    // Names may spell "nan" or "inf"; coordinates are "(x,y)" with decimals: read every
    // "(" followed by two decimal numbers "-?d+.d+" separated by a comma and closed by ")".
    auto decimal_at = [&](std::size_t& k, double& v) {
        const std::size_t start = k;
        if (k < t.size() && t[k] == '-')
            ++k;
        std::size_t digits = 0;
        while (k < t.size() && std::isdigit(static_cast<unsigned char>(t[k])))
            ++k, ++digits;
        if (!digits || k >= t.size() || t[k] != '.')
            return false;
        ++k;
        std::size_t decimals = 0;
        while (k < t.size() && std::isdigit(static_cast<unsigned char>(t[k])))
            ++k, ++decimals;
        if (!decimals)
            return false;
        v = std::stod(t.substr(start, k - start));
        return true;
    };
    for (std::size_t at = t.find('('); at != std::string::npos; at = t.find('(', at + 1)) {
        std::size_t k = at + 1;
        double x = 0, y = 0;
        if (!decimal_at(k, x) || k >= t.size() || t[k] != ',')
            continue;
        ++k;
        if (!decimal_at(k, y) || k >= t.size() || t[k] != ')')
            continue;
        for (double v : {x, y})
            if (!std::isfinite(v) || v < -0.5 || v > 9.0)
                return false;
    }
    return true;
}

derivation derive_case(const case_t& c) { return derive(c.p); }

const item* find_item(const drawing& g, const std::string& key, item::kind_t kind)
{
    for (const item& it : g.items)
        if (it.key == key && it.kind == kind)
            return &it;
    return nullptr;
}

std::string run(const std::string& cmd, int& status)
{
    std::string out;
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) {
        status = -1;
        return out;
    }
    std::array<char, 4096> buf{};
    std::size_t got = 0;
    while ((got = std::fread(buf.data(), 1, buf.size(), pipe)) > 0)
        out.append(buf.data(), got);
    status = ::pclose(pipe);
    return out;
}

/// Why the TikZ cannot be compiled here, or "" when it can.
std::string latex_missing()
{
    if (std::system("command -v pdflatex > /dev/null 2>&1") != 0)
        return "pdflatex NOT FOUND";
    if (std::system("kpsewhich tikz.sty > /dev/null 2>&1") != 0)
        return "tikz.sty NOT FOUND (kpsewhich tikz.sty)";
    return "";
}

/// Compiles pictures, one per page, each in a minipage of 0.8\linewidth of an
/// 11pt article; returns the log, status set to pdflatex's exit status.
std::string compile_tikz(const std::vector<std::pair<std::string, std::string>>& pictures, int& status,
                         const std::string& tag)
{
    const fs::path dir = fs::temp_directory_path() / ("impactgen-figure-" + tag + "-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    {
        std::ofstream doc(dir / "doc.tex");
        doc << "\\documentclass[11pt]{article}\n\\usepackage{tikz}\n\\begin{document}\n";
        for (const auto& [name, tikz] : pictures)
            doc << "% " << file_stem(name) << "\n\\noindent\\begin{minipage}{0.8\\linewidth}\n" << tikz
                << "\n\\end{minipage}\n\\newpage\n";
        doc << "\\end{document}\n";
    }
    std::string out = run("cd '" + dir.string() + "' && pdflatex -no-shell-escape -interaction=nonstopmode "
                          "-halt-on-error doc.tex 2>&1",
                          status);
    std::ifstream log_file(dir / "doc.log");
    std::stringstream log;
    log << log_file.rdbuf();
    if (status == 0 && std::getenv("IMPACTGEN_FIGURE_DUMP"))
        fs::copy_file(dir / "doc.pdf", fs::path(std::getenv("IMPACTGEN_FIGURE_DUMP")) / ("figures-" + tag + ".pdf"),
                      fs::copy_options::overwrite_existing);
    fs::remove_all(dir);
    return log.str().empty() ? out : log.str();
}

std::size_t count_of(const std::string& s, const std::string& what)
{
    std::size_t n = 0;
    for (std::size_t i = s.find(what); i != std::string::npos; i = s.find(what, i + 1))
        ++n;
    return n;
}

problem read_text(const std::string& json) { return read_problem(json, "test"); }

} // namespace

// ---------------------------------------------------------------------------
// Every class and problem file.

TEST(FigureEvery, ShowsEveryBodyContactPointAndNormal)
{
    for (const case_t& c : cases()) {
        SCOPED_TRACE(c.name);
        const derivation d = derive_case(c);
        const drawing g = draw(d);
        dump(c.name, g);
        ASSERT_EQ(g.bodies.size(), c.p.bodies.size());
        for (std::size_t i = 0; i < c.p.bodies.size(); ++i) {
            bool shown = false;
            for (const item& it : g.items)
                shown = shown || (it.what == role::body && it.body == static_cast<int>(i));
            EXPECT_TRUE(shown) << "body " << i << " has no outline";
            if (!c.p.bodies[i].infinite_mass) {
                const item* centre = nullptr;
                for (const item& it : g.items)
                    if (it.what == role::centre && it.body == static_cast<int>(i))
                        centre = &it;
                EXPECT_NE(centre, nullptr) << "body " << i << " has no centre marker";
            }
        }
        const item* o = find_item(g, "O", item::circle);
        ASSERT_NE(o, nullptr);
        EXPECT_EQ(o->what, role::contact);
        const item* en = find_item(g, "e_n", item::arrow);
        ASSERT_NE(en, nullptr);
        EXPECT_EQ(en->what, role::frame_axis);
        EXPECT_NE(find_item(g, "e_t", item::arrow), nullptr);
        EXPECT_EQ(find_item(g, "e_b", item::arrow) != nullptr, c.p.dimension == 3);
        // The two impulses at O, opposite.
        const item* n1 = find_item(g, "N1", item::arrow);
        const item* n2 = find_item(g, "N2", item::arrow);
        ASSERT_NE(n1, nullptr);
        ASSERT_NE(n2, nullptr);
        const point a = {n1->points[1].x - n1->points[0].x, n1->points[1].y - n1->points[0].y};
        const point b = {n2->points[1].x - n2->points[0].x, n2->points[1].y - n2->points[0].y};
        EXPECT_LT(a.x * b.x + a.y * b.y, 0);
        EXPECT_EQ(n1->body, static_cast<int>(c.p.contact().body1));
        EXPECT_EQ(n2->body, static_cast<int>(c.p.contact().body2));
        // Labels for C1, C2 (finite bodies), O, e_n, N.
        std::set<std::string> labels;
        for (const label& l : g.labels)
            labels.insert(l.key);
        for (const char* k : {"O", "e_n", "e_t", "N1", "N2"})
            EXPECT_TRUE(labels.count(k)) << k;
        EXPECT_FALSE(describe(g).empty());
        EXPECT_EQ(describe(g).find('\n'), std::string::npos);
    }
}

TEST(FigureEvery, SvgIsWellFormedSelfContainedAndDeterministic)
{
    for (const case_t& c : cases()) {
        SCOPED_TRACE(c.name);
        const derivation d = derive_case(c);
        const std::string svg = to_svg(draw(d));
        const xml_report r = check_xml(svg);
        EXPECT_TRUE(r.ok) << r.why;
        EXPECT_TRUE(numbers_finite(r)) << svg;
        EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
        EXPECT_NE(svg.find("viewBox=\"0 0 "), std::string::npos);
        EXPECT_NE(svg.find("<title>"), std::string::npos);
        EXPECT_EQ(svg.find("<script"), std::string::npos);
        EXPECT_EQ(svg.size() - svg.rfind("</svg>"), 6u);
        // Byte-identical: the same drawing twice, and a second derivation.
        EXPECT_EQ(svg, to_svg(draw(d)));
        EXPECT_EQ(svg, to_svg(draw(derive_case(c))));
        EXPECT_EQ(to_tikz(draw(d)), to_tikz(draw(derive_case(c))));
        EXPECT_EQ(describe(draw(d)), describe(draw(derive_case(c))));
    }
}

TEST(FigureEvery, TikzCompilesWithinPointEightLinewidth)
{
    const std::string missing = latex_missing();
    if (!missing.empty())
        GTEST_SKIP() << "\n*** " << missing << ": the TikZ figures are NOT CHECKED. Install them with: "
                     << "apt-get install --no-install-recommends texlive-latex-base texlive-pictures ***\n";
    std::vector<std::pair<std::string, std::string>> pictures;
    for (const case_t& c : cases()) {
        const std::string t = to_tikz(draw(derive_case(c)));
        EXPECT_EQ(t.rfind("\\begin{tikzpicture}", 0), 0u) << c.name;
        EXPECT_EQ(t.size() - t.rfind("\\end{tikzpicture}"), std::string("\\end{tikzpicture}").size()) << c.name;
        EXPECT_TRUE(tikz_numbers_sane(t)) << c.name << "\n" << t;
        pictures.push_back({c.name, t});
    }
    int status = 0;
    const std::string log = compile_tikz(pictures, status, "every");
    EXPECT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_EQ(count_of(log, "Overfull"), 0u) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_EQ(count_of(log, "! "), 0u);
}

// ---------------------------------------------------------------------------
// Geometry facts.

TEST(FigureGeometry, NormalArrowAlongTheProblemNormal)
{
    std::size_t planar = 0;
    for (const case_t& c : cases()) {
        if (c.p.dimension != 2)
            continue;
        ++planar;
        SCOPED_TRACE(c.name);
        const drawing g = draw(derive_case(c));
        const item* en = find_item(g, "e_n", item::arrow);
        ASSERT_NE(en, nullptr);
        const double drawn = std::atan2(en->points[1].y - en->points[0].y, en->points[1].x - en->points[0].x);
        // Every planar case here has a numeric normal.
        const double nx = GiNaC::ex_to<GiNaC::numeric>(c.p.contact().normal[0].evalf()).to_double();
        const double ny = GiNaC::ex_to<GiNaC::numeric>(c.p.contact().normal[1].evalf()).to_double();
        EXPECT_NEAR(drawn, std::atan2(ny, nx), 1e-9);
        // e_t is e_n turned by -90 degrees, as the derivation takes it.
        const item* et = find_item(g, "e_t", item::arrow);
        ASSERT_NE(et, nullptr);
        const double t_angle = std::atan2(et->points[1].y - et->points[0].y, et->points[1].x - et->points[0].x);
        EXPECT_NEAR(std::remainder(t_angle - drawn + M_PI / 2, 2 * M_PI), 0, 1e-9);
        // The impulse on body 2 runs along +n.
        const item* n2 = find_item(g, "N2", item::arrow);
        ASSERT_NE(n2, nullptr);
        EXPECT_NEAR(std::atan2(n2->points[1].y - n2->points[0].y, n2->points[1].x - n2->points[0].x), drawn, 1e-9);
    }
    EXPECT_GE(planar, 8u);
}

TEST(FigureGeometry, PinnedBodyShowsRAtE)
{
    std::size_t pinned = 0;
    for (const case_t& c : cases()) {
        if (c.p.pivots.empty())
            continue;
        ++pinned;
        SCOPED_TRACE(c.name);
        const drawing g = draw(derive_case(c));
        const item* e = find_item(g, "E", item::circle);
        ASSERT_NE(e, nullptr);
        const item* r = nullptr;
        for (const item& it : g.items)
            if (it.kind == item::arrow && it.what == role::pivot_impulse)
                r = &it;
        ASSERT_NE(r, nullptr);
        EXPECT_EQ(r->body, static_cast<int>(c.p.pivots[0].body));
        EXPECT_NEAR(r->points[0].x, e->points[0].x, 1e-12);
        EXPECT_NEAR(r->points[0].y, e->points[0].y, 1e-12);
        bool labelled = false;
        for (const label& l : g.labels)
            labelled = labelled || (l.what == role::pivot_impulse && l.tex == "R");
        EXPECT_TRUE(labelled);
        EXPECT_TRUE(g.bodies[c.p.pivots[0].body].pinned);
        EXPECT_NE(describe(g).find("pinned at E"), std::string::npos);
    }
    EXPECT_GE(pinned, 3u); // pinned-planar, hinged-rod, pinned-3d
}

TEST(FigureGeometry, ShapesFollowTheProblem)
{
    std::map<std::string, std::vector<shape>> expected = {
        {"central-direct", {shape::disc, shape::disc}},
        {"central-oblique", {shape::disc, shape::disc}},
        {"planar", {shape::box, shape::box}},
        {"noncentral-3d", {shape::box, shape::box}},
        {"massive-3d", {shape::box, shape::wall}},
        {"pinned-planar", {shape::disc, shape::rod}},
        {"ball-floor-friction", {shape::wall, shape::disc}},
        {"examples/problems/hinged-rod.json", {shape::disc, shape::rod}},
        {"examples/problems/pinned-3d.json", {shape::disc, shape::plate}},
        {"examples/problems/puck-block-34.json", {shape::disc, shape::box}},
        {"examples/problems/spinning-spheres.json", {shape::disc, shape::disc}},
        // The box's centre lies a little on the wall's side of the tangent plane: a marker.
        {"examples/problems/wall-oblique-3d.json", {shape::marker, shape::wall}},
        {"tests/explain/rod-energy-gain.json", {shape::wall, shape::rod}},
        {"tests/explain/rod-cannot-stick.json", {shape::wall, shape::rod}},
    };
    std::size_t seen = 0;
    for (const case_t& c : cases()) {
        const auto it = expected.find(c.name);
        if (it == expected.end())
            continue;
        ++seen;
        const drawing g = draw(derive_case(c));
        ASSERT_EQ(g.bodies.size(), it->second.size()) << c.name;
        for (std::size_t i = 0; i < g.bodies.size(); ++i)
            EXPECT_EQ(shape_name(g.bodies[i].form), std::string(shape_name(it->second[i]))) << c.name << " body " << i;
    }
    EXPECT_EQ(seen, expected.size());
    // A sphere's radius is |O - C|: the ball of ball-floor-friction touches O.
    const drawing g = draw(derive(find_named_class("ball-floor-friction")->build()));
    for (const item& it : g.items)
        if (it.what == role::body && it.kind == item::circle) {
            EXPECT_NEAR(std::hypot(it.points[0].x, it.points[0].y), it.radius, 1e-12);
        }
}

// A named class's symbols take their illustrative values by what they are in the problem,
// not by their names: a velocity named like a spin (w...) is drawn as the velocity it is
// (the fallback 1, not a spin's 0).
TEST(FigureGeometry, SymbolsOfANamedClassPlacedByWhatTheyAre)
{
    problem p = find_named_class("planar")->build();
    p.bodies[0].velocity[0] = symbol_named("w_slip"); // body 1 moves along e_t at "w_slip" = 1
    const drawing g = draw(derive(p));
    const item* v1 = find_item(g, "v1", item::arrow);
    ASSERT_NE(v1, nullptr);
    // v1 = (1, v_n1 = 1): at 45 degrees, not along e_n.
    const double angle = std::atan2(v1->points[1].y - v1->points[0].y, v1->points[1].x - v1->points[0].x);
    EXPECT_NEAR(angle, std::atan2(1.0, 1.0), 1e-9);
}

// The figure's values come from the quantities a symbol is in, never from its name: a problem
// file whose source reads like a named class and whose symbols carry the names that class gives
// other quantities (body 1 with planar's m2, r_n2, v_n2, body 2 with its m1, r_n1, v_n1) is drawn
// as its own: each centre on its body's side of the tangent plane, the bodies approaching. (A
// table by name put body 1's centre at r_n2 = 1, on body 2's side, and had them separate.)
TEST(FigureGeometry, SymbolsNamedLikeANamedClassesArePlacedByTheirQuantities)
{
    const problem p = read_problem(R"({"dimension": 2, "restitution": "e",
        "bodies": [{"name": "a", "mass": "m2", "inertia": "I2", "position": ["r_t2", "r_n2"],
                    "velocity": ["v_t2", "v_n2"], "angular_velocity": "w_b2"},
                   {"name": "b", "mass": "m1", "inertia": "I1", "position": ["r_t1", "r_n1"],
                    "velocity": ["v_t1", "v_n1"], "angular_velocity": "w_b1"}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0], "normal": [0, 1]}})",
                                   "planar");
    const GiNaC::exmap values = schematic_values(p);
    auto value = [&](const char* name) {
        const auto it = values.find(symbol_named(name));
        EXPECT_NE(it, values.end()) << name;
        return it == values.end() ? 0.0 : GiNaC::ex_to<GiNaC::numeric>(it->second).to_double();
    };
    EXPECT_LT(value("r_n2"), 0); // body 1 ("a") below the tangent plane, n = +y into body 2
    EXPECT_GT(value("r_n1"), 0);
    EXPECT_GT(value("v_n2") - value("v_n1"), 0); // body 1 moves towards body 2 faster: they approach
    EXPECT_EQ(value("w_b1"), 0);
    EXPECT_EQ(value("w_b2"), 0);
    const drawing g = draw(derive(p));
    const item* c1 = find_item(g, "C1", item::circle);
    const item* c2 = find_item(g, "C2", item::circle);
    ASSERT_NE(c1, nullptr);
    ASSERT_NE(c2, nullptr);
    EXPECT_LT(c1->points[0].y, 0);
    EXPECT_GT(c2->points[0].y, 0);
    // The class itself keeps its figure: its own symbols, the values it gave its quantities.
    const problem cls = find_named_class("planar")->build();
    const GiNaC::exmap class_values = schematic_values(cls);
    EXPECT_EQ(GiNaC::ex_to<GiNaC::numeric>(class_values.at(cls.bodies[0].position[1])).to_double(), -0.9);
    EXPECT_EQ(GiNaC::ex_to<GiNaC::numeric>(class_values.at(cls.bodies[1].velocity[1])).to_double(), -0.6);
    EXPECT_EQ(GiNaC::ex_to<GiNaC::numeric>(class_values.at(cls.restitution)).to_double(), 0.8);
}

TEST(FigureGeometry, DescribeNamesBodiesShapesAndNormal)
{
    auto text = [](const std::string& file) {
        return describe(draw(derive(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + file))));
    };
    EXPECT_EQ(text("/examples/problems/hinged-rod.json"),
              "ball (disc) strikes rod (rod pinned at E) at O; normal e_n along (1, 0)");
    EXPECT_EQ(text("/examples/problems/puck-block-34.json"),
              "puck (disc) strikes block (box) at O; normal e_n along (3/5, 4/5)");
    EXPECT_EQ(text("/tests/explain/ball-floor.json"), "ball (disc) strikes floor (wall) at O; normal e_n along (0, 1)");
    EXPECT_EQ(text("/examples/problems/wall-oblique-3d.json"),
              "box (point) strikes wall (wall) at O; normal e_n along (1/3, 2/3, 2/3); 3-D, oblique projection; "
              "schematic (symbols drawn with illustrative values)");
    EXPECT_EQ(describe(draw(derive(find_named_class("central-direct")->build()))),
              "body 1 (disc) strikes body 2 (disc) at O; normal e_n along (0, 1); schematic (symbols drawn with "
              "illustrative values)");
}

// ---------------------------------------------------------------------------
// Hostile names and degenerate geometry.

TEST(FigureSafety, HostileNamesComeOutInert)
{
    std::vector<problem> problems;
    problems.push_back(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/tests/explain/hostile-names.json"));
    // A script, LaTeX that reads a file, math, an XML non-character, a quote.
    problems.push_back(read_text(R"({"dimension": 2, "restitution": 0.5,
        "bodies": [{"name": "</svg><script>alert(1)</script>", "mass": 1, "position": [0, -1], "velocity": [0, 1]},
                   {"name": "\\input{/etc/passwd}$x$\"&amp;\uffff", "mass": 1, "position": [0, 1], "velocity": [0, 0]}],
        "contact": {"bodies": ["</svg><script>alert(1)</script>", "\\input{/etc/passwd}$x$\"&amp;\uffff"],
                    "point": [0, 0], "normal": [0, 1]}})"));
    std::vector<std::pair<std::string, std::string>> pictures;
    for (const problem& p : problems) {
        const drawing g = draw(derive(p));
        const std::string svg = to_svg(g), tikz = to_tikz(g);
        const xml_report r = check_xml(svg);
        EXPECT_TRUE(r.ok) << r.why << "\n" << svg;
        EXPECT_EQ(svg.find("<script"), std::string::npos);
        EXPECT_EQ(count_of(svg, "</svg>"), 1u);
        EXPECT_EQ(svg.find("\xEF\xBF\xBF"), std::string::npos);
        EXPECT_EQ(tikz.find("\\input"), std::string::npos);
        EXPECT_EQ(tikz.find("\\end{document}"), std::string::npos);
        EXPECT_EQ(tikz.find("$x$"), std::string::npos);
        // Every $ in the TikZ opens or closes one of the library's own math labels.
        std::size_t dollars = count_of(tikz, "$") - count_of(tikz, "\\$");
        std::size_t math_labels = 0;
        for (const label& l : g.labels)
            math_labels += l.is_name ? 0 : 1;
        EXPECT_EQ(dollars, 2 * math_labels);
        pictures.push_back({"hostile", tikz});
    }
    const drawing second = draw(derive(problems[1]));
    EXPECT_NE(to_svg(second).find("&lt;/svg&gt;&lt;script&gt;"), std::string::npos);
    EXPECT_NE(to_tikz(second).find("\\textbackslash{}input\\{/etc/passwd\\}\\$x\\$"), std::string::npos);
    const std::string missing = latex_missing();
    if (!missing.empty())
        GTEST_SKIP() << "\n*** " << missing << ": the TikZ of hostile names is NOT COMPILED ***\n";
    int status = 0;
    const std::string log = compile_tikz(pictures, status, "hostile");
    EXPECT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_EQ(count_of(log, "Overfull"), 0u);
}

TEST(FigureSafety, DegenerateAndExtremeGeometryStaysFinite)
{
    std::vector<std::pair<std::string, problem>> problems;
    auto add = [&](const std::string& name, const std::string& json) {
        SCOPED_TRACE(name);
        problems.push_back({name, read_text(json)});
    };
    // Both centres at O; 1e-30 against 1e30; numbers near the limit of double;
    // a symbolic normal; a 3-D normal along the projection's receding axis.
    add("centres-at-O", R"({"dimension": 2, "restitution": 1, "bodies": [
        {"name": "a", "mass": 1, "inertia": 1, "position": [0, 0], "velocity": [0, 1]},
        {"name": "b", "mass": 1, "inertia": 1, "position": [0, 0], "velocity": [0, 0]}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0], "normal": [0, 1]}})");
    add("tiny-and-huge", R"({"dimension": 2, "restitution": 1, "bodies": [
        {"name": "a", "mass": 1, "position": [0, -1e-30], "velocity": [1e-30, 1e30]},
        {"name": "b", "mass": 1e30, "inertia": 1e-30, "position": [3e29, 1e30], "velocity": [0, -1e-30]}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0], "normal": [1e-30, 1]}})");
    add("near-max", R"({"dimension": 3, "restitution": 0, "bodies": [
        {"name": "a", "mass": 1e300, "position": [-1.7e308, -1.7e308, 1.7e308], "velocity": [1.7e308, 1.7e308, -1.7e308]},
        {"name": "b", "mass": "inf", "position": [1.7e308, 1.7e308, -1.7e308], "velocity": [-1e-300, 0, 0]}],
        "contact": {"bodies": ["a", "b"], "point": [1.7e308, -1.7e308, 1.7e308], "normal": [1, 1, -1]}})");
    add("symbolic-normal", R"({"dimension": 2, "restitution": "e", "bodies": [
        {"name": "a", "mass": "m", "position": ["x1", "y1"], "velocity": ["u", "w"]},
        {"name": "b", "mass": "M", "inertia": "J", "position": ["x2", "y2"], "velocity": [0, 0]}],
        "contact": {"bodies": ["a", "b"], "point": ["px", "py"], "normal": ["nx", "ny"]}})");
    add("normal-along-view", R"({"dimension": 3, "restitution": 0.5, "bodies": [
        {"name": "a", "mass": 1, "inertia": [1, 1, 1], "position": [-0.35355339, -0.35355339, -1], "velocity": [0.35355339, 0.35355339, 1]},
        {"name": "b", "mass": 1, "position": [0.5, 0.5, 1.5], "velocity": [0, 0, 0]}],
        "contact": {"bodies": ["a", "b"], "point": [0, 0, 0], "normal": [0.35355339, 0.35355339, 1]}})");
    // Zero velocities everywhere (not an impact: derive() refuses it, the figure must not care).
    {
        problem p = read_text(R"({"dimension": 2, "restitution": 1, "bodies": [
            {"name": "a", "mass": 1, "position": [0, -1], "velocity": [0, 1]},
            {"name": "b", "mass": 1, "position": [0, 1], "velocity": [0, 0]}],
            "contact": {"bodies": ["a", "b"], "point": [0, 0], "normal": [0, 1]}})");
        problems.push_back({"zero-velocities", p});
    }
    std::vector<std::pair<std::string, std::string>> pictures;
    for (const auto& [name, p] : problems) {
        SCOPED_TRACE(name);
        derivation d = derive(p);
        if (name == "zero-velocities") // after derive(), which refuses it
            d.prob.bodies[0].velocity = zero_vec();
        const drawing g = draw(d);
        dump(name, g);
        for (const item& it : g.items) {
            for (const point& q : it.points) {
                EXPECT_TRUE(std::isfinite(q.x) && std::isfinite(q.y)) << it.key;
                EXPECT_LT(std::abs(q.x) + std::abs(q.y), 10) << it.key;
            }
            EXPECT_TRUE(std::isfinite(it.radius));
        }
        const std::string svg = to_svg(g);
        const xml_report r = check_xml(svg);
        EXPECT_TRUE(r.ok) << r.why;
        EXPECT_TRUE(numbers_finite(r)) << svg;
        const std::string tikz = to_tikz(g);
        EXPECT_TRUE(tikz_numbers_sane(tikz)) << tikz;
        pictures.push_back({name, tikz});
        if (name == "zero-velocities") {
            for (const item& it : g.items)
                EXPECT_NE(it.what, role::velocity) << "an arrow of zero length";
        }
        if (name == "symbolic-normal") {
            EXPECT_NE(describe(g).find("n (symbolic)"), std::string::npos) << describe(g);
        }
    }
    const std::string missing = latex_missing();
    if (!missing.empty())
        GTEST_SKIP() << "\n*** " << missing << ": the TikZ of degenerate problems is NOT COMPILED ***\n";
    int status = 0;
    const std::string log = compile_tikz(pictures, status, "degenerate");
    EXPECT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
    EXPECT_EQ(count_of(log, "Overfull"), 0u);
}

TEST(FigureSafety, NumbersIgnoreTheLocale)
{
    // A locale with a decimal comma, where one is installed: the output is the same bytes.
    const drawing g = draw(derive(find_named_class("planar")->build()));
    const std::string before = to_svg(g) + to_tikz(g);
    const char* old = std::setlocale(LC_NUMERIC, nullptr);
    const std::string saved = old ? old : "C";
    bool switched = false;
    for (const char* loc : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "C.UTF-8"})
        if (std::setlocale(LC_NUMERIC, loc)) {
            switched = true;
            break;
        }
    const std::string after = to_svg(g) + to_tikz(g);
    std::setlocale(LC_NUMERIC, saved.c_str());
    EXPECT_EQ(before, after) << (switched ? "" : "(no other locale installed)");
}

// One convention for position vectors in the text and the figure (issue 25, defect 5): the
// lever arm drawn from C_i to O is labelled r_{C_i O} (= O - C_i, as the set-up defines
// r_PQ = Q - P), and a centre's velocity v_{C_i}, as the text names them.
TEST(FigureGeometry, LeverArmsAndVelocitiesAreNamedAsTheTextNamesThem)
{
    std::size_t arms = 0;
    for (const case_t& c : cases()) {
        SCOPED_TRACE(c.name);
        const drawing g = draw(derive_case(c));
        for (const label& l : g.labels) {
            if (l.what == role::lever_arm) {
                ++arms;
                const item* path = nullptr;
                for (const item& it : g.items)
                    if (it.what == role::lever_arm && it.key == l.key)
                        path = &it;
                ASSERT_NE(path, nullptr);
                const std::string i = l.key.substr(1); // "r1" -> "1"
                EXPECT_EQ(l.tex, "\\underline{r}_{C_{" + i + "}O}");
                EXPECT_EQ(l.sub, "C" + i + "O");
                // drawn from the centre of mass to the contact point O = (0, 0)
                EXPECT_NEAR(path->points.back().x, 0.0, 1e-12);
                EXPECT_NEAR(path->points.back().y, 0.0, 1e-12);
            }
            if (l.what == role::velocity && !l.is_name) {
                EXPECT_EQ(l.tex.rfind("\\underline{v}_{C_{", 0), 0u) << l.tex;
            }
        }
    }
    EXPECT_GE(arms, 4u);
}
