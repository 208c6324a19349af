// Every category of bad input in shared/problem-format.md is refused with a
// message that names the problem and the key; the CLI exits 1 with one line.
#include "symbolic/named_classes.hpp"
#include "symbolic/solution.hpp"
#include "symbolic/system.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <set>
#include <map>
#include <random>
#include <unistd.h>

using namespace impactgen;
using json = nlohmann::json;

namespace {

json valid()
{
    return json::parse(R"({
      "dimension": 2, "restitution": 0.8,
      "bodies": [
        {"name": "ball", "mass": 0.5, "position": [0, -1], "velocity": [5, 0]},
        {"name": "rod", "mass": 2, "inertia": "2*1^2/12", "position": [0, -0.5], "velocity": [0, 0], "angular_velocity": 0}],
      "contact": {"bodies": ["ball", "rod"], "point": [0, -1], "normal": [1, 0]},
      "pivots": [{"body": "rod", "point": [0, 0]}]})");
}

json valid3d()
{
    return json::parse(R"({
      "dimension": 3, "restitution": 1,
      "bodies": [
        {"name": "a", "mass": 1, "inertia": [1, 2, 3], "position": [0, -1, 0], "velocity": [0, 1, 0]},
        {"name": "b", "mass": 2, "inertia": [[2, 0, 0], [0, 2, 0], [0, 0, 2]], "position": [0.5, 1, 0], "velocity": [0, 0, 0]}],
      "contact": {"bodies": ["a", "b"], "point": [0, 0, 0], "normal": [0, 1, 0]}})");
}

// A system of format version 3: two legs joined at a hip, two contacts (one with friction).
json valid_system()
{
    return json::parse(R"({
      "dimension": 2, "restitution": 0.5,
      "bodies": [
        {"name": "ground", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
        {"name": "a", "mass": 1, "inertia": 1, "position": [0, 1], "velocity": [0, -1]},
        {"name": "b", "mass": 1, "inertia": 1, "position": [2, 1], "velocity": [0, -1]}],
      "joints": [{"bodies": ["a", "b"], "point": [1, 1]}],
      "contacts": [{"bodies": ["ground", "a"], "point": [0, 0], "normal": [0, 1]},
                   {"bodies": ["ground", "b"], "point": [2, 0], "normal": [0, 1], "friction": 0.3}]})");
}

json many(const json& item, std::size_t n)
{
    json list = json::array();
    for (std::size_t k = 0; k < n; ++k)
        list.push_back(item);
    return list;
}

struct bad_case {
    const char* name;
    std::function<std::string()> text;
    std::vector<const char*> expected; // substrings of the message
};

void PrintTo(const bad_case& c, std::ostream* os) { *os << c.name; }

std::string with(json j, const std::function<void(json&)>& f)
{
    f(j);
    return j.dump();
}

std::vector<bad_case> cases()
{
    return {
        {"malformed_json", [] { return std::string(R"({"dimension": 2,)"); }, {"malformed JSON"}},
        {"nested_too_deep", [] { return std::string(5000, '[') + std::string(5000, ']'); }, {"malformed JSON", "nested deeper"}},
        {"not_an_object", [] { return std::string("[1, 2]"); }, {"expected a JSON object"}},
        {"duplicate_key", [] { return std::string(R"({"dimension": 2, "dimension": 3})"); }, {"written twice", "dimension"}},
        {"missing_restitution", [] { return with(valid(), [](json& j) { j.erase("restitution"); }); }, {"missing key \"restitution\""}},
        {"contact_and_contacts", [] { return with(valid(), [](json& j) { j["contacts"] = json::array({j["contact"]}); }); }, {"contacts", "not both"}},
        {"no_contact", [] { return with(valid(), [](json& j) { j.erase("contact"); }); }, {"missing key \"contact\""}},
        {"contacts_not_a_list", [] { return with(valid(), [](json& j) { j["contacts"] = j["contact"]; j.erase("contact"); }); }, {"contacts", "expected a list"}},
        {"contacts_empty", [] { return with(valid(), [](json& j) { j["contacts"] = json::array(); j.erase("contact"); }); }, {"contacts", "empty list"}},
        {"contacts_bad_body", [] { return with(valid(), [](json& j) { j["contact"]["bodies"][1] = "nobody"; j["contacts"] = json::array({j["contact"]}); j.erase("contact"); }); }, {"contacts[0].bodies[1]"}},
        {"contacts_bad_restitution", [] { return with(valid(), [](json& j) { j["contact"]["restitution"] = -1; j["contacts"] = json::array({j["contact"]}); j.erase("contact"); }); }, {"restitution"}},
        {"no_restitution_anywhere", [] { return with(valid(), [](json& j) { j["contacts"] = json::array({j["contact"]}); j.erase("contact"); j.erase("restitution"); }); }, {"missing key \"restitution\""}},
        {"impacts_unknown", [] { return with(valid(), [](json& j) { j["impacts"] = "together"; }); }, {"impacts", "simultaneous"}},
        {"title_not_text", [] { return with(valid(), [](json& j) { j["title"] = 3; }); }, {"title", "expected a string"}},
        {"description_control", [] { return with(valid(), [](json& j) { j["description"] = std::string("a\x01b"); }); }, {"description", "control character"}},
        {"missing_bodies", [] { return with(valid(), [](json& j) { j.erase("bodies"); }); }, {"missing key \"bodies\""}},
        {"missing_normal", [] { return with(valid(), [](json& j) { j["contact"].erase("normal"); }); }, {"contact", "missing key \"normal\""}},
        {"missing_mass", [] { return with(valid(), [](json& j) { j["bodies"][0].erase("mass"); }); }, {"bodies[0]", "missing key \"mass\""}},
        {"missing_position", [] { return with(valid(), [](json& j) { j["bodies"][1].erase("position"); }); }, {"bodies[1]", "\"position\""}},
        {"bad_dimension", [] { return with(valid(), [](json& j) { j["dimension"] = 4; }); }, {"dimension", "2 or 3"}},
        {"zero_mass", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = 0; }); }, {"bodies[0]", "mass", "> 0"}},
        {"negative_mass", [] { return with(valid(), [](json& j) { j["bodies"][1]["mass"] = "-2"; }); }, {"bodies[1]", "mass", "> 0"}},
        {"mass_of_wrong_type", [] { return with(valid(), [](json& j) { j["bodies"][1]["mass"] = true; }); }, {"mass", "expected a number"}},
        {"negative_inertia_2d", [] { return with(valid(), [](json& j) { j["bodies"][1]["inertia"] = -1; }); }, {"inertia", "positive-definite"}},
        {"inertia_not_symmetric", [] { return with(valid3d(), [](json& j) { j["bodies"][1]["inertia"][0][1] = 1; }); }, {"bodies[1]", "inertia", "not symmetric"}},
        {"inertia_not_definite", [] { return with(valid3d(), [](json& j) { j["bodies"][0]["inertia"] = {1, -2, 3}; }); }, {"bodies[0]", "inertia", "positive-definite"}},
        {"inertia_wrong_shape", [] { return with(valid3d(), [](json& j) { j["bodies"][0]["inertia"] = {1, 2}; }); }, {"inertia", "3x3"}},
        {"restitution_above_one", [] { return with(valid(), [](json& j) { j["restitution"] = 1.5; }); }, {"restitution", "[0, 1]"}},
        {"restitution_negative", [] { return with(valid(), [](json& j) { j["restitution"] = -0.1; }); }, {"restitution", "[0, 1]"}},
        {"zero_normal", [] { return with(valid(), [](json& j) { j["contact"]["normal"] = {0, 0}; }); }, {"contact.normal", "zero"}},
        {"unknown_body", [] { return with(valid(), [](json& j) { j["contact"]["bodies"][1] = "bat"; }); }, {"contact.bodies[1]", "unknown body \"bat\""}},
        {"repeated_body_name", [] { return with(valid(), [](json& j) { j["bodies"][1]["name"] = "ball"; }); }, {"bodies[1].name", "repeated body"}},
        {"body_strikes_itself", [] { return with(valid(), [](json& j) { j["contact"]["bodies"] = {"ball", "ball"}; }); }, {"contact.bodies", "repeated body"}},
        {"vector_too_long", [] { return with(valid(), [](json& j) { j["bodies"][0]["position"] = {0, -1, 0}; }); }, {"bodies[0]", "position", "expected 2 components"}},
        {"vector_not_a_list", [] { return with(valid(), [](json& j) { j["contact"]["point"] = 3; }); }, {"contact.point", "expected a list"}},
        {"angular_velocity_3d_scalar", [] { return with(valid3d(), [](json& j) { j["bodies"][0]["angular_velocity"] = 1; }); }, {"angular_velocity", "expected a list"}},
        {"overflowing_number", [] { return std::string(R"({"dimension": 2, "restitution": 1e999})"); }, {"restitution", "out of the range of double"}},
        {"infinite_velocity", [] { return with(valid(), [](json& j) { j["bodies"][0]["velocity"][0] = "inf"; }); }, {"bodies[0]", "velocity", "not a finite value"}},
        {"nan_position", [] { return with(valid(), [](json& j) { j["bodies"][0]["position"][1] = "NaN"; }); }, {"position", "not a finite value"}},
        {"tower_of_powers", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "2^(2^40)"; }); }, {"bodies[0]", "mass", "beyond what is read"}},
        {"reserved_name", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "impactgen_number_0"; }); }, {"mass", "reserved"}},
        {"imaginary_unit", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "I"; }); }, {"mass", "imaginary"}},
        {"unreadable_expression", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "2*/3"; }); }, {"mass", "cannot read the expression"}},
        {"unknown_function", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "foo(2)"; }); }, {"mass", "unknown function"}},
        {"pivot_moves", [] { return with(valid(), [](json& j) { j["bodies"][1]["velocity"] = {1, 0}; }); }, {"pivots[0]", "moves before impact"}},
        {"pivot_unknown_body", [] { return with(valid(), [](json& j) { j["pivots"][0]["body"] = "door"; }); }, {"pivots[0].body", "unknown body"}},
        {"two_pivots_on_one_body", [] { return with(valid(), [](json& j) { j["pivots"].push_back({{"body", "rod"}, {"point", {0, 0}}}); }); }, {"pivots[1]", "second pivot"}},
        {"both_infinite", [] { return with(valid(), [](json& j) { j.erase("pivots"); j["bodies"][0]["mass"] = "inf"; j["bodies"][1]["mass"] = "inf"; }); }, {"no impulse can act"}},
        {"pinned_particle_and_wall", [] { return with(valid(), [](json& j) { j["bodies"][1]["mass"] = "inf"; j["pivots"][0]["body"] = "ball"; j["pivots"][0]["point"] = {0, -1}; j["bodies"][1]["velocity"] = {-1, 0}; j["bodies"][0]["velocity"] = {0, 0}; }); }, {"contact.bodies", "no impulse can act"}},
        {"pivot_on_infinite_mass", [] { return with(valid(), [](json& j) { j["bodies"][1]["mass"] = "inf"; }); }, {"pivots[0].body", "infinite mass"}},
        // Values that are not plain rationals are decided exactly, or refused (issue "Trust at the edges").
        {"separating_sqrt_normal", [] { return with(valid(), [](json& j) { j["contact"]["normal"] = {"-sqrt(2)/2", "sqrt(2)/2"}; }); }, {"not an impact", "separate"}},
        {"restitution_pi", [] { return with(valid(), [](json& j) { j["restitution"] = "Pi"; }); }, {"restitution", "[0, 1]"}},
        {"mass_sqrt_negative", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "sqrt(2)-2"; }); }, {"bodies[0] (\"ball\").mass", "> 0"}},
        {"mass_undecidable_zero", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "sin(1)^2+cos(1)^2-1"; }); }, {"bodies[0] (\"ball\").mass", "cannot be decided"}},
        {"normal_complex", [] { return with(valid(), [](json& j) { j["contact"]["normal"] = {"(-1)^(1/3)", 0}; }); }, {"contact.normal[0]", "not real"}},
        {"normal_complex_in_symbolic", [] { return with(valid(), [](json& j) { j["contact"]["normal"] = {"x*(-1)^(1/3)", 0}; }); }, {"contact.normal[0]", "not real"}},
        {"inertia_3d_indefinite", [] { return with(valid3d(), [](json& j) { j["bodies"][0]["inertia"] = {"-sqrt(2)", "-1", "1"}; }); }, {"bodies[0] (\"a\").inertia", "not positive-definite"}},
        // (found by a hostile pass: a 400-digit fraction cut at 120 characters; the reader's own rewritten text)
        {"tiny_negative_mass", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "-1e-400"; }); }, {"bodies[0] (\"ball\").mass", "got about -1e-400"}},
        {"malformed_number", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = ".e5"; }); }, {"bodies[0] (\"ball\").mass", "\".e5\" (a number is malformed)"}},
        {"huge_exp", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "exp(exp(1000))"; }); }, {"bodies[0] (\"ball\").mass", "above 10^400"}},
        {"function_without_argument", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "sin()"; }); }, {"bodies[0] (\"ball\").mass", "sin() needs an argument"}},
        {"sqrt_without_argument", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "sqrt( )"; }); }, {"sqrt() needs an argument"}},
        {"expression_too_long", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = "(" + std::string(8000, '(') + "1" + std::string(8001, ')'); }); }, {"bodies[0] (\"ball\").mass", "at most 1000"}},
        {"parentheses_too_deep", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = std::string(40, '(') + "1" + std::string(40, ')'); }); }, {"nested deeper than 32"}},
        {"too_many_signs", [] { return with(valid(), [](json& j) { j["bodies"][0]["mass"] = std::string(20, '-') + "1"; }); }, {"signs in a row"}},
        {"sum_of_symbols_too_long", [] {
             std::string sum;
             for (int k = 0; k < 2000; ++k)
                 sum += (k ? "+s" : "s") + std::to_string(k);
             return with(valid(), [&](json& j) { j["bodies"][0]["mass"] = sum; });
         }, {"at most 1000"}},
        {"too_many_symbols", [] {
             return with(valid3d(), [](json& j) {
                 for (int b = 0; b < 2; ++b)
                     for (int c = 0; c < 3; ++c)
                         for (const char* key : {"position", "velocity"})
                         {
                             std::string sum = "0";
                             for (int k = 0; k < 6; ++k) // 2 x 3 x 2 x 6 = 72 symbols
                                 sum += "+s" + std::string(1, key[0]) + std::to_string(b) + std::to_string(c) + std::to_string(k);
                             j["bodies"][b][key][c] = sum;
                         }
             });
         }, {"distinct symbols", "at most 64"}},
        {"name_with_newline", [] { return with(valid(), [](json& j) { j["bodies"][0]["name"] = "ball\n#define private public\n//"; j["contact"]["bodies"][0] = "ball\n#define private public\n//"; }); }, {"bodies[0].name", "control character"}},
        {"name_with_nul", [] { return with(valid(), [](json& j) { j["bodies"][0]["name"] = std::string("ba\0ll", 5); }); }, {"bodies[0].name", "control character", "\\x00"}},
        // Found by the fuzzer (tests/fuzz): huge symbolic exponents crashed codegen and hung explain.
        {"symbolic_exponent_too_large", [] { return with(valid(), [](json& j) { j["restitution"] = "e^30000"; }); }, {"restitution", "exponent larger than 64"}},
        {"symbolic_exponent_nested", [] { return with(valid3d(), [](json& j) { j["bodies"][0]["inertia"][0] = "x^(2^20)"; }); }, {"inertia[0]", "exponent larger than 64"}},
        // Found by the fuzzer with seed 7: a bystander's position 1e308*10 was accepted.
        {"number_beyond_double", [] { return with(valid(), [](json& j) { j["bodies"][1]["position"][1] = "1e308*10"; }); }, {"bodies[1] (\"rod\").position[1]", "range of double"}},
        {"decimal_beyond_double", [] {
             std::string t = with(valid(), [](json& j) { j["bodies"][1]["position"][1] = 777777; });
             return t.replace(t.find("777777"), 6, "1e309"); // a JSON number token beyond double
         }, {"position", "range of double"}},
        {"file_too_large", [] { return with(valid(), [](json& j) { j["description"] = std::string(70000, 'x'); }); }, {"at most 65536"}},
        // Systems (format version 3)
        {"contacts_too_many", [] { return with(valid_system(), [](json& j) { j["contacts"] = many(j["contacts"][0], 65); }); }, {"contacts", "at most 64"}},
        // (one contact with joints is answered: test_laws_systems.cpp; several are refused)
        {"system_process_law_with_friction", [] { return with(valid_system(), [](json& j) { j["contacts"][1]["law"] = "poisson"; }); }, {"contacts[1].law", "poisson", "applies to one contact"}},
        {"system_energetic_law_rough", [] { return with(valid_system(), [](json& j) { j["contacts"][0]["law"] = "energetic"; j["contacts"][0]["friction"] = "inf"; }); }, {"law"}},
        {"joints_not_a_list", [] { return with(valid_system(), [](json& j) { j["joints"] = 3; }); }, {"joints", "expected a list"}},
        {"joints_too_many", [] { return with(valid_system(), [](json& j) { j["joints"] = many(j["joints"][0], 65); }); }, {"joints", "at most 64"}},
        {"joint_not_an_object", [] { return with(valid_system(), [](json& j) { j["joints"][0] = 1; }); }, {"joints[0]", "expected an object"}},
        {"joint_one_body", [] { return with(valid_system(), [](json& j) { j["joints"][0]["bodies"] = {"a"}; }); }, {"joints[0].bodies", "two bodies"}},
        {"joint_unknown_body", [] { return with(valid_system(), [](json& j) { j["joints"][0]["bodies"][1] = "c"; }); }, {"joints[0].bodies[1]", "unknown body \"c\""}},
        {"joint_same_body", [] { return with(valid_system(), [](json& j) { j["joints"][0]["bodies"] = {"a", "a"}; }); }, {"joints[0].bodies", "repeated body"}},
        {"joint_missing_point", [] { return with(valid_system(), [](json& j) { j["joints"][0].erase("point"); }); }, {"joints[0]", "missing key \"point\""}},
        {"joint_point_length", [] { return with(valid_system(), [](json& j) { j["joints"][0]["point"] = {1, 1, 0}; }); }, {"joints[0].point", "components"}},
        {"joint_both_infinite", [] { return with(valid_system(), [](json& j) { j["bodies"][1]["mass"] = "inf"; j["joints"][0]["bodies"] = {"ground", "a"}; }); }, {"joints[0].bodies", "infinite mass"}},
        {"joint_comes_apart", [] { return with(valid_system(), [](json& j) { j["bodies"][2]["velocity"] = {0, -2}; }); }, {"joints[0]", "comes apart before impact"}},
        {"contact_restitution_above_one", [] { return with(valid_system(), [](json& j) { j["contacts"][1]["restitution"] = 2; }); }, {"contacts[1].restitution", "[0, 1]"}},
        {"contacts_restitution_missing", [] { return with(valid_system(), [](json& j) { j.erase("restitution"); j["contacts"][0]["restitution"] = 1; }); }, {"missing key \"restitution\""}},
        {"contact_friction_negative", [] { return with(valid_system(), [](json& j) { j["contacts"][1]["friction"] = -1; }); }, {"contacts[1].friction", ">= 0"}},
        {"contact_zero_normal", [] { return with(valid_system(), [](json& j) { j["contacts"][0]["normal"] = {0, 0}; }); }, {"contacts[0].normal", "zero"}},
        {"contact_strikes_itself", [] { return with(valid_system(), [](json& j) { j["contacts"][0]["bodies"] = {"a", "a"}; }); }, {"contacts[0].bodies", "repeated body"}},
        {"contact_unknown_body", [] { return with(valid_system(), [](json& j) { j["contacts"][1]["bodies"][0] = "floor"; }); }, {"contacts[1].bodies[0]", "unknown body"}},
        {"contacts_no_approach", [] { return with(valid_system(), [](json& j) { j["bodies"][1]["velocity"] = {0, 1}; j["bodies"][2]["velocity"] = {0, 1}; }); }, {"contacts", "not an impact"}},
        {"contacts_friction_3d", [] { return std::string(R"({"dimension": 3, "restitution": 0.5, "bodies": [
            {"name": "ground", "mass": "inf", "position": [0, -1, 0], "velocity": [0, 0, 0]},
            {"name": "box", "mass": 1, "inertia": [1, 1, 1], "position": [0, 1, 0], "velocity": [0, -1, 0]}],
            "contacts": [{"bodies": ["ground", "box"], "point": [1, 0, 0], "normal": [0, 1, 0]},
                         {"bodies": ["ground", "box"], "point": [-1, 0, 0], "normal": [0, 1, 0], "friction": 0.3}]})"); }, {"contacts[1].friction", "3-D", "closed form"}},
        {"contacts_too_many_candidates", [] { return with(valid_system(), [](json& j) { j["contacts"] = many(j["contacts"][0], 13); }); }, {"contacts", "candidate sets", "4096"}},
        {"contacts_no_set_holds", [] { return std::string(R"({"dimension": 2, "restitution": 0.5, "bodies": [
            {"name": "wall", "mass": "inf", "position": [2, 0], "velocity": [-1, 0]},
            {"name": "rod", "mass": 1, "inertia": 1, "position": [0, 0], "velocity": [0, 0]}],
            "pivots": [{"body": "rod", "point": [0, 0]}],
            "contacts": [{"bodies": ["wall", "rod"], "point": [1, 0], "normal": [-1, 0], "friction": "inf"}]})"); }, {"contacts", "no set of contacts"}},
        {"sequential_without_end", [] { return std::string(R"({"dimension": 2, "restitution": 1, "impacts": "sequential", "bodies": [
            {"name": "left", "mass": "inf", "position": [-1, 0], "velocity": [0, 0]},
            {"name": "right", "mass": "inf", "position": [1, 0], "velocity": [0, 0]},
            {"name": "ball", "mass": 1, "position": [0, 0], "velocity": [-1, 0]}],
            "contacts": [{"bodies": ["left", "ball"], "point": [0, 0], "normal": [1, 0]},
                         {"bodies": ["ball", "right"], "point": [0, 0], "normal": [1, 0]}]})"); }, {"impacts", "64 steps"}},
        {"separating", [] { return with(valid(), [](json& j) { j["bodies"][0]["velocity"] = {-5, 0}; }); }, {"not an impact", "separate"}},
        {"resting", [] { return with(valid(), [](json& j) { j["bodies"][0]["velocity"] = {0, 3}; }); }, {"not an impact", "rest"}},
        // Restitution laws (format version 3, "law"): an unknown name, and poisson/energetic where
        // the process has no closed form (3-D friction, "friction": "inf", several contacts).
        {"law_unknown", [] { return with(valid(), [](json& j) { j["contact"]["law"] = "stronge"; }); }, {"contact.law", "unknown law \"stronge\""}},
        {"law_not_text", [] { return with(valid(), [](json& j) { j["contact"]["law"] = 2; }); }, {"contact.law", "expected \"newton\""}},
        {"law_unknown_in_contacts", [] { return with(valid(), [](json& j) { j["contact"]["law"] = "Poisson"; j["contacts"] = json::array({j["contact"]}); j.erase("contact"); }); }, {"contacts[0].law", "unknown law"}},
        {"law_poisson_3d_friction", [] { return with(valid3d(), [](json& j) { j["contact"]["law"] = "poisson"; j["contact"]["friction"] = 0.3; }); }, {"contact.law", "\"poisson\"", "2-D only"}},
        {"law_energetic_3d_friction", [] { return with(valid3d(), [](json& j) { j["contact"]["law"] = "energetic"; j["contact"]["friction"] = "mu"; }); }, {"contact.law", "\"energetic\"", "2-D only"}},
        {"law_poisson_friction_inf", [] { return with(valid(), [](json& j) { j["contact"]["law"] = "poisson"; j["contact"]["friction"] = "inf"; }); }, {"contact.law", "\"inf\""}},
        {"law_energetic_several_contacts", [] { return with(valid(), [](json& j) {
             json c2 = j["contact"];
             c2["point"] = {0, -1.5};
             j["contact"]["law"] = "energetic";
             j["contact"]["friction"] = 0.5;
             j["contacts"] = json::array({c2, j["contact"]});
             j.erase("contact"); }); }, {"contacts[1].law", "\"energetic\"", "one contact"}},
    };
}

class BadInput : public ::testing::TestWithParam<bad_case> {};

TEST_P(BadInput, RefusedWithAMessageNamingTheKey)
{
    const bad_case& c = GetParam();
    std::string text = c.text();
    try {
        problem p = read_problem(text, "case.json");
        if (p.is_system())
            solve_system(p);
        else
            solve(derive(p));
        FAIL() << c.name << ": accepted " << text;
    } catch (const input_error& e) {
        std::string msg = e.what();
        for (const char* part : c.expected)
            EXPECT_NE(msg.find(part), std::string::npos) << c.name << ": message \"" << msg << "\" lacks \"" << part << "\"";
    }
}

INSTANTIATE_TEST_SUITE_P(Categories, BadInput, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<bad_case>& i) { return std::string(i.param.name); });

TEST(BadInput, ContactThroughThePivotOfTheOnlyMovableBody)
{
    // A wall pushes the hinged rod straight through its pivot: nothing can move.
    std::string text = with(valid(), [](json& j) {
        j["bodies"][0] = {{"name", "wall"}, {"mass", "inf"}, {"position", {0, 1}}, {"velocity", {0, -1}}};
        j["contact"]["point"] = {0, 0};
        j["contact"]["normal"] = {0, -1};
        j["contact"]["bodies"] = {"wall", "rod"};
    });
    try {
        solve(derive(read_problem(text, "case.json")));
        FAIL() << "accepted";
    } catch (const input_error& e) {
        EXPECT_NE(std::string(e.what()).find("no impulse can act"), std::string::npos) << e.what();
    }
}

struct run_result {
    int code;
    std::string out, err;
};

run_result run_cli(const std::string& args)
{
    // Unique per process and test: ctest runs the tests in parallel.
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string base = ::testing::TempDir() + "impactgen_" + info->name() + "_" + std::to_string(getpid());
    std::string cmd = std::string(IMPACTGEN_CLI) + " " + args + " >" + base + ".out 2>" + base + ".err";
    int status = std::system(cmd.c_str());
    auto slurp = [](const std::string& f) {
        std::ifstream in(f);
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    };
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(base + ".out"), slurp(base + ".err")};
}

TEST(Cli, EveryBadInputExitsOneWithOneLine)
{
    std::string file = ::testing::TempDir() + "impactgen_bad_" + std::to_string(getpid()) + ".json";
    for (const bad_case& c : cases()) {
        {
            std::ofstream out(file);
            out << c.text();
        }
        run_result r = run_cli("solve --json " + file);
        EXPECT_EQ(r.code, 1) << c.name;
        EXPECT_TRUE(r.out.empty()) << c.name << ": printed an answer for bad input: " << r.out;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.name << ": " << r.err;
        EXPECT_EQ(r.err.rfind("impactgen: error: ", 0), 0u) << c.name << ": " << r.err;
    }
}

TEST(Cli, UsageErrorsExitTwo)
{
    EXPECT_EQ(run_cli("").code, 2);
    EXPECT_EQ(run_cli("solve").code, 2);
    EXPECT_EQ(run_cli("formulas planar --format html").code, 2);
    run_result r = run_cli("formulas no-such-class");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("neither a named class"), std::string::npos) << r.err;
    EXPECT_EQ(run_cli("solve planar").code, 1); // symbols: solve refuses, formulas is the tool
}

TEST(Cli, ListPrintsEveryGroupOfNamedClasses)
{
    run_result r = run_cli("list");
    ASSERT_EQ(r.code, 0) << r.err;
    r.out = "\n" + r.out;
    for (const auto* group : {&impactgen::named_classes(), &impactgen::friction_classes(), &impactgen::law_classes()})
        for (const impactgen::named_class& c : *group)
            EXPECT_NE(r.out.find("\n" + c.name + " "), std::string::npos) << c.name << " missing from:\n" << r.out;
    // The law classes in a group of their own, after the friction classes.
    const std::size_t group = r.out.find("restitution followed through the impact");
    ASSERT_NE(group, std::string::npos) << r.out;
    EXPECT_GT(r.out.find("\nrod-rough-floor "), group);
    EXPECT_GT(group, r.out.find("\nplanar-friction "));
    // And an unknown name lists them too.
    EXPECT_NE(run_cli("formulas no-such-class").err.find("rod-rough-floor"), std::string::npos);
}

TEST(Cli, SolveJsonIsTheAnswerObject)
{
    run_result r = run_cli("solve --json " IMPACTGEN_SOURCE_DIR "/examples/problems/hinged-rod.json");
    ASSERT_EQ(r.code, 0) << r.err;
    json a = json::parse(r.out);
    // The answer is exact and rounded once to double: 1e-15 is a few ulps of values of order 1..4;
    // the energy difference adds two more roundings (1e-14 on values of order 6).
    EXPECT_NEAR(a["bodies"]["ball"]["velocity"][0].get<double>(), -1.0 / 7, 1e-15);
    EXPECT_NEAR(a["bodies"]["rod"]["angular_velocity"].get<double>(), 27.0 / 7, 1e-15);
    EXPECT_NEAR(a["normal_impulse"].get<double>(), 18.0 / 7, 1e-15);
    ASSERT_EQ(a["pivot_impulses"].size(), 1u);
    EXPECT_NEAR(a["pivot_impulses"][0][0].get<double>(), 9.0 / 7, 1e-15);
    EXPECT_NEAR(a["kinetic_energy"]["before"].get<double>() - a["kinetic_energy"]["after"].get<double>(),
                a["kinetic_energy"]["lost"].get<double>(), 1e-14);
}

TEST(Cli, FormulasJsonReadsBackWithGinacsParser)
{
    run_result r = run_cli("formulas pinned-planar --format json");
    ASSERT_EQ(r.code, 0) << r.err;
    json a = json::parse(r.out);
    GiNaC::symtab t;
    for (const char* n : {"m1", "m2", "v1", "l", "e"})
        t[n] = symbol_named(n);
    GiNaC::parser reader(t, true);
    GiNaC::ex w = reader(a["bodies"]["2"]["angular_velocity"].get<std::string>());
    GiNaC::ex m1 = t["m1"], m2 = t["m2"], v1 = t["v1"], l = t["l"], e = t["e"];
    // The notes' result for the uniform rod: w' = 3 m1 v1 (1 + e) / (l (3 m1 + m2)).
    EXPECT_TRUE((w - 3 * m1 * v1 * (1 + e) / (l * (3 * m1 + m2))).normal().is_zero()) << w;
    EXPECT_TRUE(a["pivot_impulses"].is_array());
}

} // namespace

namespace {

// Inputs that hung or crashed a command (issue "Trust at the edges"): each must
// now finish with exit 0 or a one-line refusal. --time-limit turns a hang into a
// failing exit instead of a stuck test; nothing here is a timing assertion.
const char* const edge_files[] = {"symbolic-3d.json", "symbolic-3d-axis-normal.json", "symbolic-3d-ball-joint.json",
                                  "power-of-sum-in-point.json", "power-of-sum-mass-pinned.json",
                                  "abs-normal-2d.json"};
const char* const commands[] = {"formulas", "formulas --format json", "formulas --format latex", "explain",
                                "explain --format latex", "explain --format markdown", "codegen"};

TEST(Cli, InputsThatHungOrCrashedFinish)
{
    for (const char* f : edge_files)
        for (const char* c : commands) {
            const std::string file = std::string(IMPACTGEN_SOURCE_DIR "/tests/core/edges/") + f;
            run_result r = run_cli(std::string("--time-limit 60 ") + c + " " + file);
            const bool refused_cleanly = r.code == 1 && std::count(r.err.begin(), r.err.end(), '\n') == 1 &&
                                         r.err.rfind("impactgen: error: ", 0) == 0 && r.err.find("time budget") == std::string::npos;
            EXPECT_TRUE(r.code == 0 || refused_cleanly) << c << " " << f << ": exit " << r.code << ": " << r.err;
            // codegen refuses abs(x) (no C++ arithmetic for it); every other command answers.
            if (std::string(c) != "codegen" || std::string(f) != "abs-normal-2d.json") {
                EXPECT_EQ(r.code, 0) << c << " " << f << ": " << r.err;
            }
        }
}

TEST(Cli, FormulasJsonOfNamedClassesIsParseableAndStepFree)
{
    // The README's own command: noncentral-3d --format json (it hung in normal()).
    for (const char* cls : {"noncentral-3d", "massive-3d", "planar", "pinned-planar", "central-direct", "central-oblique"}) {
        run_result r = run_cli(std::string("--time-limit 60 formulas ") + cls + " --format json");
        ASSERT_EQ(r.code, 0) << cls << ": " << r.err;
        json a = json::parse(r.out);
        GiNaC::parser reader; // no symbol table given: unknown names become new symbols
        GiNaC::ex N = reader(a["normal_impulse"].get<std::string>());
        // written in the problem's symbols only: no step name (w_1, k, u, N ...) is left
        for (const char* step : {"w_1", "w_2", "k", "u", "N", "T_lost", "D_1", "g_t1"})
            EXPECT_EQ(a["normal_impulse"].get<std::string>().find(std::string(step) + "*"), std::string::npos) << cls;
        EXPECT_FALSE(N.is_zero()) << cls;
    }
}

TEST(Cli, UnwritableOutputsAreErrors)
{
    run_result r = run_cli("codegen planar --output /dev/null");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
    if (std::ifstream("/dev/full")) {
        int status = std::system((std::string(IMPACTGEN_CLI) + " codegen planar > /dev/full 2>/dev/null").c_str());
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << "a failed write to stdout must not exit 0";
        status = std::system((std::string(IMPACTGEN_CLI) + " solve " IMPACTGEN_SOURCE_DIR "/examples/problems/hinged-rod.json > /dev/full 2>/dev/null").c_str());
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1);
    }
    r = run_cli("solve /dev/zero");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
}

TEST(Cli, TimeBudgetStopsWithAMessage)
{
    run_result r = run_cli("--time-limit 0.000001 formulas " IMPACTGEN_SOURCE_DIR "/tests/core/edges/symbolic-3d-ball-joint.json --format json");
    // Either done within a microsecond (impossible in practice) or stopped with one line.
    if (r.code != 0) {
        EXPECT_EQ(r.code, 1);
        EXPECT_NE(r.err.find("time budget"), std::string::npos) << r.err;
    }
}

} // namespace

namespace {

TEST(Cli, JsonAnswersAreByteStableAcrossProcesses)
{
    // GiNaC's term order moves between runs; the printed answer must not.
    for (const char* args : {"formulas noncentral-3d --format json", "formulas pinned-planar --format json",
                             "solve --json " IMPACTGEN_SOURCE_DIR "/examples/problems/puck-block-34.json",
                             "formulas " IMPACTGEN_SOURCE_DIR "/examples/problems/pinned-3d.json --format json"}) {
        run_result first = run_cli(args);
        ASSERT_EQ(first.code, 0) << args << ": " << first.err;
        for (int k = 0; k < 3; ++k)
            EXPECT_EQ(run_cli(args).out, first.out) << args << ": run " << k + 2 << " differs";
    }
}

TEST(Cli, ParserSyntaxReadsBackExactly)
{
    // Every expression string of the JSON answer is GiNaC parser syntax of the same value.
    run_result r = run_cli("formulas " IMPACTGEN_SOURCE_DIR "/tests/core/edges/symbolic-3d-ball-joint.json --format json");
    ASSERT_EQ(r.code, 0) << r.err;
    json a = json::parse(r.out);
    GiNaC::parser reader;
    GiNaC::ex before = reader(a["kinetic_energy"]["before"].get<std::string>());
    GiNaC::ex after = reader(a["kinetic_energy"]["after"].get<std::string>());
    GiNaC::ex lost = reader(a["kinetic_energy"]["lost"].get<std::string>());
    // after = before - lost, checked at a rational point (the symbols as the reader made them)
    GiNaC::exmap at;
    int k = 2;
    for (const auto& [name, sym] : reader.get_syms())
        at[sym] = GiNaC::numeric(k++, 7);
    EXPECT_TRUE((before - lost - after).subs(at).normal().is_zero());
}

} // namespace

namespace {

TEST(Reader, ZeroFactorsAreNumbers)
{
    // Found by the fuzzer: an exact zero factor (0/3, 0*2, 0^2) was taken for a huge number.
    for (const char* zero : {"0/3", "0*2", "2*0", "0^2", "0.0*5"}) {
        std::string text = with(valid(), [&](json& j) { j["bodies"][0]["position"][0] = zero; });
        problem p = read_problem(text, "case.json");
        EXPECT_TRUE(p.bodies[0].position[0].is_zero()) << zero;
    }
}

// A number below 10^-400 underflows: it is refused as too small, not as "out of the range
// of double (non-finite number)", which it is not; a zero with any exponent is 0.
TEST(Reader, UnderflowIsTooSmallNotNonFinite)
{
    // The literal is put in the text as written (nlohmann's json would read it as the double 0).
    auto with_literal = [](const char* key_path, const char* literal) {
        std::string text = with(valid(), [&](json& j) { j[json::json_pointer(key_path)] = "PLACEHOLDER"; });
        text.replace(text.find("\"PLACEHOLDER\""), 13, literal);
        return text;
    };
    for (const char* tiny : {"1e-1000", "-2.5e-9999999", "0.001e-399", "9.99e-401", "1e-401"}) {
        try {
            read_problem(with_literal("/contact/normal/1", tiny), "case.json");
            ADD_FAILURE() << tiny << " accepted";
        } catch (const input_error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("too small"), std::string::npos) << tiny << ": " << msg;
            EXPECT_NE(msg.find("contact.normal[1]"), std::string::npos) << tiny << ": " << msg;
            EXPECT_EQ(msg.find("non-finite"), std::string::npos) << tiny << ": " << msg;
        }
    }
    for (const char* zero : {"0e-9999999", "0.0e-1000"})
        EXPECT_TRUE(read_problem(with_literal("/bodies/0/position/0", zero), "case.json").bodies[0].position[0].is_zero()) << zero;
    // In an expression string, a tiny value is not called non-finite either.
    for (const char* tiny : {"1/10^500", "(1e-200)^3"}) {
        std::string text = with(valid(), [&](json& j) { j["bodies"][0]["mass"] = tiny; });
        try {
            read_problem(text, "case.json");
            ADD_FAILURE() << tiny << " accepted";
        } catch (const input_error& e) {
            EXPECT_EQ(std::string(e.what()).find("non-finite"), std::string::npos) << tiny << ": " << e.what();
            EXPECT_NE(std::string(e.what()).find("below 10^-400"), std::string::npos) << tiny << ": " << e.what();
        }
    }
    // Exponents with leading zeros or a plus sign are the numbers they write (found by a hostile pass).
    const std::pair<const char*, GiNaC::numeric> same[] = {{"1e-000003", GiNaC::numeric(1, 1000)},
                                                           {"1e+0000000000000000000003", GiNaC::numeric(1000)},
                                                           {"0.17e0000000000000000000000", GiNaC::numeric(17, 100)},
                                                           {"5E+2", GiNaC::numeric(500)}};
    for (const auto& [literal, value] : same) {
        const GiNaC::ex x = read_problem(with_literal("/bodies/0/position/0", literal), "case.json").bodies[0].position[0];
        EXPECT_TRUE((x - value).is_zero()) << literal << " read as " << x;
    }
    // 1e-400 itself is read exactly.
    const GiNaC::ex x = read_problem(with_literal("/bodies/0/position/0", "1e-400"), "case.json").bodies[0].position[0];
    EXPECT_TRUE((x - GiNaC::pow(GiNaC::numeric(10), -400)).is_zero()) << x;
}

TEST(Reader, TinyTimesHugeIsOne)
{
    // The reader's magnitude bound counts a small factor as shrinking a product: 1e-300*1e300
    // was refused as beyond double range before the two bounds were made one.
    std::string text = with(valid(), [](json& j) { j["bodies"][0]["mass"] = "1e-300*1e300"; });
    problem p = read_problem(text, "case.json");
    EXPECT_TRUE((p.bodies[0].mass - 1).is_zero()) << p.bodies[0].mass;
}

TEST(Cli, OverflowingAnswerNamesTheKey)
{
    std::string file = ::testing::TempDir() + "impactgen_overflow_" + std::to_string(getpid()) + ".json";
    std::ofstream(file) << with(valid(), [](json& j) {
        j["pivots"] = json::array();
        j["bodies"][0]["mass"] = 1e300;
        j["bodies"][0]["velocity"] = {1e300, 0};
    });
    run_result r = run_cli("solve --json " + file);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("answer: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("out of the range of double"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// The symmetric case: an answer whose exact value is not 0 but below the smallest subnormal
// double would be written as 0: refused in one line naming the key (a subnormal is written:
// Friction.SubnormalValuesAreNotPrintedAsZero).
TEST(Cli, UnderflowingAnswerNamesTheKey)
{
    std::string file = ::testing::TempDir() + "impactgen_underflow_" + std::to_string(getpid()) + ".json";
    std::ofstream(file) << with(valid(), [](json& j) {
        j["pivots"] = json::array();
        j["bodies"][0]["mass"] = "1e-300";
        j["bodies"][0]["velocity"] = {"1e-300", 0};
    });
    run_result r = run_cli("solve --json " + file);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("answer: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("below the range of double"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    // The text answer prints the exact value and its decimal, never "= 0" for it.
    run_result t = run_cli("solve " + file);
    EXPECT_EQ(t.code, 0) << t.err;
    const std::size_t at = t.out.find("normal impulse");
    ASSERT_NE(at, std::string::npos) << t.out;
    const std::string line = t.out.substr(at, t.out.find('\n', at) - at);
    EXPECT_NE(line.find("e-60"), std::string::npos) << line; // about 1.5e-600
    EXPECT_EQ(line.find("= 0"), std::string::npos) << line;
    // An exact 0 stays 0 (a body at rest that the impulse does not reach).
    std::ofstream(file) << with(valid(), [](json& j) { j["pivots"] = json::array(); });
    EXPECT_EQ(run_cli("solve --json " + file).code, 0);
}

// An answer with roots prints them merged (sqrt(3)*sqrt(6) is 3*sqrt(2)), in solve's text and
// in the JSON with exact values, and explain's numbers the same.
TEST(Cli, RadicalAnswersMergeTheirRoots)
{
    std::string file = ::testing::TempDir() + "impactgen_radical_" + std::to_string(getpid()) + ".json";
    std::ifstream in(IMPACTGEN_SOURCE_DIR "/examples/problems/plate-struck-obliquely.json");
    json j = json::parse(in);
    j["contact"]["normal"] = {"sqrt(2)", 1, 0};
    std::ofstream(file) << j.dump();
    for (const char* cmd : {"solve ", "explain "}) {
        run_result r = run_cli(cmd + file);
        ASSERT_EQ(r.code, 0) << cmd << r.err;
        EXPECT_EQ(r.out.find("sqrt(3)*sqrt(6)"), std::string::npos) << cmd;
        EXPECT_EQ(r.out.find("√3·√6"), std::string::npos) << cmd;
        EXPECT_NE(r.out.find("8316"), std::string::npos) << cmd; // 179507 + 8316 sqrt(2) in the denominators
    }
}

TEST(Cli, DefaultFunctionNameFromAnyFileName)
{
    // A stem that is one of the header's own names (n, out, ok) or starts with a digit.
    for (const char* stem : {"n", "out", "9-ball", "int", "class_", "IMPACTGEN_HOT", "M_PI"}) {
        std::string file = ::testing::TempDir() + stem + ".json";
        std::ifstream in(IMPACTGEN_SOURCE_DIR "/examples/problems/hinged-rod.json");
        std::ofstream(file) << in.rdbuf();
        run_result r = run_cli("codegen " + file);
        EXPECT_EQ(r.code, 0) << stem << ": " << r.err;
        std::remove(file.c_str());
    }
}

} // namespace

namespace {

TEST(Cli, ClosedPipeIsAnErrorNotASignal)
{
    // impactgen explain ... | true: the write fails (EPIPE); the exit is 1 with a message, never SIGPIPE.
    std::string cmd = std::string("bash -c 'set -o pipefail; ") + IMPACTGEN_CLI + " explain noncentral-3d 2>/dev/null | true; echo $?'";
    FILE* f = popen(cmd.c_str(), "r");
    ASSERT_NE(f, nullptr);
    char buf[32] = {};
    ASSERT_NE(std::fgets(buf, sizeof buf, f), nullptr);
    pclose(f);
    const int code = std::atoi(buf);
    EXPECT_TRUE(code == 0 || code == 1) << "exit " << code << " (141 is death by SIGPIPE)";
}

TEST(Cli, UsageErrorsAreOneLine)
{
    for (const char* args : {"", "foo", "solve", "--time-limit nan list", "formulas planar --format html"}) {
        run_result r = run_cli(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("impactgen: error: ", 0), 0u) << args << ": " << r.err;
    }
    EXPECT_NE(run_cli("foo").err.find("unknown subcommand \"foo\""), std::string::npos);
}

TEST(Reader, LongDecimalsAreExact)
{
    // 0.47 followed by 400 digits is a number near 0.47, not "out of the range of double".
    std::string e = "0.47" + std::string(400, '3');
    std::string text = with(valid(), [&](json& j) { j["restitution"] = json::parse(e); });
    problem p = read_problem(text, "case.json");
    EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(p.restitution));
}

} // namespace

// formulas --jacobian --format json: the entries, written in the closed form's
// steps and the derivative steps, equal the derivatives of the answer's own
// formulas (in inputs only, from the solver, not from the chain rule), exactly
// at seeded random rational points.
TEST(Cli, FormulasJacobianMatchesDerivativesOfTheAnswer)
{
    // A problem whose symbols are named like the derivative steps (dN_dm1) and the impulse (N):
    // the steps are renamed clear of them, so the JSON reads back unambiguously.
    const std::string clash = ::testing::TempDir() + "impactgen_clash_" + std::to_string(getpid()) + ".json";
    {
        std::ofstream out(clash);
        out << R"({"dimension": 2, "restitution": "e", "bodies": [
            {"name": "a", "mass": "m1", "position": [0, 0], "velocity": ["dN_dm1", 0]},
            {"name": "b", "mass": "N", "position": [1, 0], "velocity": ["dw_1_dm1", 0]}],
            "contact": {"bodies": ["a", "b"], "point": [0.5, 0], "normal": [1, 0]}})";
    }
    for (const std::string cls : {"central-direct", "central-oblique", "planar", "pinned-planar", clash.c_str()}) {
        run_result r = run_cli("formulas " + cls + " --jacobian --format json");
        ASSERT_EQ(r.code, 0) << cls << ": " << r.err;
        auto a = nlohmann::json::parse(r.out);
        const auto& j = a.at("jacobian");
        auto parse = [&](const std::string& t) { return impactgen::parse_value(t, true, "jacobian test"); };
        // Steps in order: each substituted into the later ones (from the last back).
        std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> steps;
        std::set<std::string> step_names;
        for (const char* key : {"closed_form_steps", "steps"})
            for (const auto& st : j.at(key)) {
                const std::string name = st.at("name").get<std::string>();
                EXPECT_TRUE(step_names.insert(name).second) << cls << ": step " << name << " twice";
                steps.push_back({impactgen::symbol_named(name), parse(st.at("value").get<std::string>())});
            }
        for (const auto& w : j.at("wrt"))
            EXPECT_FALSE(step_names.count(w.get<std::string>())) << cls << ": a step is named like the input " << w;
        auto expand_steps = [&](GiNaC::ex e) {
            for (auto it = steps.rbegin(); it != steps.rend(); ++it)
                e = e.subs(it->first == it->second);
            return e;
        };
        // The answer's formulas for some outputs, in inputs only.
        std::map<std::string, GiNaC::ex> answer;
        answer["normal_impulse"] = parse(a.at("normal_impulse").get<std::string>());
        answer["energy_lost"] = parse(a.at("kinetic_energy").at("lost").get<std::string>());
        const auto& outputs = j.at("outputs");
        std::vector<GiNaC::symbol> wrt;
        for (const auto& w : j.at("wrt"))
            wrt.push_back(impactgen::symbol_named(w.get<std::string>()));
        ASSERT_FALSE(wrt.empty());
        std::mt19937 rng(2026);
        int compared = 0;
        for (int trial = 0; trial < 3; ++trial) {
            GiNaC::lst point;
            for (const auto& x : wrt) // positive values keep masses and inertia valid
                point.append(x == GiNaC::numeric(static_cast<int>(rng() % 97 + 3), static_cast<int>(rng() % 13 + 7)));
            for (std::size_t o = 0; o < outputs.size(); ++o) {
                auto it = answer.find(outputs[o].get<std::string>());
                if (it == answer.end())
                    continue;
                for (std::size_t k = 0; k < wrt.size(); ++k) {
                    GiNaC::ex entry = expand_steps(parse(j.at("entries")[o][k].get<std::string>())).subs(point);
                    GiNaC::ex exact = it->second.diff(wrt[k]).subs(point);
                    EXPECT_TRUE((entry - exact).normal().is_zero())
                        << cls << ": d " << it->first << " / d " << wrt[k] << " = " << entry << ", the answer's derivative " << exact;
                    ++compared;
                }
            }
        }
        EXPECT_GT(compared, 0) << cls;
    }
    run_result bad = run_cli("formulas planar --wrt nosuch");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("--wrt: nosuch is not an input"), std::string::npos) << bad.err;
}

// Coulomb friction (format version 2, contact.friction) from the command line:
// hostile values of mu, exact thresholds, edge cases checked against hand
// solutions, and the findings of the friction fuzzer (tests/fuzz) and of a
// hostile session with the feature.
namespace {

// A floor (infinite mass) and a particle of mass 1 falling on it at (vx, -1), e = 1/2:
// u_n = -1, u_t = vx, K = 1: stick P = (-vx, 3/2), so mu* = |vx| / (3/2).
std::string floor_particle(const std::string& mu, const std::string& vx = "3")
{
    return R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
        {"name": "p", "mass": 1, "position": [0, 0], "velocity": [)" + vx + R"(, -1]}],
      "contact": {"bodies": ["floor", "p"], "point": [0, 0], "normal": [0, 1], "friction": )" + mu + "}}";
}

// A problem's text in a file of this test, then impactgen with the arguments.
run_result run_on(const std::string& text, const std::string& args, const std::string& tag = "")
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string file = ::testing::TempDir() + "impactgen_fr_" + info->name() + tag + "_" + std::to_string(getpid()) + ".json";
    std::ofstream(file) << text;
    run_result r = run_cli(args + " " + file);
    std::remove(file.c_str());
    return r;
}

void expect_refusal(const run_result& r, const std::string& what, const std::string& part)
{
    EXPECT_EQ(r.code, 1) << what << ": " << r.out << r.err;
    EXPECT_TRUE(r.out.empty()) << what << ": printed " << r.out;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
    EXPECT_EQ(r.err.rfind("impactgen: error: ", 0), 0u) << what << ": " << r.err;
    EXPECT_NE(r.err.find(part), std::string::npos) << what << ": the message lacks \"" << part << "\": " << r.err;
}

double number_at(const json& a, std::initializer_list<const char*> path, int index = -1)
{
    const json* x = &a;
    for (const char* k : path)
        x = &x->at(k);
    return index < 0 ? x->get<double>() : x->at(static_cast<std::size_t>(index)).get<double>();
}

TEST(Friction, HostileValuesOfMuAreRefusedNamingTheKey)
{
    const std::vector<std::string> values = {
        "-1", "\"-10^(-300)\"", "\"1/3 - sqrt(2)/4\"", "\"-inf\"", "\"NaN\"", "\"I\"", "\"(-1)^(1/3)\"", "\"asin(2)\"",
        "null", "true", "[0.3]", "{\"mu\": 0.3}", "\"\"", "\" \"", "\"1/0\"", "\"0/0\"", "\"log(0)\"", "\"exp(1000)\"",
        "\"2^(2^40)\"", "\"mu^(10^6)\"", "\"" + std::string(40, '(') + "1/3" + std::string(40, ')') + "\"",
        "\"sin(1)^2+cos(1)^2-1\"", "\"0^0\"", "\"tan(Pi/2)\"", "\"foo(2)\"", "\"1e999\"", "1e-999"};
    for (const std::string& mu : values)
        expect_refusal(run_on(floor_particle(mu), "solve --json"), "friction " + mu, "contact.friction");
    // A number token beyond double is refused by the JSON reader, which names the last key only.
    expect_refusal(run_on(floor_particle("1e999"), "solve --json"), "friction 1e999", "friction: a number out of the range of double");
    // A symbol: formulas answers, solve needs numbers.
    expect_refusal(run_on(floor_particle("\"mu\""), "solve --json"), "friction mu", "needs numbers");
    EXPECT_EQ(run_on(floor_particle("\"mu\""), "formulas --format json").code, 0);
}

TEST(Friction, ZeroFrictionHoweverWrittenIsTheSmoothAnswer)
{
    const run_result smooth = run_on(floor_particle("0"), "solve --json");
    ASSERT_EQ(smooth.code, 0) << smooth.err;
    for (const std::string mu : {"-0", "0.0", "0e5", "\"0\"", "\"Pi - Pi\"", "\"sqrt(2) - 2^(1/2)\"", "\"(sqrt(2)+1)*(sqrt(2)-1)-1\""}) {
        const run_result r = run_on(floor_particle(mu), "solve --json");
        ASSERT_EQ(r.code, 0) << mu << ": " << r.err;
        EXPECT_EQ(r.out, smooth.out) << mu;
        const json a = json::parse(r.out);
        EXPECT_EQ(a.at("regime"), "smooth") << mu;
        EXPECT_EQ(a.at("tangential_impulse"), json::parse("[0.0, 0.0]")) << mu;
    }
    // Every answer carries the two keys; mu = 0 is smooth for the smooth-only commands too.
    EXPECT_EQ(run_on(floor_particle("\"0*mu\"", "\"v\""), "formulas --jacobian --format json").code, 0);
    EXPECT_EQ(run_on(floor_particle("\"mu - mu\"", "\"v\""), "codegen").code, 0);
}

TEST(Friction, FrictionKeyElsewhereIsIgnoredWithAWarning)
{
    std::string text = floor_particle("0");
    text.replace(text.find("\"friction\": 0"), 13, "\"mu\": 0.3");
    text.replace(text.find("\"restitution\""), 0, "\"friction\": 0.3, ");
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out).at("regime"), "smooth");
    EXPECT_NE(r.err.find("warning: "), std::string::npos);
    EXPECT_NE(r.err.find("friction: unknown key"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("contact.mu: unknown key"), std::string::npos) << r.err;
}

TEST(Friction, StickingThresholdIsExact)
{
    // mu* = |vx| / (3/2) = 2 for vx = 3: mu = mu* sticks (the cone includes its boundary).
    struct want {
        std::string mu, regime;
        double vx_after, F;
    };
    for (const want& w : std::vector<want>{{"2", "stick", 0, -3},
                                          {"\"2 - 10^(-40)\"", "slide", 1.5e-40, -3},
                                          {"\"2 + 10^(-40)\"", "stick", 0, -3},
                                          {"\"10^300\"", "stick", 0, -3},
                                          {"1e300", "stick", 0, -3},
                                          {"123456789012345678901234567890", "stick", 0, -3},
                                          {"\"1/5\"", "slide", 2.7, -0.3},
                                          {"1e-300", "slide", 3, -1.5e-300},
                                          {"\"10^(-300)\"", "slide", 3, -1.5e-300}}) {
        const run_result r = run_on(floor_particle(w.mu), "solve --json");
        ASSERT_EQ(r.code, 0) << w.mu << ": " << r.err;
        const json a = json::parse(r.out);
        EXPECT_EQ(a.at("regime"), w.regime) << w.mu;
        // Exact values rounded once to double: a few ulps.
        EXPECT_NEAR(number_at(a, {"normal_impulse"}), 1.5, 1e-15) << w.mu;
        EXPECT_NEAR(number_at(a, {"tangential_impulse"}, 0), w.F, 1e-15 * std::fabs(w.F)) << w.mu;
        EXPECT_NEAR(number_at(a, {"bodies", "p", "velocity"}, 0), w.vx_after, 1e-15 * std::max(1.0, w.vx_after)) << w.mu;
        EXPECT_NEAR(number_at(a, {"bodies", "p", "velocity"}, 1), 0.5, 1e-15) << w.mu;
    }
    // u_t = 0: sticks with no friction impulse.
    const run_result r = run_on(floor_particle("0.5", "0"), "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out).at("regime"), "stick");
    EXPECT_EQ(json::parse(r.out).at("tangential_impulse"), json::parse("[0.0, 0.0]"));
}

TEST(Friction, ThresholdsOfTheExamplesFromFormulasAreExact)
{
    // formulas prints mu* for a symbolic mu; solve sticks at mu*, slides 10^-30 below, sticks 10^-30 above.
    for (const char* name : {"ball-backspin", "rod-slips", "sphere-wall-3d"}) {
        std::ifstream in(std::string(IMPACTGEN_SOURCE_DIR "/examples/friction/") + name + ".json");
        json p = json::parse(in);
        p["contact"]["friction"] = "mu";
        const run_result f = run_on(p.dump(), "formulas --format json", "f");
        ASSERT_EQ(f.code, 0) << name << ": " << f.err;
        const std::string t = json::parse(f.out).at("stick_threshold").get<std::string>();
        for (const auto& [mu, regime] : std::vector<std::pair<std::string, std::string>>{
                 {t, "stick"}, {"(" + t + ")*(1 - 10^(-30))", "slide"}, {"(" + t + ")*(1 + 10^(-30))", "stick"}}) {
            p["contact"]["friction"] = mu;
            const run_result r = run_on(p.dump(), "solve --json", "s");
            ASSERT_EQ(r.code, 0) << name << ", mu = " << mu << ": " << r.err;
            EXPECT_EQ(json::parse(r.out).at("regime"), regime) << name << ", mu = " << mu;
        }
    }
}

TEST(Friction, GrazingImpactSlides)
{
    // A ball (I = 2/5, R = 1) skimming the floor at u_n = -10^-300, u_t = 3: N = 3/2 10^-300, F = -mu N.
    for (const char* vy : {"\"-10^(-300)\"", "-1e-300"}) {
        const std::string text = R"({"dimension": 2, "restitution": 0.5, "bodies": [
            {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
            {"name": "ball", "mass": 1, "inertia": "2/5", "position": [0, 1], "velocity": [3, )" + std::string(vy) + R"(]}],
          "contact": {"bodies": ["floor", "ball"], "point": [0, 0], "normal": [0, 1], "friction": 0.3}})";
        const run_result r = run_on(text, "solve --json");
        ASSERT_EQ(r.code, 0) << vy << ": " << r.err;
        const json a = json::parse(r.out);
        EXPECT_EQ(a.at("regime"), "slide") << vy;
        EXPECT_NEAR(number_at(a, {"normal_impulse"}), 1.5e-300, 1e-315) << vy;
        EXPECT_NEAR(number_at(a, {"tangential_impulse"}, 0), -4.5e-301, 1e-315) << vy;
        // w' = (O - C) x (F e_x) / I = (0, -1) x (F, 0) / (2/5) = F / (2/5)
        EXPECT_NEAR(number_at(a, {"bodies", "ball", "angular_velocity"}), -4.5e-301 / 0.4, 1e-315) << vy;
    }
}

TEST(Friction, HingedRodStruckByABallSticksAsByHand)
{
    // Rod (m 2, I_C 1/6, C (0, -1/2)) hinged at E = 0, struck at O = (1, -1) by a particle (m 1/2, v (5, 1)),
    // n = (1, 0), e = 0.6, mu = 0.4. Stick: the ball leaves with the contact point of the rod
    // (w' (1, 1) for w' about E) in its tangent and 3 along n: v' = (w' - 3, w'), and
    // I_E w' = rho x P with P = -m (v' - v), I_E = 1/6 + 2/4 = 2/3, rho = (1, -1):
    // w' = 2.7, v' = (-0.3, 2.7), P = (2.65, -0.85) (|F|/N = 0.32 < 0.4), R = m_rod v'_C - P = (0.05, 0.85).
    const std::string text = R"({"dimension": 2, "restitution": 0.6, "bodies": [
        {"name": "ball", "mass": 0.5, "position": [1, -1], "velocity": [5, 1]},
        {"name": "rod", "mass": 2, "inertia": "1/6", "position": [0, -0.5], "velocity": [0, 0]}],
      "contact": {"bodies": ["ball", "rod"], "point": [1, -1], "normal": [1, 0], "friction": 0.4},
      "pivots": [{"body": "rod", "point": [0, 0]}]})";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "stick");
    const double tol = 1e-14;
    EXPECT_NEAR(number_at(a, {"bodies", "ball", "velocity"}, 0), -0.3, tol);
    EXPECT_NEAR(number_at(a, {"bodies", "ball", "velocity"}, 1), 2.7, tol);
    EXPECT_NEAR(number_at(a, {"bodies", "rod", "angular_velocity"}), 2.7, tol);
    EXPECT_NEAR(number_at(a, {"normal_impulse"}), 2.65, tol);
    EXPECT_NEAR(number_at(a, {"tangential_impulse"}, 1), -0.85, tol);
    EXPECT_NEAR(a.at("pivot_impulses").at(0).at(0).get<double>(), 0.05, tol);
    EXPECT_NEAR(a.at("pivot_impulses").at(0).at(1).get<double>(), 0.85, tol);
}

TEST(Friction, ObliqueNormalsWrittenAnyWayGiveOneAnswer)
{
    // A ball (m 1, I 2/5, R 1) on a plane with normal (1, 1, 1)/sqrt(3), written three ways.
    // Independent solution (sympy): u_n = -5 sqrt(3)/6, stick N = 5 sqrt(3)/4 with mu* = 0.342096545021106;
    // mu = 0.2 slides along u_t (the isotropic case) with the same N.
    const double N = 5 * std::sqrt(3.0) / 4;
    for (const char* normal : {"[1, 1, 1]", R"J(["1/sqrt(3)", "1/sqrt(3)", "1/sqrt(3)"])J", R"J(["sqrt(3)", "sqrt(3)", "sqrt(3)"])J"})
        for (const char* mu : {"0.2", "1"}) {
            const std::string text = R"J({"dimension": 3, "restitution": 0.5, "bodies": [
                {"name": "plane", "mass": "inf", "position": [-1, -1, -1], "velocity": [0, 0, 0]},
                {"name": "ball", "mass": 1, "inertia": ["2/5", "2/5", "2/5"], "position": ["1/sqrt(3)", "1/sqrt(3)", "1/sqrt(3)"],
                 "velocity": [-2, -1, 0.5], "angular_velocity": [0, 1, 0]}],
              "contact": {"bodies": ["plane", "ball"], "point": [0, 0, 0], "normal": )J" + std::string(normal) +
                                     R"(, "friction": )" + mu + "}}";
            const run_result r = run_on(text, "solve --json");
            ASSERT_EQ(r.code, 0) << normal << ", mu " << mu << ": " << r.err;
            const json a = json::parse(r.out);
            EXPECT_NEAR(number_at(a, {"normal_impulse"}), N, 1e-14) << normal;
            if (std::string(mu) == "0.2") {
                EXPECT_EQ(a.at("regime"), "slide") << normal;
                const double F[3] = {0.29131574717953074, 0.0278395372955957, -0.3191552844751264};
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(number_at(a, {"tangential_impulse"}, c), F[c], 1e-14) << normal << " component " << c;
            } else {
                EXPECT_EQ(a.at("regime"), "stick") << normal;
            }
        }
}

TEST(Friction, PiecewiseMapHasAJacobianPerRegimeAndOtherCommandsAnswerOrRefuse)
{
    const std::string text = floor_particle("0.3", "\"v\"");
    // The map is piecewise: its Jacobian is given per regime (stick, the two slides).
    const run_result jr = run_on(text, "formulas --jacobian --format json");
    ASSERT_EQ(jr.code, 0) << jr.err;
    const json jj = json::parse(jr.out);
    ASSERT_TRUE(jj.contains("regimes")) << jr.out;
    ASSERT_EQ(jj.at("regimes").size(), 3u) << jr.out;
    EXPECT_EQ(jj.at("regimes").at(0).at("regime"), "stick");
    const run_result f = run_on(text, "formulas --format json");
    ASSERT_EQ(f.code, 0) << f.err;
    const json j = json::parse(f.out);
    for (const char* key : {"friction", "normal", "regimes", "stick_threshold"})
        EXPECT_TRUE(j.contains(key)) << key;
    ASSERT_EQ(j.at("regimes").size(), 3u); // stick, slide along +e_t, slide along -e_t
    EXPECT_EQ(j.at("regimes").at(0).at("regime"), "stick");
    // codegen and explain either answer or refuse in one line (friction is being added to them).
    for (const char* cmd : {"codegen", "explain", "explain --format markdown"}) {
        const run_result r = run_on(text, cmd);
        EXPECT_TRUE(r.code == 0 || (r.code == 1 && std::count(r.err.begin(), r.err.end(), '\n') == 1)) << cmd << ": " << r.err;
    }
}

// ---- Findings still open (reported to the lead): enable each when it is fixed. ----
// Run them with --gtest_also_run_disabled_tests --gtest_filter='Friction.DISABLED_*'.

// A tiny mu (10^-200) with one irrational value in the problem was refused with "whether
// lambda = u'_t.d > 0 ... holds is out of the range of double" (lambda is about 3): decide()
// refuses values below 10^-308.25 as out of range, and some term of a condition reaches it.
// The same problem with mu = 10^-170, or with C = (3/2, 1), slides.
TEST(Friction, TinyMuWithAnIrrationalValueSlides)
{
    const std::string text = R"J({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
        {"name": "B", "mass": 1, "inertia": 1, "position": ["sqrt(2)", 1], "velocity": [1, -1]}],
      "contact": {"bodies": ["floor", "B"], "point": [0, 0], "normal": [0, 1], "friction": "10^(-200)"}})J";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "slide");
    // K_nn = 1 + 2 / 1 = 3: N = (1 + e) / 3 = 1/2, F = -mu N.
    EXPECT_NEAR(number_at(a, {"normal_impulse"}), 0.5, 1e-15);
    EXPECT_NEAR(number_at(a, {"tangential_impulse"}, 0), -5e-201, 1e-215);
}

// A 3-D impact of a particle on a body with a ball joint, one value exp(1)/2 and two
// decimals 0.277, 0.909: refused with "whether mu^2 N^2 - |F|^2 >= 0 ... holds is out of the
// range of double", though N = 31.73, |F| = 22.41 (mu* = 0.706 < mu = 1: it sticks;
// independent solution with sympy). Changing 0.277 to 0.3 gives the stick answer.
TEST(Friction, ConeConditionOfModerateSizeIsDecided)
{
    const std::string text = R"({"dimension": 3, "restitution": "2/3", "bodies": [
        {"name": "puck", "mass": 9, "position": [-1, -1.2, -1], "velocity": [4, -1, -4.5], "angular_velocity": [1, 1, 2]},
        {"name": "cue", "mass": 2, "inertia": [[12.25, -2, -2], [-2, 9.25, -7], [-2, -7, 9.25]], "position": [-0.3, 0.277, "exp(1)/2"],
         "velocity": [0, 0, 0]}],
      "contact": {"bodies": ["puck", "cue"], "point": [0.5, 0.6, 1], "normal": [1, 0, 0], "friction": 1},
      "pivots": [{"body": "cue", "point": [0.909, 1.75, 1.3]}]})";
    // The answer is tested here, not the speed: 4-5 s in a release build on 2 shared cores,
    // 5-10 times that under ASan + UBSan, over the default budget of 10 s.
    const run_result r = run_on(text, "--time-limit 120 solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "stick");
    EXPECT_NEAR(number_at(a, {"normal_impulse"}), 31.7338743693712, 1e-9);
}

// The stick impulse of this rod has N = -33/100 < 0, so no mu sticks; formulas printed
// "mu >= mu* = |F| / N = 256/33" as the condition for sticking, and the README says sticking
// holds exactly when mu >= mu*: solve (rightly) slides at mu = 10 > 256/33.
TEST(Friction, StickingThresholdIsOnlyPrintedWhenTheStickImpulsePushes)
{
    const std::string rod = R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
        {"name": "rod", "mass": 1, "inertia": "1/12", "position": [0.3, 0.4], "velocity": [7, -2], "angular_velocity": 0}],
      "contact": {"bodies": ["floor", "rod"], "point": [0, 0], "normal": [0, 1], "friction": MU}})";
    auto with_mu = [&](const std::string& mu) {
        std::string t = rod;
        return t.replace(t.find("MU"), 2, mu);
    };
    const run_result f = run_on(with_mu("\"mu\""), "formulas --format json", "f");
    ASSERT_EQ(f.code, 0) << f.err;
    const json t = json::parse(f.out).at("stick_threshold");
    // Either no threshold is claimed, or every mu at or above it sticks.
    const GiNaC::ex value = t.is_string() ? parse_value(t.get<std::string>(), true, "mu*").evalf() : GiNaC::ex(GiNaC::symbol("none"));
    if (GiNaC::is_a<GiNaC::numeric>(value)) {
        const double mu_star = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
        for (double factor : {1.0, 2.0, 10.0}) {
            std::ostringstream mu;
            mu << "\"(" << t.get<std::string>() << ")*" << factor << "\"";
            const run_result r = run_on(with_mu(mu.str()), "solve --json", "s");
            ASSERT_EQ(r.code, 0) << r.err;
            EXPECT_EQ(json::parse(r.out).at("regime"), "stick") << "mu = " << factor << " mu* = " << factor * mu_star;
        }
    }
    const run_result text = run_on(with_mu("\"mu\""), "formulas", "t");
    EXPECT_EQ(text.out.find("mu >= mu* = |F| / N = 256/33"), std::string::npos) << text.out;
}

// A rod hinged at its centre, struck by a moving wall (infinite mass) with friction, was
// refused ("the contact response K is singular ... the tangential impulse is not
// determined"), though the law has exactly one solution: the contact point can only move
// along (-1/2, 1), so restitution fixes w' = 3 and u'_t = -3; sticking is impossible and
// the slide along -e_t holds (D_s = 6/5 > 0, lambda = 3 > 0), the other slide does not
// (lambda = -3): N = 5/4, F = (0, 3/8) on the wall, the pivot impulse R = P = (5/4, 3/8).
TEST(Friction, PinnedBodyStruckByAnImmovableOneSlides)
{
    const std::string text = R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "wall", "mass": "inf", "position": [2, 0], "velocity": [-1, 0]},
        {"name": "rod", "mass": 1, "inertia": "1/12", "position": [0, 0], "velocity": [0, 0]}],
      "contact": {"bodies": ["rod", "wall"], "point": [1, 0.5], "normal": [1, 0], "friction": 0.3},
      "pivots": [{"body": "rod", "point": [0, 0]}]})";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "slide");
    EXPECT_NEAR(number_at(a, {"normal_impulse"}), 1.25, 1e-15);
    EXPECT_NEAR(number_at(a, {"tangential_impulse"}, 1), 0.375, 1e-15);
    EXPECT_NEAR(number_at(a, {"bodies", "rod", "angular_velocity"}), 3, 1e-15);
    EXPECT_NEAR(a.at("pivot_impulses").at(0).at(0).get<double>(), 1.25, 1e-15); // R = P on the rod side
    // formulas: the two slides are the candidates (no stick); explain teaches it.
    const run_result f = run_on(text, "formulas --format json", "f");
    ASSERT_EQ(f.code, 0) << f.err;
    const json j = json::parse(f.out);
    ASSERT_EQ(j.at("regimes").size(), 2u);
    for (const auto &r : j.at("regimes"))
        EXPECT_EQ(r.at("regime"), "slide");
    const run_result x = run_on(text, "explain", "x");
    ASSERT_EQ(x.code, 0) << x.err;
    EXPECT_NE(x.out.find("Sticking is impossible"), std::string::npos);
}

// mu = 10^308 on the rod above: a slide with N = 3 / (52/25 + 36/25 10^308) = 2.083e-308
// (a subnormal double) and |F| = mu N = 2.083; the answer printed "normal_impulse": 0.0
// next to F = -2.083, so the printed answer breaks the cone |F| <= mu N. Values below
// 2.2e-308 are printed as 0 (velocity 1e-310 too).
TEST(Friction, SubnormalValuesAreNotPrintedAsZero)
{
    const std::string text = R"({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "floor", "mass": "inf", "position": [0, -1], "velocity": [0, 0]},
        {"name": "rod", "mass": 1, "inertia": "1/12", "position": [0.3, 0.4], "velocity": [7, -2], "angular_velocity": 0}],
      "contact": {"bodies": ["floor", "rod"], "point": [0, 0], "normal": [0, 1], "friction": 1e308}})";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "slide");
    const double N = number_at(a, {"normal_impulse"}), F = number_at(a, {"tangential_impulse"}, 0);
    EXPECT_GT(N, 2.08e-308);
    EXPECT_LE(std::fabs(F), 1e308 * N * (1 + 1e-9));
}

// A 3-D slide without a closed form (the sliding angle a root found at 50 digits) with a huge
// mu: up to mu = 10^20 F is antiparallel to u'_t to 16 digits; from mu = 10^40 on, solve
// answers with F/|F| = (-0.90398929, -0.42755509, 0) (the same direction for another problem
// of the fuzzer) while -u'_t/|u'_t| = (-0.90436325, -0.42676353, 0): Coulomb's law is broken
// by 0.9 mrad. (Found by the friction fuzzer, IMPACTGEN_DEEP=1 IMPACTGEN_SEED=7.)
TEST(Friction, HugeMuGeneralSlideKeepsFAntiparallelToTheSlip)
{
    const std::string text = R"({"dimension": 3, "restitution": 0, "bodies": [
        {"name": "rod", "mass": 0.7, "inertia": [[6.5, -2, -4], [-2, 2.5, 4], [-4, 4, 8.5]], "position": [-1.8, -1, -0.5],
         "velocity": [-5, -3.3, -3.8], "angular_velocity": [2.4, -2, 2.8]},
        {"name": "B", "mass": 7.8, "inertia": [0.7, 2, 3], "position": [0, -1, -1.7], "velocity": [0, 0, 0]}],
      "contact": {"bodies": ["rod", "B"], "point": [-1, 0, 1], "normal": [0, 0, 1], "friction": 1e40},
      "pivots": [{"body": "B", "point": [-1.6, -1.6, -0.3]}]})";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    EXPECT_EQ(a.at("regime"), "slide");
    // u' = v'_B + w'_B x (O - C_B) - v'_rod - w'_rod x (O - C_rod); n = z, so u'_t is its x, y part.
    auto contact_velocity = [&](const char* name, const double c[3]) {
        const json& b = a.at("bodies").at(name);
        double v[3], w[3], rr[3] = {-1 - c[0], 0 - c[1], 1 - c[2]};
        for (int k = 0; k < 3; ++k) {
            v[k] = b.at("velocity").at(k).get<double>();
            w[k] = b.at("angular_velocity").at(k).get<double>();
        }
        return std::array<double, 3>{v[0] + w[1] * rr[2] - w[2] * rr[1], v[1] + w[2] * rr[0] - w[0] * rr[2], v[2] + w[0] * rr[1] - w[1] * rr[0]};
    };
    const double c_rod[3] = {-1.8, -1, -0.5}, c_b[3] = {0, -1, -1.7};
    const auto vb = contact_velocity("B", c_b), va = contact_velocity("rod", c_rod);
    const double ux = vb[0] - va[0], uy = vb[1] - va[1], slip = std::hypot(ux, uy);
    const double fx = number_at(a, {"tangential_impulse"}, 0), fy = number_at(a, {"tangential_impulse"}, 1), f = std::hypot(fx, fy);
    ASSERT_GT(slip, 1);
    // F/|F| = -u'_t/|u'_t|: both from doubles of size 1..10, a few ulps each.
    EXPECT_NEAR(fx / f, -ux / slip, 1e-12);
    EXPECT_NEAR(fy / f, -uy / slip, 1e-12);
}

// codegen of a numeric 3-D problem with friction and a full (non-diagonal) inertia tensor was
// refused with an internal message that names no file or key: "impactgen: error: codegen
// friction: no inverse inertia step" (examples/friction/box-corner-3d.json, the README's own
// example; with a diagonal tensor the header is written). Found by the friction fuzzer.
TEST(Friction, CodegenWritesAHeaderForAFullInertiaTensor)
{
    const run_result r = run_cli("codegen " IMPACTGEN_SOURCE_DIR "/examples/friction/box-corner-3d.json");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("friction_status"), std::string::npos);
    EXPECT_EQ(r.err.find("inverse inertia step"), std::string::npos) << r.err;
}

// A decimal with two points in an expression string was read as another number: "0.3.1"
// as 0.31, "1.2.3" as 1.23, "0..3" as 0.3, "3.." as 3 (friction, mass, any value), where
// "0.3e" is refused; and "1e2e3" was refused naming the reader's internal symbol
// ("symbol \"impactgen_number_0e3\" not found").
TEST(Friction, MalformedDecimalsAreRefused)
{
    for (const std::string mu : {"\"0.3.1\"", "\"1.2.3\"", "\"0..3\"", "\"3..\"", "\"1e2e3\""}) {
        const run_result r = run_on(floor_particle(mu), "solve --json");
        expect_refusal(r, "friction " + mu, "contact.friction");
        EXPECT_EQ(r.err.find("impactgen_number_"), std::string::npos) << r.err;
    }
}

} // namespace

// Values whose exact form cancels in its leading digits (a root of 10^40 + 1 minus 10^20) are
// evaluated to double precision, not at GiNaC's default 17 digits: e = sqrt(10^40 + 1) - 10^20
// is 5e-21, so a mass of 2 at -1 striking a mass of 1 at rest leaves both at -2/3 (the text
// printed -4 and 0, and --json refused a value as "below the range of double").
TEST(Cli, CancellingRootsGiveRightDecimals)
{
    const std::string text = R"J({"dimension": 2, "restitution": "sqrt(10^40+1)-10^20", "bodies": [
        {"name": "a", "mass": 1, "position": [0, 0], "velocity": ["10^8 - sqrt(10^16+1)", 0]},
        {"name": "b", "mass": 2, "position": [1, 0], "velocity": [-1, 0]}],
      "contact": {"bodies": ["a", "b"], "point": [0.5, 0], "normal": [1, 0]}})J";
    const run_result r = run_on(text, "solve --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    // m_a v_a + m_b v_b = -2 - 5e-9 shared at a common velocity (e ~ 5e-21): -(2 + 5e-9)/3
    // (1e-15: the answer is -(2 + 5e-9)/3 to 1e-20, e moves it by 5e-21; double rounding 1e-16)
    const double common = -(2 + 5e-9) / 3;
    EXPECT_NEAR(number_at(a, {"bodies", "a", "velocity"}, 0), common, 1e-15);
    EXPECT_NEAR(number_at(a, {"bodies", "b", "velocity"}, 0), common, 1e-15);
    const run_result t = run_on(text, "solve", "_text");
    ASSERT_EQ(t.code, 0) << t.err;
    EXPECT_NE(t.out.find("= -0.666666668333333"), std::string::npos) << t.out;
    // explain's decimals the same (its notes had the old 17-digit evaluation)
    const run_result x = run_on(text, "explain", "_explain");
    ASSERT_EQ(x.code, 0) << x.err;
    EXPECT_NE(x.out.find("≈ -0.666667"), std::string::npos);
    // Deeper: 10^50 - sqrt(10^100 + 1) is a float 0 at 40 and 80 digits (no evidence of 0:
    // it printed 1.01e31, then 0), and a normal with it divided by a float 0 inside GiNaC.
    const std::string deep = R"J({"dimension": 2, "restitution": 0.5, "bodies": [
        {"name": "a", "mass": 1, "position": [0, 0], "velocity": [1, 0]},
        {"name": "b", "mass": 2, "position": [1, 0], "velocity": ["10^50 - sqrt(10^100+1)", 0]}],
      "contact": {"bodies": ["a", "b"], "point": [0.5, 0], "normal": [1, "sqrt(10^100+1)-10^50"]}})J";
    for (const char* cmd : {"solve", "solve --json", "explain", "explain --format latex"}) {
        const run_result d = run_on(deep, cmd, std::string("_deep") + std::to_string(std::strlen(cmd)));
        EXPECT_EQ(d.code, 0) << cmd << ": " << d.err;
    }
    EXPECT_NE(run_on(deep, "solve", "_deep_text").out.find("= -5e-51"), std::string::npos);
}

// A system (format version 3) is answered by solve (the answer's keys of the format) and
// refused, with one line, by explain, codegen and formulas --jacobian for now.
TEST(Cli, SystemsAnsweredBySolveExplainAndCodegen)
{
    const std::string file = std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/compass-gait.json";
    run_result r = run_cli("solve --json " + file);
    ASSERT_EQ(r.code, 0) << r.err;
    const json a = json::parse(r.out);
    for (const char* key : {"bodies", "contacts", "joint_impulses", "pivot_impulses", "kinetic_energy", "impulses_unique"})
        EXPECT_TRUE(a.contains(key)) << key;
    EXPECT_EQ(a["contacts"][1]["regime"], "open");
    EXPECT_FALSE(a.contains("sequence"));
    r = run_cli("explain " + file);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("The law holds for {0 stick, 1 open}."), std::string::npos);
    r = run_cli("explain --level summary " + file); // one page: set-up, figure, boxed results
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("Which contacts act: contact 0 pushes and sticks; contact 1 leaves"), std::string::npos);
    r = run_cli("codegen " + file);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("compass_gait_set_names[]"), std::string::npos);
    r = run_cli("formulas --jacobian " + file); // numbers: nothing to differentiate by
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--wrt: the problem has no symbols"), std::string::npos) << r.err;
    const std::string sequential = std::string(IMPACTGEN_SOURCE_DIR) + "/examples/systems/three-balls-sequential.json";
    r = run_cli("solve --json " + sequential);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out)["sequence"], json::array({0, 1}));
    r = run_cli("codegen " + sequential); // the chain in a bounded loop
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("three_balls_sequential_max_steps = 64"), std::string::npos);
    r = run_cli("codegen --jacobian " + sequential); // no Jacobian of a chain: refused naming the option
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--jacobian"), std::string::npos) << r.err;
}
