// One-dimensional ENO kernels: stencil choice by undivided differences, Lagrange weights for the
// derivative at a node and for interpolation, and the 1-2-1 smoothing pass (paper §3.2).
#include "slc/geometry_modules/eno.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "slc/core/error.hpp"

namespace slc::eno {
namespace {

constexpr int max_points = max_order + 1;

/// 1 / Π_{l≠m} (m − l) for the Lagrange basis on nodes 0..p − 1: table[p][m].
using InverseDenominators = std::array<std::array<double, max_points>, max_points + 1>;

const InverseDenominators& inverse_denominators() {
    static const InverseDenominators table = [] {
        InverseDenominators t{};
        for (int p = 1; p <= max_points; ++p) {
            for (int m = 0; m < p; ++m) {
                double d = 1.0;
                for (int l = 0; l < p; ++l)
                    if (l != m) d *= m - l;
                t[static_cast<std::size_t>(p)][static_cast<std::size_t>(m)] = 1.0 / d;
            }
        }
        return t;
    }();
    return table;
}

void check_order(int order) {
    SLC_ASSERT(order >= 1 && order <= max_order, "ENO order is in 1..max_order");
}

/// Undivided differences of a line, level by level: at(d, k) = Δ^d f_k over samples k..k + d,
/// for d = 1..levels, each level computed from the one below (the same operations, in the same
/// order, whatever the window, so stencil choices do not depend on how a line is cut).
class DifferenceTable {
public:
    DifferenceTable(std::span<const double> f, int levels) : n_(f.size()) {
        const std::size_t size = static_cast<std::size_t>(levels) * n_;
        if (size > small_.size()) large_.resize(size);
        diff_ = size > small_.size() ? large_.data() : small_.data();
        if (size <= small_.size()) {
            // A short window (a stencil's), column by column from the right: each entry from
            // two of the level below, one of them just computed. Level by level, the vectorized
            // loads of each level would wait for the stores of the level before.
            for (std::size_t k = n_ - 1; k-- > 0;) {
                diff_[k] = f[k + 1] - f[k];
                for (int d = 2; d <= levels && k + static_cast<std::size_t>(d) < n_; ++d) {
                    const std::size_t row = static_cast<std::size_t>(d - 1) * n_;
                    diff_[row + k] = diff_[row - n_ + k + 1] - diff_[row - n_ + k];
                }
            }
            return;
        }
        for (std::size_t k = 0; k + 1 < n_; ++k) diff_[k] = f[k + 1] - f[k];
        for (int d = 2; d <= levels; ++d) {
            const std::size_t row = static_cast<std::size_t>(d - 1) * n_, below = row - n_;
            for (std::size_t k = 0; k + static_cast<std::size_t>(d) < n_; ++k)
                diff_[row + k] = diff_[below + k + 1] - diff_[below + k];
        }
    }
    DifferenceTable(const DifferenceTable&) = delete;
    DifferenceTable& operator=(const DifferenceTable&) = delete;

    /// |Δ^d f_k|, for 1 <= d <= levels and k + d < n.
    double magnitude(int d, std::size_t k) const {
        return std::abs(diff_[static_cast<std::size_t>(d - 1) * n_ + k]);
    }

private:
    std::size_t n_;
    std::array<double, 64> small_;  ///< enough for the windows of stencil(): (2E + 2)·E <= 60
    std::vector<double> large_;
    double* diff_ = nullptr;
};

/// The ENO rule on a precomputed table (see stencil()).
/// The preferred side is the one that brings the stencil nearer its start's centre, and where
/// both leave it equally far off, the left one (the right one if `lean_right`). It wins ties,
/// and with a bias (eno::derivative) any difference less than `bias` times the other side's.
Stencil grow(const DifferenceTable& table, std::size_t n, std::size_t lo, std::size_t hi, int order,
             double bias = 1.0, bool lean_right = false) {
    const std::size_t centre2 = lo + hi;  // twice the centre of the starting stencil
    int points = static_cast<int>(hi - lo) + 1;
    while (points < order + 1 && hi - lo + 1 < n) {
        bool left;
        if (lo == 0) {
            left = false;
        } else if (hi + 1 == n) {
            left = true;
        } else {
            const double dl = table.magnitude(points, lo - 1), dr = table.magnitude(points, lo);
            const bool prefer_left = lean_right ? lo + hi > centre2 : lo + hi >= centre2;
            left = prefer_left ? dl <= bias * dr : bias * dl < dr;
        }
        if (left) {
            --lo;
        } else {
            ++hi;
        }
        ++points;
    }
    return {lo, points};
}

/// Weights w[m] with Σ w[m] f(m) = p'(at) for the polynomial p of degree points − 1 through the
/// samples at the integers 0..points − 1 (unit spacing): w[m] = L_m'(at).
std::array<double, max_points> lagrange_derivative_weights(int points, double at) {
    std::array<double, max_points> w{};
    for (int m = 0; m < points; ++m) {
        double denominator = 1.0;
        for (int l = 0; l < points; ++l)
            if (l != m) denominator *= m - l;
        double sum = 0.0;
        for (int q = 0; q < points; ++q) {
            if (q == m) continue;
            double product = 1.0;
            for (int l = 0; l < points; ++l)
                if (l != m && l != q) product *= at - l;
            sum += product;
        }
        w[static_cast<std::size_t>(m)] = sum / denominator;
    }
    return w;
}

/// Derivative weights for every stencil size and every node of the stencil, computed once:
/// table[points][node][m].
using DerivativeTable =
    std::array<std::array<std::array<double, max_points>, max_points>, max_points + 1>;

const DerivativeTable& derivative_table() {
    static const DerivativeTable table = [] {
        DerivativeTable t{};
        for (int p = 1; p <= max_points; ++p)
            for (int node = 0; node < p; ++node)
                t[static_cast<std::size_t>(p)][static_cast<std::size_t>(node)] =
                    lagrange_derivative_weights(p, node);
        return t;
    }();
    return table;
}

/// Σ L_m(at) f[m] for the Lagrange basis on the integer nodes 0..P − 1: L_m(at) =
/// Π_{l≠m} (at − l) / Π_{l≠m} (m − l), the numerators from prefix and suffix products, the
/// denominators from a table. P is fixed at compile time so that the products stay in registers.
template <std::size_t P>
double lagrange_sum(const double* f, double at) {
    static_assert(P >= 1 && P <= max_points);
    std::array<double, P + 1> suffix{};
    suffix[P] = 1.0;
    for (std::size_t l = P; l-- > 0;) suffix[l] = suffix[l + 1] * (at - static_cast<double>(l));
    const auto& inverse = inverse_denominators()[P];
    // The prefix product Π_{l<m} (at − l) runs along with the sum.
    double prefix = 1.0, sum = 0.0;
    for (std::size_t m = 0; m < P; ++m) {
        sum += prefix * suffix[m + 1] * inverse[m] * f[m];
        prefix *= at - static_cast<double>(m);
    }
    return sum;
}

}  // namespace

Stencil stencil(std::span<const double> f, std::size_t lo, std::size_t hi, int order) {
    check_order(order);
    SLC_ASSERT(lo <= hi && hi < f.size(), "the starting stencil lies inside the line");
    // Only samples within `order` of the start can join the stencil.
    const std::size_t first =
        lo >= static_cast<std::size_t>(order) ? lo - static_cast<std::size_t>(order) : 0;
    const std::size_t last = std::min(f.size() - 1, hi + static_cast<std::size_t>(order));
    const auto window = f.subspan(first, last - first + 1);
    const DifferenceTable table(window, order);
    const Stencil s = grow(table, window.size(), lo - first, hi - first, order);
    return {s.first + first, s.points};
}

void derivative(std::span<const double> f, double h, int order, std::span<double> out,
                double bias) {
    check_order(order);
    SLC_ASSERT(out.size() == f.size(), "one derivative per sample");
    SLC_ASSERT(h > 0.0, "positive spacing");
    SLC_ASSERT(bias >= 1.0, "a bias of at least 1");
    if (f.size() < 2) {
        std::fill(out.begin(), out.end(), 0.0);
        return;
    }
    const DerivativeTable& weights = derivative_table();
    const DifferenceTable differences(f, order);
    for (std::size_t k = 0; k < f.size(); ++k) {
        const auto difference = [&](const Stencil& s) {
            const auto& w = weights[static_cast<std::size_t>(s.points)][k - s.first];
            double sum = 0.0;
            for (int m = 0; m < s.points; ++m)
                sum += w[static_cast<std::size_t>(m)] * f[s.first + static_cast<std::size_t>(m)];
            return sum / h;
        };
        const Stencil s = grow(differences, f.size(), k, k, order, bias);
        out[k] = difference(s);
        if (bias > 1.0) {
            // The same rule leaning right where the stencil is balanced, and the mean of the two.
            const Stencil r = grow(differences, f.size(), k, k, order, bias, true);
            if (r.first != s.first || r.points != s.points) out[k] = 0.5 * (out[k] + difference(r));
        }
    }
}

double interpolate(std::span<const double> f, std::size_t i, double theta, int order) {
    check_order(order);
    SLC_ASSERT(i + 1 < f.size(), "the interval [x_i, x_{i+1}] lies inside the line");
    return interpolate(f, stencil(f, i, i + 1, order), i, theta);
}

double interpolate(std::span<const double> f, const Stencil& s, std::size_t i, double theta) {
    SLC_ASSERT(s.points >= 1 && s.points <= max_points && s.first <= i &&
                   s.first + static_cast<std::size_t>(s.points) <= f.size(),
               "the stencil lies inside the line and holds x_i");
    // Lagrange basis on the integer nodes 0..p − 1 of the stencil at x_i + theta in those units.
    const double at = static_cast<double>(i - s.first) + theta;
    const double* samples = f.data() + s.first;
    switch (s.points) {
        case 1:
            return lagrange_sum<1>(samples, at);
        case 2:
            return lagrange_sum<2>(samples, at);
        case 3:
            return lagrange_sum<3>(samples, at);
        case 4:
            return lagrange_sum<4>(samples, at);
        case 5:
            return lagrange_sum<5>(samples, at);
        default:
            return lagrange_sum<6>(samples, at);
    }
}

void smooth(std::span<const double> f, std::span<double> out) {
    SLC_ASSERT(out.size() == f.size(), "one output per sample");
    const std::size_t n = f.size();
    if (n == 0) return;
    out[0] = f[0];
    out[n - 1] = f[n - 1];
    for (std::size_t k = 1; k + 1 < n; ++k) out[k] = 0.25 * (f[k - 1] + 2.0 * f[k] + f[k + 1]);
}

}  // namespace slc::eno
