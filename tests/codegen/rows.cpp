// codegen --rows: NAME_rows, the contact's rows for an iterative solver (codegen/writer_rows.cpp).
// On seeded random inputs: the rows' effective masses are 1/(d.K d) of the symbolic contact
// response K (symbolic/friction.hpp's steps, evaluated exactly), their couplings J_d M^-1 J_d'^T
// are d.K d', the directions are an orthonormal frame with the unit normal; and for a single
// contact one projected step along the normal is the closed form's impulse and velocities.
#include "rows_noncentral_3d.hpp"
#include "rows_planar.hpp"
#include "rows_planar_engine.hpp"
#include "rows_planar_friction.hpp"
#include "rows_tilted_box.hpp"

#include "symbolic/derivation.hpp"
#include "symbolic/friction.hpp"
#include "symbolic/named_classes.hpp"
#include "symbolic/problem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace
{

namespace gen = impactgen::generated;
using namespace GiNaC;

// The contact response K (world axes) of a problem with friction, in its input symbols.
struct symbolic_K {
    ex K[3][3];
    std::map<std::string, symbol> by_name;
};

symbolic_K response_of(const impactgen::problem &p)
{
    const impactgen::derivation d = impactgen::derive(p);
    const impactgen::friction_solution f = impactgen::solve_friction(d);
    symbolic_K r;
    lst earlier;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            r.K[a][b] = 0;
    for (const impactgen::step &st : f.shared.steps) {
        const ex v = st.value.subs(earlier);
        earlier.append(st.sym == v);
        if (st.role == impactgen::step_role::contact_response)
            r.K[st.row][st.column] = r.K[st.column][st.row] = v;
    }
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            exset syms;
            for (const_preorder_iterator it = r.K[a][b].preorder_begin(); it != r.K[a][b].preorder_end(); ++it)
                if (is_a<symbol>(*it))
                    r.by_name[ex_to<symbol>(*it).get_name()] = ex_to<symbol>(*it);
        }
    return r;
}

// A double as the exact rational it is.
ex exact(double v)
{
    int e2 = 0;
    const double fr = std::frexp(v, &e2);
    const long long mant = static_cast<long long>(std::ldexp(fr, 53));
    return numeric(mant) * pow(numeric(2), e2 - 53);
}

// d.K d' for the inputs (by name), evaluated exactly (the doubles as exact rationals).
double dKd(const symbolic_K &k, const std::map<std::string, double> &x, const double *d, const double *dd, int dim)
{
    lst values;
    for (const auto &[nm, s] : k.by_name)
        values.append(s == exact(x.at(nm)));
    ex sum = 0;
    const int axes[2] = {0, 1};
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            const int ra = dim == 2 ? axes[a] : a, rb = dim == 2 ? axes[b] : b;
            sum += exact(d[a]) * k.K[ra][rb].subs(values) * exact(dd[b]);
        }
    return ex_to<numeric>(evalf(sum)).to_double();
}

// J_d M^-1 J_d'^T from two rows.
template <typename Row, typename Rows> double coupling(const Rows &r, const Row &a, const Row &b, int dim)
{
    const int A = dim == 2 ? 1 : 3;
    double s = 0;
    for (int c = 0; c < dim; ++c)
        s += (r.inv_m1 + r.inv_m2) * a.dir[c] * b.dir[c];
    for (int i = 0; i < A; ++i)
        for (int j = 0; j < A; ++j)
            s += a.ang1[i] * r.inv_I1[A * i + j] * b.ang1[j] + a.ang2[i] * r.inv_I2[A * i + j] * b.ang2[j];
    return s;
}

double rel(double a, double b)
{
    return std::fabs(a - b) / std::max(1.0, std::fabs(b));
}

// Random inputs by name: masses and inertia in [0.5, 3] (diagonal-dominant tensors), positions
// and velocities in [-1, 1], a random normal, e in [0, 1], mu in [0, 1].
std::vector<double> draw(std::mt19937_64 &g, const char *const *names, int n)
{
    std::uniform_real_distribution<double> U(-1, 1), P(0.5, 3), E(0, 1);
    std::vector<double> x(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const std::string nm = names[i];
        double &v = x[static_cast<std::size_t>(i)];
        if (nm == "e" || nm == "mu")
            v = E(g);
        else if (nm.rfind("inv_", 0) == 0 || nm[0] == 'm' || nm[0] == 'I')
            v = P(g);
        else
            v = U(g);
        if (nm.size() == 5 && nm[0] == 'I' && nm[2] == '_' && nm[3] != nm[4])
            v = 0.2 * U(g); // an off-diagonal entry of a positive-definite tensor
        if (nm.size() == 7 && nm.rfind("I", 0) == 0 && nm[4] != nm[5])
            v = 0.2 * U(g);
    }
    return x;
}

std::map<std::string, double> by_name(const char *const *names, const std::vector<double> &x)
{
    std::map<std::string, double> m;
    for (std::size_t i = 0; i < x.size(); ++i)
        m[names[i]] = x[i];
    return m;
}

template <typename Rows> void expect_orthonormal(const Rows &r, int dim)
{
    auto dot = [&](const double *a, const double *b) {
        double s = 0;
        for (int c = 0; c < dim; ++c)
            s += a[c] * b[c];
        return s;
    };
    EXPECT_NEAR(dot(r.normal.dir, r.normal.dir), 1, 1e-14);
    for (int k = 0; k < dim - 1; ++k) {
        EXPECT_NEAR(dot(r.tangent[k].dir, r.tangent[k].dir), 1, 1e-14);
        EXPECT_NEAR(dot(r.tangent[k].dir, r.normal.dir), 0, 1e-14);
    }
    if (dim == 3) {
        EXPECT_NEAR(dot(r.tangent[0].dir, r.tangent[1].dir), 0, 1e-14);
    }
}

TEST(codegen_rows, effective_masses_are_those_of_the_symbolic_K_planar)
{
    const symbolic_K k = response_of(impactgen::find_named_class("planar-friction")->build());
    std::mt19937_64 g(24);
    for (int trial = 0; trial < 25; ++trial) {
        const std::vector<double> x =
            draw(g, gen::rows_planar_friction_input_names, gen::rows_planar_friction_input_count);
        gen::rows_planar_friction_rows_result<double> r;
        ASSERT_EQ(gen::rows_planar_friction_rows(x.data(), r), gen::impact_status::ok);
        expect_orthonormal(r, 2);
        const auto m = by_name(gen::rows_planar_friction_input_names, x);
        const double Knn = dKd(k, m, r.normal.dir, r.normal.dir, 2),
                     Ktt = dKd(k, m, r.tangent[0].dir, r.tangent[0].dir, 2);
        EXPECT_LE(rel(r.normal.effective_mass, 1 / Knn), 1e-13);
        EXPECT_LE(rel(r.tangent[0].effective_mass, 1 / Ktt), 1e-13);
        EXPECT_NEAR(coupling(r, r.normal, r.tangent[0], 2), dKd(k, m, r.normal.dir, r.tangent[0].dir, 2), 1e-13 * Knn);
        EXPECT_NEAR(coupling(r, r.normal, r.normal, 2), Knn, 1e-13 * Knn);
    }
}

TEST(codegen_rows, effective_masses_are_those_of_the_symbolic_K_3d_any_normal)
{
    const symbolic_K k = response_of(impactgen::load_problem_file(std::string(IMPACTGEN_SOURCE_DIR) +
                                                                  "/tests/codegen/friction/tilted-box-friction.json"));
    std::mt19937_64 g(2424);
    for (int trial = 0; trial < 25; ++trial) {
        std::vector<double> x = draw(g, gen::rows_tilted_box_input_names, gen::rows_tilted_box_input_count);
        auto m = by_name(gen::rows_tilted_box_input_names, x);
        // Every direction of the normal, the axes and their negatives included.
        if (trial < 6)
            for (int c = 0; c < 3; ++c) {
                const std::string nm = std::string("n") + "xyz"[c];
                const double v = c == trial % 3 ? (trial < 3 ? 1.0 : -1.0) : 0.0;
                x[static_cast<std::size_t>(
                    std::find_if(gen::rows_tilted_box_input_names,
                                 gen::rows_tilted_box_input_names + gen::rows_tilted_box_input_count,
                                 [&](const char *s) { return nm == s; }) -
                    gen::rows_tilted_box_input_names)] = v;
                m[nm] = v;
            }
        gen::rows_tilted_box_rows_result<double> r;
        ASSERT_EQ(gen::rows_tilted_box_rows(x.data(), r), gen::impact_status::ok);
        expect_orthonormal(r, 3);
        const double len = std::sqrt(m["nx"] * m["nx"] + m["ny"] * m["ny"] + m["nz"] * m["nz"]);
        EXPECT_NEAR(r.normal.dir[0], m["nx"] / len, 1e-15);
        EXPECT_NEAR(r.normal.dir[2], m["nz"] / len, 1e-15);
        const double Knn = dKd(k, m, r.normal.dir, r.normal.dir, 3);
        EXPECT_LE(rel(r.normal.effective_mass, 1 / Knn), 1e-13);
        for (int t = 0; t < 2; ++t) {
            EXPECT_LE(rel(r.tangent[t].effective_mass, 1 / dKd(k, m, r.tangent[t].dir, r.tangent[t].dir, 3)), 1e-13);
            EXPECT_NEAR(coupling(r, r.normal, r.tangent[t], 3), dKd(k, m, r.normal.dir, r.tangent[t].dir, 3),
                        1e-13 * Knn);
        }
        EXPECT_NEAR(coupling(r, r.tangent[0], r.tangent[1], 3), dKd(k, m, r.tangent[0].dir, r.tangent[1].dir, 3),
                    1e-13 * Knn);
    }
}

// One projected step along the normal: lambda = max(0, m_n (bias - u_n)), the impulse of
// the closed form for this one contact, and the velocities after it.
template <typename Rows> double one_step(const Rows &r)
{
    return std::max(0.0, r.normal.effective_mass * (r.bias - r.normal.velocity));
}

TEST(codegen_rows, one_step_for_one_contact_is_the_closed_form)
{
    std::mt19937_64 g(7);
    int approaching = 0;
    for (int trial = 0; trial < 200; ++trial) {
        {
            const std::vector<double> x = draw(g, gen::rows_planar_input_names, gen::rows_planar_input_count);
            gen::rows_planar_result<double> a;
            gen::rows_planar_rows_result<double> r;
            ASSERT_EQ(gen::rows_planar_rows(x.data(), r), gen::impact_status::ok);
            if (gen::rows_planar(x.data(), a) == gen::impact_status::ok) {
                ++approaching;
                const double lam = one_step(r);
                EXPECT_LE(rel(lam, a.normal_impulse), 1e-13);
                const auto m = by_name(gen::rows_planar_input_names, x);
                EXPECT_NEAR(m.at("v_n2") + r.inv_m2 * lam * r.normal.dir[1], a.v_n2, 1e-13);
                EXPECT_NEAR(m.at("w_b2") + r.inv_I2[0] * lam * r.normal.ang2[0], a.w_b2, 1e-13);
                EXPECT_NEAR(m.at("w_b1") - r.inv_I1[0] * lam * r.normal.ang1[0], a.w_b1, 1e-13);
            } else {
                EXPECT_EQ(one_step(r), 0.0); // separating: no impulse
            }
        }
        {
            // The engine convention: a static body (inverse mass and inertia 0) in one trial in three.
            std::vector<double> x = draw(g, gen::rows_planar_engine_input_names, gen::rows_planar_engine_input_count);
            if (trial % 3 == 0)
                x[1] = x[2] = 0;
            gen::rows_planar_engine_result<double> a;
            gen::rows_planar_engine_rows_result<double> r;
            ASSERT_EQ(gen::rows_planar_engine_rows(x.data(), r), gen::impact_status::ok);
            if (gen::rows_planar_engine(x.data(), a) == gen::impact_status::ok) {
                EXPECT_LE(rel(one_step(r), a.normal_impulse), 1e-13);
            }
        }
        {
            const std::vector<double> x =
                draw(g, gen::rows_noncentral_3d_input_names, gen::rows_noncentral_3d_input_count);
            gen::rows_noncentral_3d_result<double> a;
            gen::rows_noncentral_3d_rows_result<double> r;
            ASSERT_EQ(gen::rows_noncentral_3d_rows(x.data(), r), gen::impact_status::ok);
            expect_orthonormal(r, 3);
            if (gen::rows_noncentral_3d(x.data(), a) == gen::impact_status::ok) {
                const double lam = one_step(r);
                EXPECT_LE(rel(lam, a.normal_impulse), 1e-12);
                const auto m = by_name(gen::rows_noncentral_3d_input_names, x);
                for (int c = 0; c < 3; ++c) {
                    double dw = 0;
                    for (int j = 0; j < 3; ++j)
                        dw += r.inv_I2[3 * c + j] * lam * r.normal.ang2[j];
                    const double after[3] = {a.w_t2, a.w_n2, a.w_b2};
                    EXPECT_NEAR(m.at(std::string("w_") + "tnb"[c] + "2") + dw, after[c], 1e-12);
                }
            }
        }
    }
    EXPECT_GT(approaching, 20);
}

TEST(codegen_rows, refused_with_a_pivot_in_one_line)
{
    const std::string cmd = std::string(IMPACTGEN_BINARY) + " codegen pinned-planar --rows --output /dev/null 2>&1";
    FILE *p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    std::string text;
    char buf[512];
    while (fgets(buf, sizeof buf, p))
        text += buf;
    const int rc = pclose(p);
    EXPECT_NE(rc, 0);
    EXPECT_NE(text.find("--rows"), std::string::npos) << text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

} // namespace
