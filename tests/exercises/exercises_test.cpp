// Exercise sheets (issue 25), the library: one golden sheet; the same seed gives the same
// files byte for byte; every exercise's answer file is the answer of its own problem file
// read back; the regime asked for is kept, away from its boundary (mu a third larger or
// smaller gives the same regime, checked here by solving); every asked value is a short
// fraction; bad options are refused with one line naming the option.
// IMPACTGEN_REGENERATE_GOLDEN=1 (or make regenerate-golden-exercises) rewrites the golden files.
#include "exercises/exercises.hpp"
#include "print/answer.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/named_systems.hpp"
#include "symbolic/system.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

namespace fs = std::filesystem;
using namespace impactgen;

namespace
{

problem hinged_rod()
{
    return load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/problems/hinged-rod.json");
}

// units: the work units of the search (options::units; 0 the default, sized for a sheet)
exercises::sheet sheet_of(const problem &p, int count, std::uint64_t seed, const std::string &regime = "",
                          int units = 0)
{
    exercises::options o;
    o.units = units;
    o.count = count;
    o.seed = seed;
    o.regime = regime;
    return exercises::make_sheet(p, o);
}

std::string read_text(const fs::path &p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

regime_case answer_of(const problem &p, derivation &d)
{
    d = derive(p);
    return select_candidate(d, solve_impact(d));
}

} // namespace

TEST(ExerciseSheet, GoldenSheetOfTheHingedRod)
{
    const std::map<std::string, std::string> files = exercises::sheet_files(sheet_of(hinged_rod(), 3, 1));
    const fs::path dir = fs::path(IMPACTGEN_EXERCISES_GOLDEN_DIR) / "hinged-rod-3-seed-1";
    for (const char *name : {"sheet.tex", "sheet.html", "quiz.xml", "problems/01.json", "answers/01.json"}) {
        const fs::path golden = dir / name;
        if (std::getenv("IMPACTGEN_REGENERATE_GOLDEN")) {
            fs::create_directories(golden.parent_path());
            std::ofstream(golden, std::ios::binary) << files.at(name);
        }
        ASSERT_TRUE(fs::exists(golden)) << golden << " is missing: make regenerate-golden-exercises";
        EXPECT_EQ(read_text(golden), files.at(name))
            << golden << ": review the change, then make regenerate-golden-exercises";
    }
}

TEST(ExerciseSheet, SameSeedSameFilesByteForByte)
{
    const auto a = exercises::sheet_files(sheet_of(hinged_rod(), 4, 42));
    const auto b = exercises::sheet_files(sheet_of(hinged_rod(), 4, 42));
    EXPECT_EQ(a, b);
    const auto c = exercises::sheet_files(sheet_of(hinged_rod(), 4, 43));
    EXPECT_NE(a.at("problems/01.json") + a.at("problems/02.json"), c.at("problems/01.json") + c.at("problems/02.json"));
    // 4 exercises: 4 problems, answers and worked solutions (LaTeX and HTML), the sheet twice, the quiz
    EXPECT_EQ(a.size(), 4u * 4 + 3);
}

TEST(ExerciseSheet, EveryAnswerIsTheAnswerOfItsProblemFile)
{
    for (const char *what : {"hinged-rod", "central-direct", "planar", "ball-floor-friction", "planar-friction"}) {
        SCOPED_TRACE(what);
        const problem base = std::string(what) == "hinged-rod" ? hinged_rod() : find_named_class(what)->build();
        const auto files = exercises::sheet_files(sheet_of(base, 3, 5));
        for (int k = 1; k <= 3; ++k) {
            const std::string nn = "0" + std::to_string(k);
            // the problem file read back, solved afresh
            const problem p = read_problem(files.at("problems/" + nn + ".json"), nn);
            ASSERT_TRUE(p.is_numeric());
            derivation d;
            const regime_case c = answer_of(p, d);
            EXPECT_EQ(print::answer_json(d, c, false).dump(2) + "\n", files.at("answers/" + nn + ".json"));
            // every asked value a short fraction, and equal to the answer file's decimal
            const nlohmann::json answer = nlohmann::json::parse(files.at("answers/" + nn + ".json"));
            for (const exercises::quantity &q : exercises::asked_quantities(d, c)) {
                ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(q.exact)) << q.pointer;
                const GiNaC::numeric v = GiNaC::ex_to<GiNaC::numeric>(q.exact);
                EXPECT_TRUE(v.is_rational()) << q.pointer;
                EXPECT_LE(v.denom().to_long(), q.pointer == "/kinetic_energy/lost" ? 2000 : 200) << q.pointer;
                EXPECT_NEAR(answer.at(nlohmann::json::json_pointer(q.pointer)).get<double>(), v.to_double(),
                            1e-12 * std::max(1.0, std::abs(v.to_double())))
                    << q.pointer;
            }
            // a worked solution for each, titled by its exercise
            EXPECT_NE(files.at("solutions/" + nn + ".tex").find("\\title{Exercise " + std::to_string(k) + ": "),
                      std::string::npos);
            EXPECT_NE(files.at("solutions/" + nn + ".html").find("<h1>Exercise " + std::to_string(k) + ": "),
                      std::string::npos);
        }
    }
}

TEST(ExerciseSheet, RegimeAskedForIsKeptAwayFromItsBoundary)
{
    // (a free planar pair that sticks seldom has short answers: planar-friction slides only)
    for (const auto &[what, regime] : {std::pair<std::string, std::string>{"ball-floor-friction", "stick"},
                                       {"ball-floor-friction", "slide"},
                                       {"planar-friction", "slide"}}) {
        {
            SCOPED_TRACE(what + " " + regime);
            const exercises::sheet s = sheet_of(find_named_class(what)->build(), 3, 11, regime);
            ASSERT_EQ(s.exercises.size(), 3u);
            for (const exercises::exercise &e : s.exercises) {
                derivation d;
                const regime_case c = answer_of(e.prob, d);
                EXPECT_EQ(regime_name(c.kind), regime);
                EXPECT_EQ(e.regime, regime);
                for (const GiNaC::numeric &f : {GiNaC::numeric(3, 4), GiNaC::numeric(4, 3)}) {
                    problem near = e.prob;
                    near.contact().set_friction(near.contact().friction() * f);
                    derivation dn;
                    const regime_case cn = answer_of(near, dn);
                    EXPECT_EQ(cn.kind, c.kind);
                    EXPECT_EQ(cn.sign, c.sign);
                }
            }
        }
    }
    // a smooth problem's variants are smooth
    for (const exercises::exercise &e : sheet_of(hinged_rod(), 2, 3, "smooth").exercises)
        EXPECT_EQ(e.regime, "smooth");
}

TEST(ExerciseSheet, VariantsKeepTheProblemsGeometryAndKind)
{
    const problem base = hinged_rod();
    for (const exercises::exercise &e : sheet_of(base, 5, 9).exercises) {
        ASSERT_EQ(e.prob.bodies.size(), base.bodies.size());
        EXPECT_EQ(e.prob.pivots.size(), 1u);
        for (std::size_t i = 0; i < base.bodies.size(); ++i) {
            EXPECT_EQ(e.prob.bodies[i].name, base.bodies[i].name);
            for (int k = 0; k < 2; ++k) {
                EXPECT_EQ(e.prob.bodies[i].position[k], base.bodies[i].position[k]);
                // the sign of every velocity, and which are zero, kept
                EXPECT_EQ(GiNaC::ex_to<GiNaC::numeric>(e.prob.bodies[i].velocity[k]).csgn(),
                          GiNaC::ex_to<GiNaC::numeric>(base.bodies[i].velocity[k]).csgn());
            }
        }
        // the rod stays a uniform rod of its length: I = m l^2/12 with l = 1
        EXPECT_EQ(e.prob.bodies[1].inertia[2][2], e.prob.bodies[1].mass / 12);
        EXPECT_EQ(e.prob.contact().point[1], base.contact().point[1]);
    }
}

TEST(ExerciseSheet, BadOptionsAreRefusedInOneLine)
{
    auto refused = [](const problem &p, int count, const std::string &regime, const std::string &key) {
        try {
            sheet_of(p, count, 1, regime);
            ADD_FAILURE() << "accepted: count " << count << ", regime " << regime;
        } catch (const input_error &e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(key), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    };
    refused(hinged_rod(), 0, "", "--count");
    refused(hinged_rod(), 100, "", "--count");
    refused(hinged_rod(), 2, "stick", "--regime stick");
    refused(hinged_rod(), 2, "bounce", "--regime");
    refused(find_named_class("planar-friction")->build(), 2, "smooth", "--regime smooth");
}

TEST(ExerciseSheet, ProblemJsonReadsBackToTheSameProblem)
{
    for (const exercises::exercise &e : sheet_of(find_named_class("ball-floor-friction")->build(), 3, 2).exercises) {
        const problem back = read_problem(exercises::problem_json(e.prob).dump(), "x");
        EXPECT_EQ(exercises::problem_json(back), exercises::problem_json(e.prob));
        EXPECT_EQ(back.contact().friction(), e.prob.contact().friction());
        EXPECT_EQ(back.bodies[1].angular_velocity[2], e.prob.bodies[1].angular_velocity[2]);
        EXPECT_FALSE(back.bodies[1].angular_velocity[2].is_zero()); // the spin is the point of this problem
    }
}

TEST(ExerciseSheet, ProblemWhoseAnswersAreSeldomShortGetsDecimalAnswers)
{
    // A 3-D contact with friction and a plate struck obliquely seldom give short fractions: the
    // variant with the shortest answers serves, its answers written as decimals, and it is still
    // exactly the answer of its own problem file.
    for (const std::string what : {"noncentral-3d-friction", "plate-struck-obliquely"}) {
        SCOPED_TRACE(what);
        const problem base = what == "plate-struck-obliquely"
                                 ? load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) +
                                                     "/examples/problems/plate-struck-obliquely.json")
                                 : find_named_class(what)->build();
        const exercises::sheet s = sheet_of(base, 2, 1, "", 500); // a short search, then the shortest
        ASSERT_EQ(s.exercises.size(), 2u);
        const auto files = exercises::sheet_files(s);
        bool some_long = false;
        for (const exercises::exercise &e : s.exercises) {
            derivation d;
            const regime_case c = answer_of(e.prob, d);
            EXPECT_EQ(print::answer_json(d, c, false), e.answer);
            for (const exercises::quantity &q : e.asked)
                some_long = some_long || !GiNaC::is_a<GiNaC::numeric>(q.exact) ||
                            GiNaC::ex_to<GiNaC::numeric>(q.exact).denom() > 9999;
        }
        if (some_long) { // a long answer is given by its decimal, never as a fraction of many digits
            EXPECT_NE(files.at("sheet.tex").find("\\approx"), std::string::npos);
        }
        EXPECT_FALSE(std::regex_search(files.at("sheet.tex"),
                                       std::regex(R"(\\tfrac\{[0-9]{7,}\}|\\tfrac\{[0-9]+\}\{[0-9]{5,}\})")))
            << "a long fraction on the sheet";
    }
}

// The search is bounded by draws, never by the clock: a search slowed down draw by draw writes
// the same files byte for byte, also where its draws run out before short answers (which a time
// limit used to cut at another draw on a loaded machine). A search that passes the safety net of
// options::seconds is refused, never cut to another sheet.
TEST(ExerciseSheet, ASlowSearchGivesTheSameSheetOrNone)
{
    EXPECT_EQ(sheet_of(hinged_rod(), 3, 1).short_of_draws, 0) << "short answers found in a few draws";
    const problem rod = find_named_class("rod-rough-floor")->build(); // seldom short answers
    exercises::options o;
    o.count = 2;
    o.units = 300; // 8 draws for each exercise, then 50 more for the sheet
    const exercises::sheet fast = exercises::make_sheet(rod, o);
    EXPECT_EQ(fast.short_of_draws, 2) << "the draws run out: each exercise is the best of its draws";
    int draws = 0;
    o.before_draw = [&draws] {
        ++draws;
        std::this_thread::sleep_for(std::chrono::milliseconds(4));
    };
    const exercises::sheet slow = exercises::make_sheet(rod, o);
    EXPECT_EQ(draws, 2 * 8 + 300 / exercises::draw_units(rod));
    EXPECT_EQ(exercises::sheet_files(slow), exercises::sheet_files(fast));
    o.seconds = 0.05; // past the net after a few slow draws: an error naming it, no sheet
    try {
        exercises::make_sheet(rod, o);
        ADD_FAILURE() << "a search past its safety net gave a sheet";
    } catch (const input_error &e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("safety net of 0.05 s"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

// A system's sheet (issue 25: "keep the regime or active set"): every variant keeps the set of
// regimes of the problem as given, its answer file is solve_system of its own problem file read
// back, and every asked value is where the answer file holds it. --regime is refused for a system.
TEST(ExerciseSheet, SystemSheetKeepsTheSetOfRegimesAndAnswersAreItsFilesSolved)
{
    for (const char *file : {"compass-gait", "three-balls-sequential", "double-pendulum-struck", "box-four-corners"}) {
        SCOPED_TRACE(file);
        const problem base =
            load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/" + file + ".json");
        const system_answer own = solve_system(base);
        const exercises::sheet s = sheet_of(base, 3, 7, "", 1000);
        ASSERT_EQ(s.exercises.size(), 3u);
        const auto files = exercises::sheet_files(s);
        for (std::size_t k = 0; k < 3; ++k) {
            const exercises::exercise &e = s.exercises[k];
            const std::string nn = "0" + std::to_string(k + 1);
            const problem back = read_problem(files.at("problems/" + nn + ".json"), nn);
            ASSERT_TRUE(back.is_system());
            ASSERT_EQ(back.contacts.size(), base.contacts.size());
            ASSERT_EQ(back.joints.size(), base.joints.size());
            EXPECT_EQ(back.sequential, base.sequential);
            const system_answer a = solve_system(back);
            EXPECT_EQ(a.result.name(), own.result.name()) << "the set of regimes is kept";
            EXPECT_EQ(print::system_answer_json(back, a).dump(2) + "\n", files.at("answers/" + nn + ".json"));
            const nlohmann::json answer = nlohmann::json::parse(files.at("answers/" + nn + ".json"));
            for (const exercises::quantity &q : e.asked) {
                const double v = GiNaC::ex_to<GiNaC::numeric>(q.exact.evalf()).to_double();
                // The answer file holds the exact value as a double: only the round trip through
                // its decimal text (and this 17-digit evalf against the file's finer evaluation)
                // separates the two, a few units in the last place; 1e-12 relative (absolute
                // below 1) is far above that and far below any wrong set or formula.
                EXPECT_NEAR(answer.at(nlohmann::json::json_pointer(q.pointer)).get<double>(), v,
                            1e-12 * std::max(1.0, std::abs(v)))
                    << q.pointer;
            }
            if (!a.impulses_unique) { // redundant contacts: only what is determined is asked
                for (const exercises::quantity &q : e.asked)
                    EXPECT_EQ(q.pointer.find("impulse"), std::string::npos) << q.pointer;
            }
            EXPECT_NE(files.at("solutions/" + nn + ".tex").find("\\title{Exercise " + std::to_string(k + 1) + ": "),
                      std::string::npos);
        }
    }
    try {
        sheet_of(load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json"), 2, 1,
                 "stick");
        ADD_FAILURE() << "--regime was taken for a system";
    } catch (const input_error &e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--regime"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

// Every named system class makes a sheet from its own worked example (its figure's schematic
// values alone left the bodies at rest: "not an impact" in every draw), and keeps its set.
TEST(ExerciseSheet, EveryNamedSystemClassMakesASheet)
{
    for (const named_class &c : system_classes()) {
        SCOPED_TRACE(c.name);
        const problem base = c.build();
        const exercises::sheet s = sheet_of(base, 2, 3, "", 1000);
        ASSERT_EQ(s.exercises.size(), 2u);
        const auto files = exercises::sheet_files(s);
        for (std::size_t k = 0; k < 2; ++k) {
            const std::string nn = "0" + std::to_string(k + 1);
            const problem back = read_problem(files.at("problems/" + nn + ".json"), nn);
            ASSERT_TRUE(back.is_system());
            EXPECT_EQ(back.contacts.size(), base.contacts.size());
            EXPECT_EQ(print::system_answer_json(back, solve_system(back)).dump(2) + "\n",
                      files.at("answers/" + nn + ".json"));
        }
    }
}

// The law of restitution travels with the exercise: an energetic-law class gives energetic-law
// problem files, answered under that law.
TEST(ExerciseSheet, RestitutionLawIsKeptInTheProblemFiles)
{
    const exercises::sheet s = sheet_of(find_named_class("rod-rough-floor")->build(), 2, 1, "", 1000);
    for (const exercises::exercise &e : s.exercises) {
        EXPECT_TRUE(std::holds_alternative<energetic_restitution>(e.prob.contact().law_of_restitution));
        EXPECT_EQ(exercises::problem_json(e.prob).at("contact").at("law"), "energetic");
    }
}
