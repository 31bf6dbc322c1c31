// Exact orientation and segment-intersection predicates (Shewchuk, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", 1997). orientation() runs in
// three tiers, each taken only when the one before cannot decide:
//   1. a floating-point filter with Shewchuk's a-priori error bound (almost every call ends here);
//   2. the exact determinant as an expansion: six products split by two_product (std::fma) into
//      twelve doubles, summed without error by two_sum (Grow-Expansion); the inputs are first
//      scaled by a power of two so that no product overflows or loses bits to underflow;
//   3. for inputs whose magnitudes span more than doubles can hold in one expansion (say 1e300
//      next to 1e-300), the same six products summed exactly in a fixed-point integer.
// The sign of the determinant never changes under scaling by 2^k, so all tiers agree.
// NOTE: FMA contraction (-ffp-contract=fast with -mfma) is harmless: only the filter feeds a
// product into a sum, and fusing there only removes a rounding. -ffast-math would break tiers 1-2.
#include "slc/geometry/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>

#include "slc/geometry/segment.hpp"

namespace slc {

namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon() / 2;  // 2^-53, unit roundoff

/// Shewchuk's bound for the filter: |det − det_computed| ≤ ccw_bound_a · detsum.
constexpr double ccw_bound_a = (3.0 + 16.0 * epsilon) * epsilon;

/// Shewchuk's bound assumes that nothing underflows. A product is safe when it is at least this
/// large (its rounding is then relative) or when one of its factors is exactly zero...
constexpr double smallest_safe_product = 2 * std::numeric_limits<double>::min();
/// ...and the bound itself, ccw_bound_a · detsum, is a normal number above this sum.
constexpr double smallest_safe_sum = 0x1p-960;

bool is_safe_product(double product, double f, double g) {
    return f == 0.0 || g == 0.0 || std::abs(product) >= smallest_safe_product;
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

/// a + b = s + e exactly (Knuth's two_sum), barring overflow.
void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

/// Stage 1: the sign of the determinant if rounding cannot have changed it, else 0 with
/// decided = false. Differences never underflow inexactly (a subnormal x − y is exact), so only
/// the products and overflow need guarding.
int filtered_orientation(Vec2 a, Vec2 b, Vec2 c, bool& decided) {
    const double ax = a.x - c.x;
    const double ay = a.y - c.y;
    const double bx = b.x - c.x;
    const double by = b.y - c.y;
    const double det_left = ax * by;
    const double det_right = ay * bx;
    const double det = det_left - det_right;
    const double det_sum = std::abs(det_left) + std::abs(det_right);
    decided = true;
    if (det_sum >= smallest_safe_sum && det_sum <= std::numeric_limits<double>::max() &&
        is_safe_product(det_left, ax, by) && is_safe_product(det_right, ay, bx) &&
        std::abs(det) > ccw_bound_a * det_sum) {
        return sign(det);
    }
    // Each product vanishes exactly when one of its differences does (x − y == 0 iff x == y).
    if ((ax == 0.0 || by == 0.0) && (ay == 0.0 || bx == 0.0)) return 0;
    decided = false;
    return 0;
}

/// A nonoverlapping expansion (Shewchuk §2): a sum held without error as at most n doubles of
/// increasing magnitude (zeros allowed), to which doubles and products of doubles are added
/// exactly. The caller keeps every term and partial sum clear of overflow and underflow.
template <std::size_t n>
class Expansion {
public:
    /// Adds q without error (Grow-Expansion): one term more.
    void add(double q) {
        for (std::size_t i = 0; i < length_; ++i) two_sum(q, e_[i], q, e_[i]);
        e_[length_++] = q;
    }
    /// Adds x·y without error as two terms (two_product: x·y = p + fma(x, y, −p) exactly).
    void add_product(double x, double y) {
        const double p = x * y;
        add(std::fma(x, y, -p));
        add(p);
    }
    /// Adds x·y·z without error as four terms: x·y = p + pe, then p·z and pe·z each split by fma.
    void add_product(double x, double y, double z) {
        const double p = x * y;
        const double pe = std::fma(x, y, -p);
        const double p1 = p * z, e1 = pe * z;
        add(std::fma(p, z, -p1));
        add(std::fma(pe, z, -e1));
        add(e1);
        add(p1);
    }
    /// The sign of the sum: the most significant nonzero term carries it.
    int sign() const {
        for (std::size_t i = length_; i-- > 0;) {
            if (e_[i] != 0.0) return slc::sign(e_[i]);
        }
        return 0;
    }

private:
    std::array<double, n> e_{};
    std::size_t length_ = 0;
};

/// Stage 2: the sign of ax·by − ax·cy + bx·cy − bx·ay + cx·ay − cx·by, every product and sum
/// error-free. Precondition: all nonzero inputs lie in [2^-485, 2^509), so that every product
/// is below 2^1018 (no overflow in twelve-term sums) and its low part, a multiple of
/// 2^(2·(-485) − 104) = 2^-1074, is representable.
int expansion_orientation(Vec2 a, Vec2 b, Vec2 c) {
    const std::array<std::array<double, 2>, 6> factors = {
        {{a.x, b.y}, {-a.x, c.y}, {b.x, c.y}, {-b.x, a.y}, {c.x, a.y}, {-c.x, b.y}}};
    Expansion<12> sum;
    for (const auto& [x, y] : factors) sum.add_product(x, y);
    return sum.sign();
}

/// Stage 3: a two's-complement fixed-point integer wide enough for any sum of six products of
/// finite doubles. A double is m · 2^q with |m| < 2^53 and q in [-1126, 971]; a product is below
/// 2^(106 + 1942) and a multiple of 2^-2252, so bits [-2304, 2176) hold six of them and a sign.
class WideInteger {
public:
    __extension__ typedef unsigned __int128 Word128;  // __extension__: a GCC/Clang type

    void add_product(double x, double y) {
        if (x == 0.0 || y == 0.0) return;
        int qx = 0;
        int qy = 0;
        const auto mx = static_cast<std::int64_t>(std::ldexp(std::frexp(x, &qx), 53));
        const auto my = static_cast<std::int64_t>(std::ldexp(std::frexp(y, &qy), 53));
        const bool negative = (mx < 0) != (my < 0);
        const auto magnitude =
            static_cast<Word128>(mx < 0 ? -mx : mx) * static_cast<Word128>(my < 0 ? -my : my);
        add_shifted(magnitude, qx + qy - 106 - lowest_bit, negative);
    }

    int sign() const {
        if (limbs_.back() >> 63) return -1;
        return std::any_of(limbs_.begin(), limbs_.end(), [](std::uint64_t l) { return l != 0; });
    }

private:
    static constexpr int lowest_bit = -2304;
    static constexpr std::size_t limb_count = 70;  // 4480 bits from 2^-2304

    /// Adds or subtracts magnitude · 2^shift, carrying through the limbs above.
    void add_shifted(Word128 magnitude, int shift, bool negative) {
        const auto limb = static_cast<std::size_t>(shift / 64);
        const int bit = shift % 64;
        const auto lo = static_cast<std::uint64_t>(magnitude);
        const auto hi = static_cast<std::uint64_t>(magnitude >> 64);
        const std::array<std::uint64_t, 3> words = {
            lo << bit, bit == 0 ? hi : (hi << bit) | (lo >> (64 - bit)),
            bit == 0 ? 0 : hi >> (64 - bit)};
        std::uint64_t carry = 0;  // carry when adding, borrow when subtracting
        for (std::size_t i = limb; i < limb_count; ++i) {
            const std::uint64_t w = i - limb < 3 ? words[i - limb] : 0;
            if (w == 0 && carry == 0 && i - limb >= 3) break;
            const std::uint64_t old = limbs_[i];
            if (negative) {
                limbs_[i] = old - w - carry;
                carry = (old < w || old - w < carry) ? 1 : 0;
            } else {
                limbs_[i] = old + w + carry;
                carry = (limbs_[i] < old || (carry == 1 && limbs_[i] == old)) ? 1 : 0;
            }
        }
    }

    std::array<std::uint64_t, limb_count> limbs_{};
};

int wide_orientation(Vec2 a, Vec2 b, Vec2 c) {
    WideInteger sum;
    sum.add_product(a.x, b.y);
    sum.add_product(-a.x, c.y);
    sum.add_product(b.x, c.y);
    sum.add_product(-b.x, a.y);
    sum.add_product(c.x, a.y);
    sum.add_product(-c.x, b.y);
    return sum.sign();
}

/// Stages 2 and 3: scales the inputs by 2^k into the range of expansion_orientation when their
/// exponents span at most 993 binades, else sums in a WideInteger.
int exact_orientation(Vec2 a, Vec2 b, Vec2 c) {
    const std::array<double, 6> v = {a.x, a.y, b.x, b.y, c.x, c.y};
    int hi = std::numeric_limits<int>::min();
    int lo = std::numeric_limits<int>::max();
    for (double x : v) {
        if (x == 0.0) continue;
        hi = std::max(hi, std::ilogb(x));
        lo = std::min(lo, std::ilogb(x));
    }
    if (hi == std::numeric_limits<int>::min()) return 0;  // all zero
    // The allowed binades of expansion_orientation: 2^-485 ≤ |x| < 2^509.
    constexpr int top = 508;
    constexpr int bottom = -485;
    if (hi - lo > top - bottom) return wide_orientation(a, b, c);
    if (hi <= top && lo >= bottom) return expansion_orientation(a, b, c);
    // Scaling by a power of two is exact here: every scaled value is a normal double.
    const int k = top - hi;
    auto scaled = [k](Vec2 p) { return Vec2{std::ldexp(p.x, k), std::ldexp(p.y, k)}; };
    return expansion_orientation(scaled(a), scaled(b), scaled(c));
}

/// Stage 1 of the 3D orientation: the sign of the determinant of the differences if rounding
/// cannot have changed it (Shewchuk's bound for orient3d), else decided = false. Below
/// smallest_safe_permanent a product may have lost bits to underflow, so the filter gives up.
int filtered_orientation(Vec3 a, Vec3 b, Vec3 c, Vec3 d, bool& decided) {
    constexpr double o3d_bound_a = (7.0 + 56.0 * epsilon) * epsilon;
    constexpr double smallest_safe_permanent = 0x1p-800;
    const Vec3 u = b - a, v = c - a, w = d - a;
    const double m0 = v.y * w.z - v.z * w.y;
    const double m1 = v.z * w.x - v.x * w.z;
    const double m2 = v.x * w.y - v.y * w.x;
    const double det = u.x * m0 + u.y * m1 + u.z * m2;
    const double permanent = std::abs(u.x) * (std::abs(v.y * w.z) + std::abs(v.z * w.y)) +
                             std::abs(u.y) * (std::abs(v.z * w.x) + std::abs(v.x * w.z)) +
                             std::abs(u.z) * (std::abs(v.x * w.y) + std::abs(v.y * w.x));
    decided = permanent >= smallest_safe_permanent &&
              permanent <= std::numeric_limits<double>::max() &&
              std::abs(det) > o3d_bound_a * permanent;
    if (permanent == 0.0 && u == Vec3{} && v == Vec3{} && w == Vec3{}) decided = true;
    return decided ? sign(det) : 0;
}

/// Adds s·|p q r| to sum without error, s = ±1: |p q r| = p·(q × r), six signed triple products
/// of four terms each.
template <std::size_t n>
void add_determinant(Expansion<n>& sum, Vec3 p, Vec3 q, Vec3 r, double s) {
    sum.add_product(s * p.x, q.y, r.z);
    sum.add_product(-s * p.x, q.z, r.y);
    sum.add_product(s * p.y, q.z, r.x);
    sum.add_product(-s * p.y, q.x, r.z);
    sum.add_product(s * p.z, q.x, r.y);
    sum.add_product(-s * p.z, q.y, r.x);
}

/// Stage 2 of the 3D orientation: det[b − a; c − a; d − a] = |b c d| − |a c d| + |a b d| − |a b c|
/// (multilinearity in the rows, |p q r| the determinant of three points), 24 triple products of
/// coordinates, each split without error into four doubles (two_product twice) and summed without
/// error by Grow-Expansion. Precondition: nonzero inputs lie in [2^-300, 2^300], so that no
/// product overflows and no low part underflows.
int expansion_orientation(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    Expansion<96> sum;
    add_determinant(sum, b, c, d, 1.0);
    add_determinant(sum, a, c, d, -1.0);
    add_determinant(sum, a, b, d, 1.0);
    add_determinant(sum, a, b, c, -1.0);
    return sum.sign();
}

/// Stage 2 for 3D when the differences u = b − a, v = c − a, w = d − a are exact doubles (as
/// they are for nearby points, by Sterbenz's lemma): det[u; v; w], six triple products of four
/// doubles each summed without error, a quarter of expansion_orientation's terms and a
/// sixteenth of its work. Precondition: nonzero components in [2^-300, 2^301].
int difference_orientation(Vec3 u, Vec3 v, Vec3 w) {
    Expansion<24> sum;
    add_determinant(sum, u, v, w, 1.0);
    return sum.sign();
}

/// q − p when it is an exact double whose components are zero or at least 2^-300; else
/// nullopt.
std::optional<Vec3> exact_difference(Vec3 q, Vec3 p) {
    double out[3];
    for (int i = 0; i < 3; ++i) {
        double s = 0.0, e = 0.0;
        two_sum(q[i], -p[i], s, e);
        if (e != 0.0 || (s != 0.0 && std::abs(s) < 0x1p-300)) return std::nullopt;
        out[i] = s;
    }
    return Vec3{out[0], out[1], out[2]};
}

/// Stages 2 for 3D: scales the inputs by 2^k (which scales the determinant by 2^3k, keeping its
/// sign) so that the largest lies just below 2^300.
int exact_orientation(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    {
        // Nearby points in the ordinary range need no scaling.
        const auto u = exact_difference(b, a), v = exact_difference(c, a),
                   w = exact_difference(d, a);
        auto ordinary = [](const std::optional<Vec3>& x) {
            return x && std::abs(x->x) <= 0x1p300 && std::abs(x->y) <= 0x1p300 &&
                   std::abs(x->z) <= 0x1p300;
        };
        if (ordinary(u) && ordinary(v) && ordinary(w)) return difference_orientation(*u, *v, *w);
    }
    int hi = std::numeric_limits<int>::min();
    for (const Vec3 p : {a, b, c, d}) {
        for (int i = 0; i < 3; ++i)
            if (p[i] != 0.0) hi = std::max(hi, std::ilogb(p[i]));
    }
    if (hi == std::numeric_limits<int>::min()) return 0;  // all zero
    const int k = 299 - hi;
    auto scaled = [k](Vec3 p) {
        return Vec3{std::ldexp(p.x, k), std::ldexp(p.y, k), std::ldexp(p.z, k)};
    };
    const Vec3 sa = scaled(a), sb = scaled(b), sc = scaled(c), sd = scaled(d);
    const auto u = exact_difference(sb, sa), v = exact_difference(sc, sa),
               w = exact_difference(sd, sa);
    if (u && v && w) return difference_orientation(*u, *v, *w);
    return expansion_orientation(sa, sb, sc, sd);
}

/// p lies in the bounding box of s; with p on the line of s, that means p lies on s.
bool in_box(Segment s, Vec2 p) { return bounding_box(s).contains(p); }

}  // namespace

int orientation(Vec2 a, Vec2 b, Vec2 c) {
    bool decided = false;
    const int s = filtered_orientation(a, b, c, decided);
    return decided ? s : exact_orientation(a, b, c);
}

int orientation(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    bool decided = false;
    const int s = filtered_orientation(a, b, c, d, decided);
    return decided ? s : exact_orientation(a, b, c, d);
}

bool segments_intersect(Segment s, Segment t) {
    // Disjoint bounding boxes (compared exactly) share no point: most pairs end here.
    if (!bounding_box(s).overlaps(bounding_box(t))) return false;
    const int o1 = orientation(s.a, s.b, t.a);
    const int o2 = orientation(s.a, s.b, t.b);
    const int o3 = orientation(t.a, t.b, s.a);
    const int o4 = orientation(t.a, t.b, s.b);
    // A proper crossing: each segment has the endpoints of the other strictly on both sides.
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    // Otherwise any common point is an endpoint of one segment lying on the other (this covers
    // touching, collinear overlap and degenerate segments).
    return (o1 == 0 && in_box(s, t.a)) || (o2 == 0 && in_box(s, t.b)) ||
           (o3 == 0 && in_box(t, s.a)) || (o4 == 0 && in_box(t, s.b));
}

int exact_volume_sign(std::span<const Vec3> vertices,
                      std::span<const std::array<std::uint32_t, 3>> triangles) {
    int hi = std::numeric_limits<int>::min();
    for (const auto& t : triangles) {
        for (std::uint32_t v : t) {
            for (int k = 0; k < 3; ++k)
                if (vertices[v][k] != 0.0) hi = std::max(hi, std::ilogb(vertices[v][k]));
        }
    }
    if (hi == std::numeric_limits<int>::min()) return 0;  // every corner at the origin
    // Scaled by 2^k, every triple product is below 2^903, and its parts are exact unless they
    // fall below 2^-1074.
    const int k = 300 - hi;
    WideInteger sum;
    // x·y·z = p·z + pe·z, x·y = p + pe exactly; each of p·z and pe·z split again by fma.
    auto add_triple = [&sum](double x, double y, double z) {
        const double p = x * y, pe = std::fma(x, y, -p);
        const double p1 = p * z, e1 = pe * z;
        for (double part : {std::fma(p, z, -p1), std::fma(pe, z, -e1), e1, p1})
            sum.add_product(part, 1.0);
    };
    for (const auto& t : triangles) {
        Vec3 q[3];
        for (int i = 0; i < 3; ++i) {
            const Vec3 v = vertices[t[static_cast<std::size_t>(i)]];
            q[i] = {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
        }
        const Vec3 a = q[0], b = q[1], c = q[2];
        add_triple(a.x, b.y, c.z);
        add_triple(-a.x, b.z, c.y);
        add_triple(a.y, b.z, c.x);
        add_triple(-a.y, b.x, c.z);
        add_triple(a.z, b.x, c.y);
        add_triple(-a.z, b.y, c.x);
    }
    return sum.sign();
}

}  // namespace slc
