// Seeded random inputs for the named classes and random problems. The seed
// and the count come from IMPACTGEN_SEED and IMPACTGEN_SAMPLES when set.
#pragma once

#include "symbolic/named_classes.hpp"

#include <cstdlib>
#include <random>
#include <string>

namespace impactgen::testing
{

/// GiNaC's Digits at 40 for the scope: the tests' evaluations of closed forms with CLN.
struct digits_40 {
    long saved = GiNaC::Digits;
    digits_40() { GiNaC::Digits = 40; }
    ~digits_40() { GiNaC::Digits = saved; }
};

inline unsigned seed_from_env(unsigned fallback = 20261121u)
{
    const char *s = std::getenv("IMPACTGEN_SEED");
    return s ? static_cast<unsigned>(std::strtoul(s, nullptr, 10)) : fallback;
}
inline int samples_from_env(int fallback)
{
    const char *s = std::getenv("IMPACTGEN_SAMPLES");
    return s ? std::atoi(s) : fallback;
}

class sampler
{
public:
    explicit sampler(unsigned seed) : rng_(seed) {}

    /// A rational p/q with |p/q| <= bound, q in 1..12.
    GiNaC::numeric rational(int bound)
    {
        std::uniform_int_distribution<int> den(1, 12);
        int q = den(rng_);
        std::uniform_int_distribution<int> num(-bound * q, bound * q);
        return GiNaC::numeric(num(rng_), q);
    }
    GiNaC::numeric positive(int lo_den, int hi)
    {
        std::uniform_int_distribution<int> num(1, hi * lo_den);
        return GiNaC::numeric(num(rng_), lo_den);
    }
    /// A mass, now and then extreme (ratios 1e-6 .. 1e6 between bodies).
    GiNaC::numeric mass()
    {
        std::uniform_int_distribution<int> pick(0, 9);
        int k = pick(rng_);
        if (k == 0)
            return GiNaC::numeric(1, 1000) * positive(4, 3);
        if (k == 1)
            return GiNaC::numeric(1000) * positive(4, 3);
        return positive(4, 10);
    }
    GiNaC::numeric restitution()
    {
        std::uniform_int_distribution<int> pick(0, 10);
        return GiNaC::numeric(pick(rng_), 10);
    }
    /// A symmetric positive-definite 3x3 matrix: A^T A + c 1, A random.
    impactgen::mat3 spd()
    {
        impactgen::mat3 A, M;
        for (auto &row : A)
            for (auto &e : row)
                e = rational(2);
        GiNaC::numeric c = positive(4, 2);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                GiNaC::ex s = i == j ? GiNaC::ex(c) : GiNaC::ex(0);
                for (int k = 0; k < 3; ++k)
                    s += A[k][i] * A[k][j];
                M[i][j] = s;
            }
        return M;
    }
    std::mt19937 &engine() { return rng_; }

private:
    std::mt19937 rng_;
};

/// Values for every symbol of a named class, by the names the notes use:
/// m*, e, I* (positive / SPD tensors), l, R* (lengths > 0), the rest in [-3, 3].
/// Velocities are flipped when the bodies would not approach.
inline GiNaC::lst sample_class_inputs(const problem &p, sampler &rnd)
{
    GiNaC::lst values;
    impactgen::mat3 I[3] = {rnd.spd(), rnd.spd(), rnd.spd()};
    const std::string ax = "tnb";
    for (const GiNaC::symbol &s : p.parameters()) {
        const std::string n = s.get_name();
        GiNaC::ex v;
        if (n[0] == 'm')
            v = rnd.mass();
        else if (n == "e")
            v = rnd.restitution();
        else if (n[0] == 'I' && n.size() == 5 && n[2] == '_') // I1_tn
            v = I[n[1] - '0'][ax.find(n[3])][ax.find(n[4])];
        else if (n[0] == 'I' || n[0] == 'l' || n[0] == 'R')
            v = rnd.positive(4, 4);
        else
            v = rnd.rational(3);
        values.append(s == v);
    }
    return values;
}

} // namespace impactgen::testing
