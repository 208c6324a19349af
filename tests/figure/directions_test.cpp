// Defects 2 and 3 of issue 25: every impulse is drawn in the direction of the answer (the
// pivot impulse R of the hinged rod towards +x, R_x = +9/7 N s), for a problem with symbols in
// the sense in which its unknown counts positive (said by directions_note, which the caption
// carries); the friction impulse is drawn at O on both bodies, and a spin before impact about
// its body's centre. The answers are computed here from the solver, not read from the figure.
#include "figure/figure.hpp"
#include "symbolic/friction.hpp"
#include "symbolic/named_classes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace impactgen;
using namespace impactgen::figure;

namespace
{

const item *arrow(const drawing &g, const std::string &key)
{
    for (const item &it : g.items)
        if (it.key == key && it.kind == item::arrow)
            return &it;
    return nullptr;
}

point along(const item &a)
{
    const double dx = a.points[1].x - a.points[0].x, dy = a.points[1].y - a.points[0].y, l = std::hypot(dx, dy);
    return {dx / l, dy / l};
}

double value(const solution &s, const ex &e)
{
    return GiNaC::ex_to<GiNaC::numeric>(s.expand_steps(e).evalf()).to_double();
}

/// A planar vector's direction, or {0, 0} when it is zero.
point direction(double x, double y)
{
    const double l = std::hypot(x, y);
    return l > 1e-12 ? point{x / l, y / l} : point{0, 0};
}

/// The drawn direction of a world vector: itself in the plane, in 3-D the figure's cabinet
/// projection (figure.hpp: z towards the viewer at 45 degrees down-left, foreshortened by 1/2).
point drawn(const solution &s, const vec3 &v, int dimension)
{
    const double x = value(s, v[0]), y = value(s, v[1]), z = dimension == 3 ? value(s, v[2]) : 0;
    const double k = std::sqrt(2.0) / 4;
    return direction(x - k * z, y - k * z);
}

std::vector<std::string> files_in(const std::string &dir)
{
    std::vector<std::string> out;
    for (const auto &e : fs::directory_iterator(std::string(IMPACTGEN_SOURCE_DIR) + dir))
        if (e.path().extension() == ".json")
            out.push_back(e.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> numeric_files()
{
    std::vector<std::string> out;
    for (const char *dir : {"/examples/problems", "/examples/friction", "/tests/explain"})
        for (const std::string &f : files_in(dir))
            if (load_problem_file(f).is_numeric())
                out.push_back(f);
    return out;
}

} // namespace

TEST(FigureDirections, HingedRodPivotImpulsePointsToPlusX)
{
    const derivation d = derive(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json"));
    const drawing g = draw(d);
    const item *r = arrow(g, "R");
    ASSERT_NE(r, nullptr);
    // the answer: R_x = +9/7 on the rod
    const regime_case c = select_candidate(d, solve_impact(d));
    ASSERT_EQ(c.sol.pivot_impulses.size(), 1u);
    EXPECT_EQ(c.sol.expand_steps(c.sol.pivot_impulses[0][0]), GiNaC::numeric(9, 7));
    EXPECT_GT(along(*r).x, 0.999);
    EXPECT_TRUE(g.impulses_from_answer);
    EXPECT_EQ(directions_note(g), ""); // a numeric problem: nothing assumed
}

TEST(FigureDirections, NamedPinnedClassDrawsRInItsPositiveSenseAndSaysSo)
{
    const drawing g = draw(derive(find_named_class("pinned-planar")->build()));
    const item *r = arrow(g, "R");
    ASSERT_NE(r, nullptr);
    // R_x = N/2 > 0 for a rod struck at its end; R_y = 0: drawn along +x only
    EXPECT_GT(along(*r).x, 0.999);
    EXPECT_FALSE(g.impulses_from_answer);
    EXPECT_NE(directions_note(g).find("pivot impulse towards +x"), std::string::npos) << directions_note(g);
    EXPECT_EQ(directions_note(g).find("+y"), std::string::npos);
}

TEST(FigureDirections, EveryNumericImpulseAlongItsAnswer)
{
    std::size_t pivots = 0, frictions = 0;
    for (const std::string &f : numeric_files()) {
        SCOPED_TRACE(f);
        const derivation d = derive(load_problem_file(f));
        const impact_solution s = solve_impact(d);
        regime_case c;
        try {
            c = select_candidate(d, s);
        } catch (const input_error &) {
            continue; // no single answer (block-several-regimes): nothing to compare with
        }
        const drawing g = draw(d);
        for (std::size_t j = 0; j < c.sol.pivot_impulses.size(); ++j) {
            const point want = drawn(c.sol, c.sol.pivot_impulses[j], d.prob.dimension);
            const item *r = arrow(g, d.prob.pivots.size() == 1 ? "R" : "R" + std::to_string(j + 1));
            if (want.x == 0 && want.y == 0) {
                EXPECT_EQ(r, nullptr); // no impulse, no arrow
                continue;
            }
            ASSERT_NE(r, nullptr);
            const point got = along(*r);
            EXPECT_GT(got.x * want.x + got.y * want.y, 0.999);
            ++pivots;
        }
        if (d.prob.contact().friction().is_zero())
            continue;
        const point want = drawn(c.sol, c.tangential_impulse, d.prob.dimension);
        const item *f2 = arrow(g, "F2"), *f1 = arrow(g, "F1");
        if (want.x == 0 && want.y == 0) {
            EXPECT_EQ(f2, nullptr);
            continue;
        }
        ASSERT_NE(f2, nullptr);
        ASSERT_NE(f1, nullptr);
        const point got2 = along(*f2), got1 = along(*f1);
        EXPECT_GT(got2.x * want.x + got2.y * want.y, 0.999); // on body 2 along the answer
        EXPECT_LT(got1.x * want.x + got1.y * want.y, -0.999); // on body 1 the opposite
        // where friction acts: at O (the origin), just inside each body
        EXPECT_LT(std::hypot(f2->points[0].x, f2->points[0].y), 0.2);
        EXPECT_LT(std::hypot(f1->points[0].x, f1->points[0].y), 0.2);
        EXPECT_EQ(f2->body, static_cast<int>(d.prob.contact().body2));
        EXPECT_EQ(f1->body, static_cast<int>(d.prob.contact().body1));
        ++frictions;
    }
    EXPECT_GE(pivots, 2u);    // hinged-rod, plate-struck-obliquely (3-D)
    EXPECT_GE(frictions, 4u); // ball-floor, ball-backspin, box-corner-3d, ...
}

TEST(FigureDirections, FrictionClassesDrawFAlongThePositiveTangent)
{
    for (const char *name : {"planar-friction", "ball-floor-friction"}) {
        SCOPED_TRACE(name);
        const derivation d = derive(find_named_class(name)->build());
        const drawing g = draw(d);
        const item *f2 = arrow(g, "F2"), *f1 = arrow(g, "F1");
        ASSERT_NE(f2, nullptr);
        ASSERT_NE(f1, nullptr);
        const point got = along(*f2);
        EXPECT_GT(got.x * g.t_hat.x + got.y * g.t_hat.y, 0.999);
        EXPECT_LT(along(*f1).x * g.t_hat.x + along(*f1).y * g.t_hat.y, -0.999);
        EXPECT_NE(directions_note(g).find("friction impulse"), std::string::npos);
    }
}

TEST(FigureDirections, SpinDrawnAboutTheCentreInItsSense)
{
    struct want_t {
        std::string what;
        std::string key;
        double sense; // +1 counter-clockwise
    };
    // ball-floor-friction: the spin w is a symbol, drawn counter-clockwise (positive);
    // ball-backspin.json: the ball spins with its own sign.
    const std::string backspin = std::string(IMPACTGEN_SOURCE_DIR) + "/examples/friction/ball-backspin.json";
    const problem bs = load_problem_file(backspin);
    const double w_backspin = GiNaC::ex_to<GiNaC::numeric>(bs.bodies[1].angular_velocity[2].evalf()).to_double();
    ASSERT_NE(w_backspin, 0);
    for (const auto &[p, sense] : {std::pair<problem, double>{find_named_class("ball-floor-friction")->build(), 1.0},
                                   std::pair<problem, double>{bs, w_backspin > 0 ? 1.0 : -1.0}}) {
        SCOPED_TRACE(p.source);
        const drawing g = draw(derive(p));
        const item *centre = nullptr, *arc = nullptr, *head = nullptr;
        for (const item &it : g.items) {
            if (it.key == "C2" && it.kind == item::circle)
                centre = &it;
            if (it.key == "w2" && it.kind == item::path)
                arc = &it;
            if (it.key == "w2" && it.kind == item::arrow)
                head = &it;
        }
        ASSERT_NE(centre, nullptr);
        ASSERT_NE(arc, nullptr);
        ASSERT_NE(head, nullptr);
        EXPECT_EQ(arc->what, role::spin);
        const point c = centre->points[0];
        const double r = std::hypot(arc->points[0].x - c.x, arc->points[0].y - c.y);
        EXPECT_GT(r, 0.05);
        for (const point &q : arc->points) // a circle about C
            EXPECT_NEAR(std::hypot(q.x - c.x, q.y - c.y), r, 1e-9);
        // the head turns about C in the spin's sense: (tip - C) x (tip - tail) has its sign
        const point tip = head->points[1], tail = head->points[0];
        const double turn = (tip.x - c.x) * (tip.y - tail.y) - (tip.y - c.y) * (tip.x - tail.x);
        EXPECT_GT(turn * sense, 0);
        bool labelled = false;
        for (const label &l : g.labels)
            labelled = labelled || (l.what == role::spin && l.tex == "\\omega_{2}");
        EXPECT_TRUE(labelled);
    }
    // a body without spin before impact has none drawn
    const drawing hinged = draw(derive(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json")));
    for (const item &it : hinged.items)
        EXPECT_NE(it.what, role::spin);
}
