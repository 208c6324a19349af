/// Why a call of a generated function with friction computed no post-impact state; the
/// first values are those of impact_status (same numbers). On any status but ok the
/// result holds the state unchanged: the velocities as before the impact, every impulse,
/// the approach velocity and the energy lost zero, regime smooth.
enum class friction_status : int {
    ok = 0,
    non_finite_input,    ///< an input is infinite or NaN
    invalid_mass,        ///< a mass is <= 0 or not finite
    invalid_inertia,     ///< an inertia (or its determinant, a leading minor) is <= 0 or not finite
    invalid_restitution, ///< e outside [0, 1]
    not_approaching,     ///< the contact points separate or rest: (v_B - v_A).n >= 0
    invalid_normal,      ///< the normal is zero, denormal or not finite (or, declared unit, not of length 1)
    singular,            ///< the contact response K is singular (det K <= 0) where the answer needs it (no slide holds; Routh's process), or n.K n <= 0 (mu = 0)
    overflow,            ///< finite inputs whose result overflows
    invalid_friction,    ///< mu < 0 or not finite
    no_solution,         ///< no regime satisfies its conditions (strong coupling of normal and tangential motion)
    ambiguous            ///< more than one regime (or sliding direction) satisfies its conditions
};

IMPACTGEN_FUNC constexpr const char* to_string(friction_status s) noexcept
{
    switch (s) {
    case friction_status::ok: return "ok";
    case friction_status::non_finite_input: return "non-finite input";
    case friction_status::invalid_mass: return "invalid mass";
    case friction_status::invalid_inertia: return "invalid inertia";
    case friction_status::invalid_restitution: return "invalid restitution";
    case friction_status::not_approaching: return "not approaching";
    case friction_status::invalid_normal: return "invalid normal";
    case friction_status::singular: return "singular contact response";
    case friction_status::overflow: return "overflow";
    case friction_status::invalid_friction: return "invalid friction";
    case friction_status::no_solution: return "no solution";
    case friction_status::ambiguous: return "ambiguous";
    }
    return "?";
}

/// Which solution of the law of restitution with Coulomb friction the impulse is:
/// smooth (mu = 0: no tangential impulse), stick (the contact points leave with no
/// tangential relative velocity, the impulse inside the friction cone) or slide (they
/// leave sliding, the impulse on the cone's edge, against the sliding direction).
enum class impact_regime : int { smooth = 0, stick, slide };

IMPACTGEN_FUNC constexpr const char* to_string(impact_regime r) noexcept
{
    switch (r) {
    case impact_regime::smooth: return "smooth";
    case impact_regime::stick: return "stick";
    case impact_regime::slide: return "slide";
    }
    return "?";
}

namespace detail {
IMPACTGEN_FUNC constexpr friction_status friction_status_of(impact_status s) noexcept
{
    return static_cast<friction_status>(static_cast<int>(s));
}
IMPACTGEN_FUNC constexpr friction_status friction_status_of(friction_status s) noexcept { return s; }

/// The stick/slide boundary within rounding: there the stick candidate and a slide are
/// one solution, their impulses equal to within the rounding of the stick candidate's
/// (relative errors of a few eps times the condition number of K, up to ~1e6 for the
/// mass ratios and lever arms impacts have). Impulses within eps^(2/3) (2^-35 in double,
/// 2^-16 in float) relative of each other count as that one solution.
template <typename T> IMPACTGEN_FUNC T boundary_tolerance() noexcept
{
    T r(1); // 2^-k by halving: exact, and for any scalar (an autodiff type has no ldexp)
    for (int k = 2 * std::numeric_limits<T>::digits / 3; k > 0; --k)
        r = r / T(2);
    return r;
}

/// A unit tangent basis (t, b) of the plane normal to n (any length; n = 0 or not finite
/// gives zeros, which the caller's normal check refuses), with b = t x n/|n|, computed at
/// run time for a normal given as inputs: every direction works, the axes included. It is
/// the branch-free basis of the unit normal (x, y, z) with s = +1 for z >= 0, -1 below:
/// t = (1 + s x^2 a, s x y a, -s x), b = -(x y a, s + y^2 a, -y), a = -1/(s + z); it is
/// continuous in n except across the plane z = 0, where s changes sign (no tangent basis
/// is continuous over every direction). The answer does not depend on the basis: it only
/// parametrises the sliding direction.
template <typename T> IMPACTGEN_FUNC void tangent_basis(T nx, T ny, T nz, T* t, T* b) noexcept
{
    using std::sqrt;
    const T ax = nx < T(0) ? -nx : nx, ay = ny < T(0) ? -ny : ny, az = nz < T(0) ? -nz : nz;
    const T big = ax < ay ? (ay < az ? az : ay) : (ax < az ? az : ax);
    if (!(big > T(0)) || !finite(big)) {
        for (int k = 0; k < 3; ++k)
            t[k] = b[k] = T(0);
        return;
    }
    nx = nx / big; // scaled first: no overflow or underflow in the squares
    ny = ny / big;
    nz = nz / big;
    const T length = sqrt(nx * nx + ny * ny + nz * nz);
    const T x = nx / length, y = ny / length, z = nz / length;
    const T s = z < T(0) ? T(-1) : T(1);
    const T a = T(-1) / (s + z), xya = x * y * a;
    t[0] = T(1) + s * x * x * a;
    t[1] = s * xya;
    t[2] = -s * x;
    b[0] = -xya;
    b[1] = -(s + y * y * a);
    b[2] = y;
}

/// How many iterations the slow paths of detail::trig2_roots took (tests and benchmarks
/// read them; define IMPACTGEN_TRIG2_STATS before including to count).
#ifdef IMPACTGEN_TRIG2_STATS
struct trig2_stats {
    static long& polished() { static long n = 0; return n; }   ///< roots Halley's steps left to the safeguarded loop
    static long& split() { static long n = 0; return n; }      ///< arcs subdivided
    static long& circle() { static long n = 0; return n; }     ///< calls that fell back to the whole-circle method
    static long& iterations() { static long n = 0; return n; } ///< iterations of the safeguarded loop
    static long& max_iterations() { static long n = 0; return n; }
};
#define IMPACTGEN_TRIG2_COUNT(what) (++detail::trig2_stats::what())
#else
#define IMPACTGEN_TRIG2_COUNT(what) ((void)0)
#endif

template <typename T> IMPACTGEN_FUNC T abs_of(T x) noexcept { return x < T(0) ? T(-x) : x; }
template <typename T> IMPACTGEN_FUNC T max_of(T x, T y) noexcept { return x < y ? y : x; }

/// cos(r pi / 8), r = 0..4.
template <typename T> IMPACTGEN_FUNC T cos_pi8(int r) noexcept
{
    switch (r) {
    case 0: return T(1);
    case 1: return detail::constant<T>(IMPACTGEN_WIDE(0.9238795325112867561281831893967882868224));
    case 2: return detail::constant<T>(IMPACTGEN_WIDE(0.7071067811865475244008443621048490392848));
    case 3: return detail::constant<T>(IMPACTGEN_WIDE(0.3826834323650897717284599840303988667613));
    default: return T(0);
    }
}

/// cos and sin of k pi / 8 (k >= 0), from the first quadrant by symmetry.
template <typename T> IMPACTGEN_FUNC void unit_pi8(int k, T& c, T& s) noexcept
{
    const int r = k & 3;
    const T x = cos_pi8<T>(r), y = cos_pi8<T>(4 - r);
    switch ((k >> 2) & 3) {
    case 0: c = x; s = y; break;
    case 1: c = -y; s = x; break;
    case 2: c = -x; s = -y; break;
    default: c = y; s = -x; break;
    }
}

/// p(x) = c[0] x^deg + ... + c[deg] and p'(x), by Horner's rule.
template <typename T> IMPACTGEN_FUNC void horner(const T* c, int deg, T x, T& p, T& dp) noexcept
{
    p = c[0];
    dp = T(0);
    for (int i = 1; i <= deg; ++i) {
        dp = dp * x + p;
        p = p * x + c[i];
    }
}

/// The root of the polynomial c (degree deg) between lo and hi, where its values flo and
/// fhi have opposite signs and it has no other root: Newton's method safeguarded by
/// bisection (a Newton step is taken when it stays inside the bracket and is at most
/// half the step before the last, else the bracket is halved), from x0 (inside the
/// bracket, else its midpoint), until the step is at most tol. At most
/// std::numeric_limits<T>::digits + 16 iterations (69 in double): every accepted Newton
/// step is at most half the one two steps before and every other step halves the
/// bracket, so the steps shrink geometrically (a bracket of width W is below tol after
/// log2(W / tol) halvings: digits + 1 for the brackets here, W <= 2^16 tol / eps); the
/// cap only bounds the work when rounding makes the steps wander, the point returned
/// being inside the bracket whatever happens. The test suite records the most taken.
template <typename T> IMPACTGEN_FUNC T poly_root(const T* c, int deg, T lo, T hi, T flo, T fhi, T x0, T tol) noexcept
{
    if (flo == T(0))
        return lo;
    if (fhi == T(0))
        return hi;
    T neg = flo < T(0) ? lo : hi, pos = flo < T(0) ? hi : lo; // p(neg) < 0 < p(pos)
    T x = (x0 - lo) * (x0 - hi) < T(0) ? x0 : (lo + hi) / T(2);
    T dx_old = abs_of<T>(hi - lo), dx = dx_old;
    T f, df;
    horner<T>(c, deg, x, f, df);
    const int cap = std::numeric_limits<T>::digits + 16;
    int it = 0;
    for (; it < cap; ++it) {
        if (f == T(0))
            break;
        if (f < T(0))
            neg = x;
        else
            pos = x;
        const T newton = x - f / df;
        dx_old = dx;
        if ((newton - neg) * (newton - pos) < T(0) && abs_of<T>(T(2) * f) <= abs_of<T>(dx_old * df)) {
            dx = abs_of<T>(x - newton);
            x = newton;
        } else {
            dx = abs_of<T>(pos - neg) / T(2);
            x = (pos + neg) / T(2);
        }
        if (dx <= tol)
            break;
        horner<T>(c, deg, x, f, df);
    }
#ifdef IMPACTGEN_TRIG2_STATS
    trig2_stats::iterations() += it;
    if (it > trig2_stats::max_iterations())
        trig2_stats::max_iterations() = it;
#endif
    return x;
}

/// The unit vector at angle phi from (c, s), given t = tan(phi / 2).
template <typename T> IMPACTGEN_FUNC void trig2_rotate(T c, T s, T t, T& rc, T& rs) noexcept
{
    const T tt = t * t, den = T(1) / (T(1) + tt);
    const T cp = (T(1) - tt) * den, sp = T(2) * t * den;
    rc = cp * c - sp * s;
    rs = sp * c + cp * s;
}

/// The quartic p(t) = (1 + t^2)^2 g(theta) in the chart t = tan(phi / 2), theta = theta_0 + phi,
/// with (c, s) = (cos theta_0, sin theta_0): its coefficients, highest first. p(0) = g(theta_0),
/// and the leading coefficient is g(theta_0 + pi).
template <typename T> IMPACTGEN_FUNC void trig2_chart(T a0, T a1, T b1, T a2, T b2, T c, T s, T* p) noexcept
{
    const T c2 = c * c - s * s, s2 = T(2) * c * s;
    const T al1 = a1 * c + b1 * s, be1 = b1 * c - a1 * s, al2 = a2 * c2 + b2 * s2, be2 = b2 * c2 - a2 * s2;
    p[0] = a0 - al1 + al2;
    p[1] = T(2) * be1 - T(4) * be2;
    p[2] = T(2) * a0 - T(6) * al2;
    p[3] = T(2) * be1 + T(4) * be2;
    p[4] = a0 + al1 + al2;
}

/// The roots of g by a method that needs no sampling: the quartic of the chart whose
/// t = infinity is the sample (of the 16) where |g| is largest (so that its leading
/// coefficient is at least 1/1.09 of max |g| over the circle: a trigonometric polynomial
/// of degree 2 sampled at 16 points exceeds its largest sample by at most
/// 1/cos(2 pi / 16)), made monic; every root of it and of its derivatives lies in
/// |t| < B (Cauchy's bound, Gauss-Lucas). The roots of q'' (closed form) split [-B, B]
/// where q' is monotone: its roots there (safeguarded Newton) are the critical points of
/// q, which split [-B, B] where q is monotone: one root in each piece where q changes
/// sign, and a root at a critical point where q is 0. The slow path of trig2_roots
/// (exact zeros at the samples, or arcs it cannot decide after subdivision); a root of
/// even multiplicity is found where rounding leaves q at the critical point 0 or of the
/// other sign.
template <typename T>
IMPACTGEN_COLD IMPACTGEN_FUNC int trig2_roots_circle(T a0, T a1, T b1, T a2, T b2, const T* g, T* rc, T* rs) noexcept
{
    using std::sqrt;
    IMPACTGEN_TRIG2_COUNT(circle);
    int kmax = 0;
    for (int k = 1; k < 16; ++k)
        if (abs_of<T>(g[k]) > abs_of<T>(g[kmax]))
            kmax = k;
    T cc, sc;
    unit_pi8<T>((kmax + 8) & 15, cc, sc);
    T q[5];
    trig2_chart<T>(a0, a1, b1, a2, b2, cc, sc, q);
    for (int i = 1; i < 5; ++i)
        q[i] /= q[0];
    q[0] = T(1);
    T B = abs_of<T>(q[1]);
    for (int i = 2; i < 5; ++i)
        B = max_of<T>(B, abs_of<T>(q[i]));
    B += T(1);
    const T eps = detail::machine_epsilon<T>();
    const T d1[4] = {T(4), T(3) * q[1], T(2) * q[2], q[3]}; // q'
    const T d2[3] = {T(12), T(6) * q[1], T(2) * q[2]};      // q''
    T ends[4];
    int ne = 0;
    ends[ne++] = -B;
    const T disc = d2[1] * d2[1] - T(4) * d2[0] * d2[2];
    if (disc > T(0)) {
        const T r = sqrt(disc);
        const T m = -(d2[1] + (d2[1] < T(0) ? -r : r)) / T(2); // no cancellation
        const T r1 = m / d2[0], r2 = d2[2] / m;
        ends[ne++] = r1 < r2 ? r1 : r2;
        ends[ne++] = r1 < r2 ? r2 : r1;
    }
    ends[ne++] = B;
    T crit[5], dd;
    int nc = 0;
    crit[nc++] = -B;
    T prev;
    horner<T>(d1, 3, ends[0], prev, dd);
    for (int i = 1; i < ne; ++i) {
        T v;
        horner<T>(d1, 3, ends[i], v, dd);
        if ((prev < T(0) && v > T(0)) || (prev > T(0) && v < T(0)))
            crit[nc++] = poly_root<T>(d1, 3, ends[i - 1], ends[i], prev, v, (ends[i - 1] + ends[i]) / T(2), T(2) * eps * (T(1) + abs_of<T>(ends[i])));
        else if (v == T(0) && i + 1 < ne)
            crit[nc++] = ends[i];
        prev = v;
    }
    crit[nc++] = B;
    int n = 0;
    horner<T>(q, 4, crit[0], prev, dd);
    for (int i = 1; i < nc && n < 4; ++i) {
        T v, t = T(0);
        horner<T>(q, 4, crit[i], v, dd);
        bool found = true;
        if ((prev < T(0) && v > T(0)) || (prev > T(0) && v < T(0)))
            t = poly_root<T>(q, 4, crit[i - 1], crit[i], prev, v, (crit[i - 1] + crit[i]) / T(2), T(2) * eps * (T(1) + abs_of<T>(crit[i])));
        else if (v == T(0) && i + 1 < nc)
            t = crit[i];
        else
            found = false;
        if (found) {
            trig2_rotate<T>(cc, sc, t, rc[n], rs[n]);
            ++n;
        }
        prev = v;
    }
    return n;
}

/// The index of the lowest bit set (bits != 0).
IMPACTGEN_FUNC int trig2_lowest(unsigned bits) noexcept
{
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
    return __builtin_ctz(bits);
#else
    int k = 0;
    while (((bits >> k) & 1u) == 0u)
        ++k;
    return k;
#endif
}

/// An arc of the circle: unit vectors at its ends, g, g' and g'' there, its angle w.
template <typename T> struct trig2_arc {
    T cl, sl, gl, dl, el, ch, sh, gh, dh, eh, w;
    int depth;
};

/// g, g' and g'' at the unit vector (c, s).
template <typename T> IMPACTGEN_FUNC void trig2_at(T a0, T a1, T b1, T a2, T b2, T c, T s, T& g, T& d, T& e) noexcept
{
    const T c2 = c * c - s * s, s2 = T(2) * c * s, h2 = a2 * c2 + b2 * s2;
    g = a0 + a1 * c + b1 * s + h2;
    d = b1 * c - a1 * s + T(2) * (b2 * c2 - a2 * s2);
    e = a0 - g - T(3) * h2;
}

/// How many roots g has inside an arc whose ends are not roots: 0, 1 (then g changes
/// sign across it), or 2 for undecided. With |g'| <= L1, |g''| <= L2, |g'''| <= L3 on the
/// circle (and the tighter bounds on the arc they give with the values at its ends):
/// no root when g keeps its sign and cannot reach 0 (first order: |g_l| + |g_h| > w max|g'|;
/// second order from each end to the middle; g' of one sign; g concave towards 0, or
/// convex with both end tangents' crossing on the same side); one root when g changes
/// sign and g' or g'' keeps its sign (then g has at most two roots on the arc, one of
/// them where it changes sign).
template <typename T> IMPACTGEN_FUNC int trig2_classify(const trig2_arc<T>& a, T L1, T L2, T L3) noexcept
{
    const T w = a.w;
    const T L2a = detail::min_of<T>(L2, max_of<T>(abs_of<T>(a.el), abs_of<T>(a.eh)) + L3 * w / T(2)); // |g''| on the arc
    const T L1a = detail::min_of<T>(L1, max_of<T>(abs_of<T>(a.dl), abs_of<T>(a.dh)) + L2a * w / T(2)); // |g'| on the arc
    const T r3 = L3 * w * w / T(8);
    const T sd = a.dl < T(0) ? T(-1) : T(1);
    const bool mono = abs_of<T>(a.dl) + abs_of<T>(a.dh) > L2a * w ||
                      (sd * a.dh > T(0) && sd * (a.dl + a.el * w / T(2)) > r3 && sd * (a.dh - a.eh * w / T(2)) > r3);
    const bool conv = (a.el < T(0)) == (a.eh < T(0)) && a.el != T(0) && abs_of<T>(a.el) + abs_of<T>(a.eh) > L3 * w;
    if ((a.gl < T(0)) != (a.gh < T(0)))
        return mono || conv ? 1 : 2;
    if (mono || abs_of<T>(a.gl) + abs_of<T>(a.gh) > L1a * w)
        return 0;
    // In units where g > 0 at the ends: G = sigma g.
    const T sg = a.gl < T(0) ? T(-1) : T(1);
    const T Gl = sg * a.gl, Gh = sg * a.gh, Dl = sg * a.dl, Dh = sg * a.dh, q = L2a * w * w / T(8);
    if (Gl + Dl * w / T(2) > q && Gh - Dh * w / T(2) > q)
        return 0;
    if (conv) {
        if (sg * a.el < T(0) || Dl >= T(0) || Dh <= T(0))
            return 0; // concave (above its chord), or convex and monotone
        // Convex, falling then rising: above both end tangents, which cross inside the arc.
        const T x = (Gh - Gl - Dh * w) / (Dl - Dh);
        if (Gl + Dl * x > T(0))
            return 0;
    }
    return 2;
}

/// Refines the roots of g alone in arcs: n arcs (n <= 4) given by their first end (cl, sl),
/// angle w and tw = tan(w / 2), g and g' at both ends, side by side.
/// Halley's method on the quartic of each arc's chart (trig2_chart: t = tan(phi / 2),
/// phi the angle from the first end, t in [0, tan(w / 2)]), from inverse cubic Hermite
/// interpolation of the angle as a function of g; steps in every lane side by side (a
/// bisection instead when the step would leave the lane's bracket), at least two and at
/// most eight, until every lane is done: its last step stayed in its bracket and was at
/// most about eps^(1/3) / 4 tan(w / 2) (a Halley step s leaves an error of order s^3
/// relative to the arc: below the rounding of T). A lane not done after eight goes on
/// with poly_root (at most digits + 16 further iterations); a lane whose bracket ends
/// have the same computed sign has its root within rounding of an end (taken). The roots
/// go to rc, rs as unit vectors.
template <typename T>
IMPACTGEN_FUNC void trig2_refine(T a0, T a1, T b1, T a2, T b2, int n, const T* cl, const T* sl, const T* tw, const T* gl,
                                 const T* dl, const T* gh, const T* dh, const T* w, T* rc, T* rs) noexcept
{
    T p0[4], p1[4], p2[4], p3[4], p4[4], t[4], lo[4], hi[4], th[4], step[4], inside[4];
    for (int j = 0; j < n; ++j) {
        T p[5];
        trig2_chart<T>(a0, a1, b1, a2, b2, cl[j], sl[j], p);
        p0[j] = p[0];
        p1[j] = p[1];
        p2[j] = p[2];
        p3[j] = p[3];
        p4[j] = p[4];
        th[j] = tw[j]; // tan(w / 2)
        // Inverse cubic Hermite interpolation: phi(g) with phi = 0, w at g_l, g_h and
        // dphi/dg = 1/g'_l, 1/g'_h there, at g = 0 (s: where 0 lies between g_l and g_h).
        const T d = gh[j] - gl[j], s = -gl[j] / d, ss = s * s, sss = ss * s;
        T phi = (T(3) * ss - T(2) * sss) * w[j] + (sss - T(2) * ss + s) * (d / dl[j]) + (sss - ss) * (d / dh[j]);
        phi = phi > T(0) && phi < w[j] ? phi : s * w[j];
        const T x = phi / T(2), xx = x * x;
        t[j] = x * (T(1) + xx * (T(1) / T(3) + xx * (T(2) / T(15)))); // tan(phi / 2) to fifth order
        lo[j] = T(0);
        hi[j] = th[j];
        step[j] = th[j];
        inside[j] = T(0);
    }
    const T tight = T(1) / T(1LL << (std::numeric_limits<T>::digits / 3 + 2));
    bool done = false;
    for (int it = 0; it < 8 && !done; ++it) {
        done = it >= 1;
        for (int j = 0; j < n; ++j) {
            const T x = t[j];
            const T f = (((p0[j] * x + p1[j]) * x + p2[j]) * x + p3[j]) * x + p4[j];
            const T f1 = ((T(4) * p0[j] * x + T(3) * p1[j]) * x + T(2) * p2[j]) * x + p3[j];
            const T f2 = (T(12) * p0[j] * x + T(6) * p1[j]) * x + T(2) * p2[j];
            const bool left = (f < T(0)) == (p4[j] < T(0)); // the sign p has at t = 0
            lo[j] = left ? x : lo[j];
            hi[j] = left ? hi[j] : x;
            const T halley = x - T(2) * f * f1 / (T(2) * f1 * f1 - f * f2);
            const bool in = (halley > lo[j] && halley < hi[j]) || f == T(0);
            const T next = f == T(0) ? x : in ? halley : (lo[j] + hi[j]) / T(2);
            step[j] = abs_of<T>(next - x);
            inside[j] = in ? T(1) : T(0);
            t[j] = next;
            done = done && in && step[j] <= tight * th[j];
        }
    }
    const T eps = detail::machine_epsilon<T>();
    for (int j = 0; j < n; ++j) {
        if (!(inside[j] > T(0) && step[j] <= tight * th[j])) {
            IMPACTGEN_TRIG2_COUNT(polished);
            const T p[5] = {p0[j], p1[j], p2[j], p3[j], p4[j]};
            T flo, fhi, dd;
            horner<T>(p, 4, lo[j], flo, dd);
            horner<T>(p, 4, hi[j], fhi, dd);
            if ((flo < T(0)) != (fhi < T(0)))
                t[j] = poly_root<T>(p, 4, lo[j], hi[j], flo, fhi, t[j], T(2) * eps * th[j]);
            else // the root is within rounding of an end of the bracket (p has the same computed sign at both)
                t[j] = abs_of<T>(flo) <= abs_of<T>(fhi) ? lo[j] : hi[j];
        }
        trig2_rotate<T>(cl[j], sl[j], t[j], rc[j], rs[j]);
    }
}

/// The arcs between the 16 angles k pi / 8 (u: cos, sin of them; v: of twice them; w = pi / 8)
/// where the filter f (keep: its five coefficients as g's, or null) is negative throughout,
/// f(ends) + max|f'| w/2 < 0, as bits: they hold no root wanted.
template <typename T>
IMPACTGEN_FUNC unsigned trig2_dropped(const T* keep, const T* uc, const T* us, const T* vc, const T* vs, T w) noexcept
{
    using std::sqrt;
    unsigned drop = 0;
    if (keep == nullptr || !detail::all_finite(keep[0], keep[1], keep[2], keep[3], keep[4]))
        return drop;
    const T mk = max_of<T>(max_of<T>(max_of<T>(abs_of<T>(keep[0]), abs_of<T>(keep[1])), max_of<T>(abs_of<T>(keep[2]), abs_of<T>(keep[3]))), abs_of<T>(keep[4]));
    if (!(mk > T(0)))
        return drop;
    const T rk = T(1) / mk;
    const T k0 = keep[0] * rk, k1 = keep[1] * rk, k2 = keep[2] * rk, k3 = keep[3] * rk, k4 = keep[4] * rk;
    const T half = (sqrt(k1 * k1 + k2 * k2) + T(2) * sqrt(k3 * k3 + k4 * k4)) * w / T(2);
    T f[17];
    for (int k = 0; k < 17; ++k)
        f[k] = k0 + k1 * uc[k] + k2 * us[k] + k3 * vc[k] + k4 * vs[k];
    for (int k = 0; k < 16; ++k)
        drop |= static_cast<unsigned>(max_of<T>(f[k], f[k + 1]) + half < T(0)) << k;
    return drop;
}

/// The arcs that hold one root each, as trig2_refine takes them: ends, tan of half the
/// width, g and g' at the ends, width; n of them (at most four).
template <typename T> struct trig2_found {
    T cl[4], sl[4], tw[4], gl[4], dl[4], gh[4], dh[4], ww[4];
    int n = 0;
};

/// Adds the arc a (tan_half: the tangent of half its width) to f; false when f holds four
/// already (more roots than g can have: rounding).
template <typename T> IMPACTGEN_FUNC bool trig2_add(trig2_found<T>& f, const trig2_arc<T>& a, T tan_half) noexcept
{
    if (f.n == 4)
        return false;
    f.cl[f.n] = a.cl;
    f.sl[f.n] = a.sl;
    f.tw[f.n] = tan_half;
    f.gl[f.n] = a.gl;
    f.dl[f.n] = a.dl;
    f.gh[f.n] = a.gh;
    f.dh[f.n] = a.dh;
    f.ww[f.n] = a.w;
    ++f.n;
    return true;
}

/// Halves the undecided arcs todo[0..top) (the last first) until trig2_classify decides
/// each half, and adds the halves with one root to f; false when that cannot be done (an
/// arc halved 6 times, down to pi / 512; a midpoint exactly a root; more than four roots).
template <typename T>
IMPACTGEN_FUNC bool trig2_split(T a0, T a1, T b1, T a2, T b2, T L1, T L2, T L3, trig2_arc<T>* todo, int top, trig2_found<T>& f) noexcept
{
    using std::sqrt;
    while (top > 0) {
        IMPACTGEN_TRIG2_COUNT(split);
        const trig2_arc<T> a = todo[--top];
        if (a.depth == 6)
            return false;
        T cm = a.cl + a.ch, sm = a.sl + a.sh; // the arc's midpoint: the normalised sum of its ends
        const T len = T(1) / sqrt(cm * cm + sm * sm);
        cm *= len;
        sm *= len;
        T gm, dm, em;
        trig2_at(a0, a1, b1, a2, b2, cm, sm, gm, dm, em);
        if (gm == T(0))
            return false;
        const T hw = a.w / T(2);
        const trig2_arc<T> half[2] = {{a.cl, a.sl, a.gl, a.dl, a.el, cm, sm, gm, dm, em, hw, a.depth + 1},
                                      {cm, sm, gm, dm, em, a.ch, a.sh, a.gh, a.dh, a.eh, hw, a.depth + 1}};
        for (const trig2_arc<T>& b : half) {
            const int kind = trig2_classify(b, L1, L2, L3);
            if (kind == 2)
                todo[top++] = b;
            if (kind == 1 && !trig2_add<T>(f, b, (b.cl * b.sh - b.sl * b.ch) / (T(1) + b.cl * b.ch + b.sl * b.sh))) // tan(w / 2)
                return false;
        }
    }
    return true;
}

/// The roots of g(theta) = a0 + a1 cos theta + b1 sin theta + a2 cos 2 theta + b2 sin 2 theta
/// on the circle, as unit vectors (cos theta, sin theta) in rc[0..n), rs[0..n), n <= 4
/// returned; -1 when g vanishes identically (every direction), -2 when a coefficient is
/// not finite. keep (null, or the five coefficients of a polynomial f of the same form):
/// roots in arcs between samples where f < 0 provably (f at the ends plus the bound of
/// |f'| times half the arc) may be left out -- the caller wants only roots where f > 0
/// (and checks that itself).
///
/// The filter first: f at the 16 angles k pi / 8 (w = pi / 8 apart) and the arcs where it
/// is negative throughout (none left: no root wanted, return 0). Then g (scaled by its
/// largest coefficient), g' and g'' at the same angles (a table, no trigonometric call);
/// each arc left has no root when g keeps its sign and |g_l| + |g_h| > w max|g'| or g'
/// keeps its sign (|g'_l| + |g'_h| > w max|g''|), and exactly one when g changes sign and
/// g' keeps its sign; the few arcs these first order tests leave open get
/// trig2_classify's further tests, and halves of them while it cannot decide (at most 6
/// halvings: arcs down to pi / 512). The roots, each alone in its arc, are refined side by
/// side (trig2_refine). An arc still undecided then (roots closer than that, a root of
/// even multiplicity), a sample or midpoint exactly a root, or more than four roots
/// (rounding) send the call to trig2_roots_circle, which finds every root.
template <typename T> IMPACTGEN_FUNC int trig2_roots(T a0, T a1, T b1, T a2, T b2, const T* keep, T* rc, T* rs) noexcept
{
    using std::sqrt;
    if (!detail::all_finite(a0, a1, b1, a2, b2))
        return -2;
    // The roots do not change with the scale of g: divide by the largest coefficient, so
    // that the squares and bounds below neither overflow nor underflow.
    const T m = max_of<T>(max_of<T>(max_of<T>(abs_of<T>(a0), abs_of<T>(a1)), max_of<T>(abs_of<T>(b1), abs_of<T>(a2))), abs_of<T>(b2));
    if (m == T(0))
        return -1;
    const T r = T(1) / m;
    a0 *= r;
    a1 *= r;
    b1 *= r;
    a2 *= r;
    b2 *= r;
    const T A1 = sqrt(a1 * a1 + b1 * b1), A2 = sqrt(a2 * a2 + b2 * b2);
    const T L1 = A1 + T(2) * A2, L2 = A1 + T(4) * A2, L3 = A1 + T(8) * A2; // bounds of |g'|, |g''|, |g'''|
    const T w = detail::constant<T>(IMPACTGEN_WIDE(0.3926990816987241548078304229099378605246)); // pi / 8
    const T c1 = cos_pi8<T>(1), c2 = cos_pi8<T>(2), c3 = cos_pi8<T>(3);
    // cos, sin of k pi / 8 and of twice that, k = 0..16
    const T uc[17] = {T(1), c1, c2, c3, T(0), -c3, -c2, -c1, T(-1), -c1, -c2, -c3, T(0), c3, c2, c1, T(1)};
    const T us[17] = {T(0), c3, c2, c1, T(1), c1, c2, c3, T(0), -c3, -c2, -c1, T(-1), -c1, -c2, -c3, T(0)};
    const T vc[17] = {T(1), c2, T(0), -c2, T(-1), -c2, T(0), c2, T(1), c2, T(0), -c2, T(-1), -c2, T(0), c2, T(1)};
    const T vs[17] = {T(0), c2, T(1), c2, T(0), -c2, T(-1), -c2, T(0), c2, T(1), c2, T(0), -c2, T(-1), -c2, T(0)};
    const unsigned drop = trig2_dropped<T>(keep, uc, us, vc, vs, w);
    if (drop == 0xFFFFu)
        return 0; // no root wanted anywhere
    T g[17], dg[17], eg[17];
    for (int k = 0; k < 17; ++k) {
        const T h2 = a2 * vc[k] + b2 * vs[k];
        g[k] = a0 + a1 * uc[k] + b1 * us[k] + h2;
        dg[k] = b1 * uc[k] - a1 * us[k] + T(2) * (b2 * vc[k] - a2 * vs[k]);
        eg[k] = a0 - g[k] - T(3) * h2;
    }
    unsigned change = 0, open = 0, zero = 0;
    const T L1w = L1 * w, L2w = L2 * w;
    for (int k = 0; k < 16; ++k) {
        const unsigned ch = static_cast<unsigned>((g[k] < T(0)) != (g[k + 1] < T(0)));
        const unsigned mono = static_cast<unsigned>(abs_of<T>(dg[k]) + abs_of<T>(dg[k + 1]) > L2w);
        const unsigned far = static_cast<unsigned>(abs_of<T>(g[k]) + abs_of<T>(g[k + 1]) > L1w);
        change |= ch << k;
        open |= ((ch & ~mono) | (~ch & ~mono & ~far & 1u)) << k;
        zero |= static_cast<unsigned>(g[k] == T(0));
    }
    if (zero != 0u)
        return trig2_roots_circle(a0, a1, b1, a2, b2, g, rc, rs);
    change &= ~drop;
    open &= ~drop;
    // Arcs with one root: those where g changes sign and the first order test or
    // trig2_classify says so, and the halves of undecided arcs that trig2_classify
    // decides (at most 6 halvings: arcs down to pi / 512).
    trig2_found<T> found;
    const T tw0 = detail::constant<T>(IMPACTGEN_WIDE(0.1989123673796580069098427269237060575042)); // tan(pi / 16)
    trig2_arc<T> todo[24]; // a stack of undecided arcs: 16 + 6 + 1 entries at most
    int top = 0;
    for (unsigned bits = change | open; bits != 0u; bits &= bits - 1u) {
        const int k = trig2_lowest(bits);
        const trig2_arc<T> a{uc[k], us[k], g[k], dg[k], eg[k], uc[k + 1], us[k + 1], g[k + 1], dg[k + 1], eg[k + 1], w, 0};
        const int kind = ((open >> k) & 1u) != 0u ? trig2_classify(a, L1, L2, L3) : 1;
        if (kind == 2)
            todo[top++] = a;
        if (kind == 1 && !trig2_add<T>(found, a, tw0))
            return trig2_roots_circle(a0, a1, b1, a2, b2, g, rc, rs);
    }
    if (!trig2_split<T>(a0, a1, b1, a2, b2, L1, L2, L3, todo, top, found))
        return trig2_roots_circle(a0, a1, b1, a2, b2, g, rc, rs);
    if (found.n == 0)
        return 0;
    trig2_refine(a0, a1, b1, a2, b2, found.n, found.cl, found.sl, found.tw, found.gl, found.dl, found.gh, found.dh, found.ww, rc, rs);
    return found.n;
}

/// The sliding direction (c, s) (cos and sin of its angle from e_t towards e_b) of the one
/// solution of a 3-D impact that has at most one solution and does not stick (the caller
/// checked both: see the emitted function's test). With a = -(1 + e) u_n > 0, the tangential impulse
/// over N, tau, lies in the disc |tau| <= mu, and u'_t / N = (b + M tau) / a with
/// b = a K_tn + u_t K_nn and M = a K_tt + u_t K_nt^T (2 x 2, tangential axes); sliding,
/// tau = -mu d for the sliding direction d, and u'_t = lambda d (lambda > 0) reads
/// (mu M + l 1) d = b with l = a lambda / N > 0. Given m = mu M and b, d = x / |x| with
/// x(l) = adj(m + l 1) b / det(m + l 1), and l is the root of |x(l)| = 1: |x| falls
/// strictly for l >= 0 when m + m^T is positive definite, from above 1 at l = 0 (the
/// stick candidate is outside the cone) to below 1 at l = |b|, so the root is one and
/// bracketed. Newton's method on psi(l) = det(m + l 1) / |adj(m) b + l b| - 1 (linear
/// in l when m is a multiple of 1: one step), from the estimate l = |b| - b.m b / |b|^2,
/// a bisection whenever a step leaves the bracket, until a step is below 4 eps |b|: at
/// most 12 iterations (3 to 4 on random impacts); false when it has
/// not settled by then or a value is not finite (the caller then searches every
/// direction with trig2_roots).
template <typename T>
IMPACTGEN_FUNC bool slide_direction(T m11, T m12, T m21, T m22, T b1, T b2, T& c, T& s) noexcept
{
    using std::sqrt;
    // The direction does not change when m and b are scaled together.
    const T sc = max_of<T>(max_of<T>(max_of<T>(abs_of<T>(m11), abs_of<T>(m12)), max_of<T>(abs_of<T>(m21), abs_of<T>(m22))), max_of<T>(abs_of<T>(b1), abs_of<T>(b2)));
    if (!(sc > T(0) && detail::finite(sc)))
        return false;
    const T r = T(1) / sc;
    m11 *= r;
    m12 *= r;
    m21 *= r;
    m22 *= r;
    b1 *= r;
    b2 *= r;
    const T tr = m11 + m22, det = m11 * m22 - m12 * m21;
    const T a1 = m22 * b1 - m12 * b2, a2 = m11 * b2 - m21 * b1; // adj(m) b
    const T nb = sqrt(b1 * b1 + b2 * b2), tol = T(4) * detail::machine_epsilon<T>() * nb;
    // l = |b| - b.m b / |b|^2: the root when m is a multiple of 1 (for large l, |x| ~ |b| / (l + b.m b / |b|^2))
    T lo = T(0), hi = nb, l = max_of<T>(T(0), nb - (b1 * (m11 * b1 + m12 * b2) + b2 * (m21 * b1 + m22 * b2)) / (nb * nb));
    for (int it = 0; it < 12; ++it) {
        // x = (a1 + l b1, a2 + l b2) = adj(m + l 1) b, q = det(m + l 1); the Newton step
        // psi / psi' = (q - |x|) |x|^2 / ((2 l + tr) |x|^2 - q (x.b)), psi < 0 where q < |x|.
        const T x1 = a1 + l * b1, x2 = a2 + l * b2, xx2 = x1 * x1 + x2 * x2, xx = sqrt(xx2);
        const T q = l * (l + tr) + det;
        const T step = (q - xx) * xx2 / ((T(2) * l + tr) * xx2 - q * (x1 * b1 + x2 * b2));
        if (!detail::finite(step))
            return false;
        if (q < xx)
            lo = l;
        else
            hi = l;
        T next = l - step;
        if (!(next > lo && next < hi))
            next = (lo + hi) / T(2);
        if (abs_of<T>(next - l) <= tol || q == xx) {
            const T inv = T(1) / xx;
            c = x1 * inv;
            s = x2 * inv;
            return true;
        }
        l = next;
    }
    return false;
}
} // namespace detail
