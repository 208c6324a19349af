// The figure of a system (figure/system.hpp): every body, joint, pivot and contact of each
// planar example of examples/systems drawn, the impulses as action and reaction, finite
// coordinates, an SVG element with the system's own alternative text; 3-D and symbolic
// systems give no figure.
#include "figure/figure.hpp"
#include "figure/system.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace impactgen;
using namespace impactgen::figure;
namespace fs = std::filesystem;

namespace {

problem load(const std::string& stem)
{
    const fs::path f = fs::path(IMPACTGEN_SOURCE_DIR) / "examples/systems" / (stem + ".json");
    std::ifstream in(f);
    std::stringstream s;
    s << in.rdbuf();
    return read_problem(s.str(), f.filename().string());
}

std::size_t count(const drawing& g, role r, const std::string& key)
{
    return static_cast<std::size_t>(std::count_if(g.items.begin(), g.items.end(), [&](const item& it) {
        return it.what == r && it.key == key;
    }));
}

} // namespace

TEST(SystemFigure, EveryBodyJointPivotAndContactIsDrawn)
{
    for (const std::string stem :
         {"compass-gait", "double-pendulum-struck", "three-balls-sequential", "three-balls-simultaneous",
          "two-corner-landing"}) {
        SCOPED_TRACE(stem);
        const problem p = load(stem);
        const std::optional<drawing> g = draw_system(p);
        ASSERT_TRUE(g.has_value());
        ASSERT_EQ(g->bodies.size(), p.bodies.size());
        for (std::size_t b = 0; b < p.bodies.size(); ++b) {
            bool drawn = false;
            for (const item& it : g->items)
                drawn = drawn || (it.what == role::body && it.body == static_cast<int>(b));
            EXPECT_TRUE(drawn) << p.bodies[b].name;
            EXPECT_EQ(g->bodies[b].infinite_mass, p.bodies[b].infinite_mass);
        }
        for (std::size_t i = 0; i < p.contacts.size(); ++i) {
            const std::string k = std::to_string(i);
            EXPECT_EQ(count(*g, role::contact, "O" + k), 1u);
            // on the second body, and the reaction on the first where it can move
            const std::size_t arrows = p.bodies[p.contacts[i].body1].infinite_mass ? 1u : 2u;
            EXPECT_EQ(count(*g, role::impulse, "P" + k), arrows);
        }
        for (std::size_t j = 0; j < p.joints.size(); ++j)
            EXPECT_EQ(count(*g, role::pivot_impulse, "J" + std::to_string(j)), 2u);
        for (std::size_t k = 0; k < p.pivots.size(); ++k)
            EXPECT_EQ(count(*g, role::pivot, "E" + std::to_string(k)), 1u);
        for (const item& it : g->items)
            for (const point& q : it.points) {
                EXPECT_TRUE(std::isfinite(q.x) && std::isfinite(q.y));
                EXPECT_LE(std::abs(q.x) + std::abs(q.y), 4.0) << it.key;
            }
        const std::string svg = to_svg(*g);
        EXPECT_EQ(svg.rfind("<svg", 0), 0u);
        EXPECT_NE(svg.find(std::to_string(p.contacts.size()) + (p.contacts.size() == 1 ? " contact " : " contacts ")),
                  std::string::npos);
        EXPECT_NE(to_tikz(*g).find("\\begin{tikzpicture}"), std::string::npos);
    }
}

// The legs of the compass gait are rods; the joint impulses point along the answer when given.
TEST(SystemFigure, CompassGaitLegsAreRodsAndJointImpulseFollowsTheAnswer)
{
    const problem p = load("compass-gait");
    const std::vector<vec3> J{{GiNaC::ex(0), GiNaC::ex(-3), GiNaC::ex(0)}};
    const std::optional<drawing> g = draw_system(p, &J);
    ASSERT_TRUE(g.has_value());
    EXPECT_EQ(g->bodies[1].form, shape::rod);
    EXPECT_EQ(g->bodies[2].form, shape::rod);
    EXPECT_EQ(g->bodies[0].form, shape::wall);
    for (const item& it : g->items)
        if (it.key == "J0") {
            if (it.what != role::pivot_impulse)
                continue;
            const double dy = it.points[1].y - it.points[0].y;
            // on the second body (swing) down, on the first (stance) up
            EXPECT_LT(it.body == 2 ? dy : -dy, 0.0);
            EXPECT_NEAR(it.points[1].x - it.points[0].x, 0.0, 1e-12);
        }
}

TEST(SystemFigure, SpatialOrSymbolicSystemsHaveNoFigure)
{
    EXPECT_FALSE(draw_system(load("box-four-corners")).has_value());
    const problem p = read_problem(R"({"dimension": 2, "restitution": "e", "bodies": [
        {"name": "a", "mass": "m", "position": [0, 0], "velocity": ["v", 0]},
        {"name": "b", "mass": "m", "position": [2, 0], "velocity": [0, 0]},
        {"name": "c", "mass": "m", "position": [4, 0], "velocity": [0, 0]}],
      "contacts": [{"bodies": ["a", "b"], "point": [1, 0], "normal": [1, 0]},
                   {"bodies": ["b", "c"], "point": [3, 0], "normal": [1, 0]}]})",
                                   "symbolic-balls.json");
    EXPECT_FALSE(draw_system(p).has_value());
}
