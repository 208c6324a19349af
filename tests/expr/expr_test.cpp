// The one canonical expression layer (expr/): the tree's sharing, order and signs, the printer
// over it, and code generation reading the same tree.
#include "codegen/canonical.hpp"
#include "codegen/form_text.hpp"
#include "codegen/program.hpp"
#include "expr/print.hpp"
#include "expr/roles.hpp"
#include "expr/tree.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace GiNaC;
using namespace impactgen;

namespace
{

std::string text(const ex &e)
{
    const expr::shared_tree shared;
    return expr::print(shared.get(), shared.get().of(e), expr::syntax::text).s;
}

} // namespace

TEST(ExprTree, OneNodePerExpressionSharedByEveryParent)
{
    const symbol a("a"), b("b"), c("c"), d("d");
    expr::tree t;
    const int ab = t.of(a + b);
    EXPECT_EQ(t.of(b + a), ab);
    const int x = t.of((a + b) * c), y = t.of(pow(a + b, 2) / d);
    const auto &fx = t.product(x), &fy = t.product(y);
    ASSERT_EQ(fx.numerator.size(), 2u);
    ASSERT_EQ(fy.numerator.size(), 1u);
    EXPECT_EQ(fy.numerator[0].base, ab);
    EXPECT_TRUE(fx.numerator[0].base == ab || fx.numerator[1].base == ab);
    EXPECT_EQ(t.at(ab).k, expr::kind::sum);
    EXPECT_EQ(t.at(x).k, expr::kind::product);
}

TEST(ExprTree, OperandsInTheOrderOfTheirTextWhateverGinacsOrder)
{
    // Symbols made in the opposite order of their names: GiNaC orders them by creation.
    const symbol z("z"), y("y"), a("a");
    EXPECT_EQ(text(z + a + y), "a + y + z");
    EXPECT_EQ(text(z * a * y), "a·y·z");
    expr::tree t;
    const int s = t.of(z - a + y);
    ASSERT_EQ(t.at(s).terms.size(), 3u);
    // positive terms first, each group in order of its key
    EXPECT_EQ(t.at(s).terms[0].key, "y");
    EXPECT_EQ(t.at(s).terms[1].key, "z");
    EXPECT_EQ(t.at(s).terms[2].key, "a");
    EXPECT_TRUE(t.at(s).terms[2].negative);
}

TEST(ExprTree, TheSignOfASumMovesToTheCoefficient)
{
    const symbol a("a"), b("b"), c("c"), d("d");
    expr::tree t;
    const int n = t.of(1 / (b - a));
    const auto &f = t.product(n);
    EXPECT_EQ(f.coefficient, -1);
    ASSERT_EQ(f.denominator.size(), 1u);
    EXPECT_EQ(f.denominator[0].key, "a - b");
    EXPECT_EQ(text((a - b) / (c - d)), text((b - a) / (d - c)));
    EXPECT_EQ(text(1 / (b - a)), "-1/(a - b)");
}

TEST(ExprPrint, FourSyntaxesOfOneTree)
{
    const symbol a("a"), b("b");
    const symbol w = expr::symbol_with_role("w_z1", "", expr::symbol_role::angular_velocity);
    const ex e = sqrt(a) / (2 * pow(b, 2)) + w;
    const expr::shared_tree shared;
    expr::tree &t = shared.get();
    const int id = t.of(e);
    EXPECT_EQ(expr::print(t, id, expr::syntax::text).s, "ω_z1 + √a/(2·b²)");
    EXPECT_EQ(expr::print(t, id, expr::syntax::parser).s, "w_z1 + sqrt(a)/(2*b^2)");
    EXPECT_EQ(expr::print(t, id, expr::syntax::latex).s, "w_{z1} + \\frac{\\sqrt{a}}{2 b^{2}}");
    // The text form is the tree's order key, kept in the node.
    ASSERT_TRUE(t.at(id).text.has_value());
    EXPECT_EQ(t.at(id).text->s, "ω_z1 + √a/(2·b²)");
    // abs(x) as bars when asked (the documents), by name otherwise.
    const int m = t.of(abs(a - b));
    EXPECT_EQ(expr::print(t, m, expr::syntax::text).s, "abs(a - b)");
    EXPECT_EQ(expr::print(t, m, expr::syntax::text, nullptr, true).s, "|a - b|");
    EXPECT_EQ(expr::print(t, m, expr::syntax::latex, nullptr, true).s, "\\left|a - b\\right|");
}

TEST(ExprPrint, WhatNoSyntaxPrintsIsAnErrorNotATreeFailure)
{
    const symbol a("a");
    expr::tree t;
    const int id = t.of(a + I);
    EXPECT_THROW(expr::print(t, id, expr::syntax::text), std::invalid_argument);
    EXPECT_THROW(expr::print(t, t.of(2.5 * a), expr::syntax::parser), std::invalid_argument);
}

// ω comes from the role the model gave a symbol, never from its name: two symbols named alike
// print alike unless one of them is an angular velocity.
TEST(ExprPrint, OmegaOnlyForASymbolWhoseRoleIsAnAngularVelocity)
{
    const symbol user("w_t1"), weight("weight"), w("w"), primed("w'_z1");
    const symbol spin = expr::symbol_with_role("w_t1", "\\omega_{t1}", expr::symbol_role::angular_velocity);
    const symbol spin_after = expr::symbol_with_role("w'_z1", "\\omega'_{z1}", expr::symbol_role::angular_velocity);
    EXPECT_EQ(text(user), "w_t1");
    EXPECT_EQ(text(weight), "weight");
    EXPECT_EQ(text(w), "w");
    EXPECT_EQ(text(primed), "w′_z1");
    EXPECT_EQ(text(spin), "ω_t1");
    EXPECT_EQ(text(spin_after), "ω′_z1");
    EXPECT_EQ(expr::role_of(user), expr::symbol_role::none);
    EXPECT_EQ(expr::role_of(spin), expr::symbol_role::angular_velocity);
    // In a sum each keeps its own: the user's w_t1 beside the spin ω_t1.
    const std::string sum = text(user + 2 * spin);
    EXPECT_NE(sum.find("w_t1"), std::string::npos) << sum;
    EXPECT_NE(sum.find("2·ω_t1"), std::string::npos) << sum;
    // Copies of a symbol are the symbol: the role goes with them.
    const ex copy = spin;
    EXPECT_EQ(text(copy * copy), "ω_t1²");
}

TEST(ExprTree, NestedScopesKeepTheSharedNodes)
{
    const symbol a("a"), b("b");
    const expr::shared_tree outer;
    const int id = outer.get().of(a - b);
    {
        const expr::shared_tree inner;
        EXPECT_EQ(&inner.get(), &outer.get());
        EXPECT_EQ(inner.get().of(a - b), id);
    }
    EXPECT_EQ(outer.get().at(id).k, expr::kind::sum);
}

TEST(ExprCodegen, CodeGenerationReadsTheSameCanonicalForm)
{
    const symbol a("a"), b("b"), c("c"), d("d");
    codegen::canonical_pool pool;
    pool.set_input_names({{a, "a"}, {b, "b"}, {c, "c"}, {d, "d"}});
    const codegen::scaled x = pool.convert((a - b) / (c - d)), y = pool.convert((b - a) / (d - c));
    EXPECT_EQ(x.node, y.node);
    EXPECT_EQ(x.scale, y.scale);
    const codegen::scaled z = pool.convert((b - a) / (c - d));
    EXPECT_EQ(z.node, x.node);
    EXPECT_EQ(z.scale, -x.scale);
    // 2*Pi is valued whole; cos and sin of symbols are nodes of their own (a rod's angle), any
    // other function of symbols is refused.
    const codegen::scaled k = pool.convert(2 * Pi * a);
    ASSERT_GE(k.node, 0);
    EXPECT_EQ(pool.at(k.node).kind, codegen::cnode::input);
    EXPECT_NEAR(k.scale.to_double(), 6.283185307179586, 1e-15);
    const codegen::scaled s = pool.convert(sin(a));
    ASSERT_GE(s.node, 0);
    EXPECT_EQ(pool.at(s.node).kind, codegen::cnode::sin_);
    EXPECT_THROW(pool.convert(exp(a)), std::runtime_error);
    EXPECT_THROW(pool.convert(tan(a)), std::runtime_error);
}

// The emitter and the header writers put parentheses by the structure of what they combine (the
// precedence of its top operation), never by looking for a space in its text: a negation or a
// call whose text has spaces stays bare, a sum or a product is parenthesised.
TEST(ExprCodegen, ParenthesesComeFromTheStructureNotTheText)
{
    codegen::program prog;
    const int x = prog.input("x"), y = prog.input("y");
    const int sum = prog.binary(codegen::op::add, x, y);
    const int negated = prog.negate(sum);
    const int product = prog.binary(codegen::op::mul, x, y);
    auto energy = [&](int id) {
        codegen::emit_options o;
        o.energy_output = 0;
        return codegen::emit_cpp(prog, {{"energy_lost", id}}, {}, {}, {}, o).code;
    };
    EXPECT_NE(energy(negated).find("with_energy_lost ? -(x + y) : T(0)"), std::string::npos) << energy(negated);
    EXPECT_NE(energy(product).find("with_energy_lost ? (x * y) : T(0)"), std::string::npos) << energy(product);
    EXPECT_NE(energy(x).find("with_energy_lost ? x : T(0)"), std::string::npos) << energy(x);
    // Sums of names: each partial sum is a sum, parenthesised as an operand of the next.
    EXPECT_EQ(codegen::form_text::balanced_sum({"a", "b", "c"}), "(a + b) + c");
    EXPECT_EQ(codegen::form_text::balanced_sum({"a", "b", "c", "d"}), "(a + b) + (c + d)");
    // The finiteness sum of a branchless form: a call with spaces in its text is an atom.
    const std::string t =
        codegen::form_text::timed_sum({{"f(a + b)", 0, false, 4}, {"-(c + d)", 0, false, 3}, {"p * q", 0, false, 2}});
    EXPECT_EQ(t, "T((p * q) + (f(a + b) + -(c + d)))"); // the two earliest summed first
}
