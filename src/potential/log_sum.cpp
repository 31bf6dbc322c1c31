// The fast multipole method of logarithmic potentials (log_sum.hpp). The expansions are scaled
// by the boxes' radii (a_k of (r/(z − c))^k, b_l of ((z − c)/r)^l), so that no power of a small
// box's size underflows; with radii that bound their children's (r ≥ |c' − c| + r'), every
// translation's terms are at most the sum they make, and no digits are lost to cancellation.
#include "log_sum.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>

#include "slc/core/parallel.hpp"

namespace slc::detail {
namespace {

using Complex = std::complex<double>;

/// Two boxes interact through their expansions when their radii sum to at most this fraction of
/// the distance between their centres: the truncation after p terms is then below 2 · 0.5^{p+1}.
constexpr double separation = 0.5;
/// Boxes of at most this many points are not split.
constexpr std::size_t leaf_size = 64;
/// Boxes this deep are not split (coincident points).
constexpr int max_depth = 52;

/// The number of terms p' after which ρ^{p'+1}/(1 − ρ) is below tol (ρ < 1).
std::size_t terms_for(double rho, double tol) {
    if (!(rho > 0.0)) return 1;
    return static_cast<std::size_t>(
        std::max(1.0, std::ceil(std::log(tol * (1.0 - rho)) / std::log(rho)) - 1.0));
}

/// 1/z without the library's checks for infinities (z is never 0 or infinite here).
Complex inverse(Complex z) { return std::conj(z) / std::norm(z); }

}  // namespace

LogSum::LogSum(std::span<const Vec2> points, std::span<const std::size_t> group, double tolerance)
    : tolerance_(tolerance), terms_(terms_for(separation, tolerance)) {
    const std::size_t n = points.size();
    const std::size_t width = 2 * terms_ + 1;
    binomial_.assign(width * width, 0.0);
    for (std::size_t a = 0; a < width; ++a) {
        binomial_[a * width] = 1.0;
        for (std::size_t b = 1; b <= a; ++b)
            binomial_[a * width + b] =
                binomial_[(a - 1) * width + b - 1] + (b < a ? binomial_[(a - 1) * width + b] : 0.0);
    }
    m2l_.assign((terms_ + 1) * (terms_ + 1), 0.0);
    for (std::size_t l = 1; l <= terms_; ++l)
        for (std::size_t k = 1; k <= terms_; ++k)
            m2l_[k * (terms_ + 1) + l] = binomial_[(l + k - 1) * width + k - 1];
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    // Points group by group (stable: each group's points in input order), then a tree for each.
    if (!group.empty())
        std::stable_sort(order_.begin(), order_.end(),
                         [&](std::size_t a, std::size_t b) { return group[a] < group[b]; });
    points_.resize(n);
    for (std::size_t k = 0; k < n; ++k) points_[k] = {points[order_[k]].x, points[order_[k]].y};
    nodes_.reserve(2 * n / leaf_size + 8);
    std::vector<std::size_t> roots;
    for (std::size_t first = 0; first < n;) {
        std::size_t last = first + 1;
        while (last < n && (group.empty() || group[order_[last]] == group[order_[first]])) ++last;
        double lo_x = points_[first].real(), hi_x = lo_x, lo_y = points_[first].imag(), hi_y = lo_y;
        for (std::size_t k = first; k < last; ++k) {
            lo_x = std::min(lo_x, points_[k].real());
            hi_x = std::max(hi_x, points_[k].real());
            lo_y = std::min(lo_y, points_[k].imag());
            hi_y = std::max(hi_y, points_[k].imag());
        }
        const double half = 0.5 * std::max(hi_x - lo_x, hi_y - lo_y);
        roots.push_back(
            build(first, last - first, {0.5 * (lo_x + hi_x), 0.5 * (lo_y + hi_y)}, half, 0));
        first = last;
    }
    for (std::size_t b = 0; b < nodes_.size(); ++b) {
        const auto depth = static_cast<std::size_t>(nodes_[b].depth);
        if (levels_.size() <= depth) levels_.resize(depth + 1);
        levels_[depth].push_back(b);
        if (nodes_[b].leaf) leaves_.push_back(b);
    }
    far_.resize(nodes_.size());
    near_.resize(nodes_.size());
    for (const std::size_t root : roots) interact(root, root);
}

void LogSum::take_near_logs() const {
    const std::size_t n = points_.size();
    // log|z_i − z_k| for every point i and every point k ≠ i of the leaves near i's, in the
    // order the sums take them: each sum of potentials reads them instead of taking the logs (a
    // sum of fields alone, as K′'s, never needs them).
    near_log_offset_.assign(n + 1, 0);
    for (const std::size_t leaf : leaves_) {
        std::size_t pairs = 0;
        for (const std::size_t s : near_[leaf]) pairs += nodes_[s].count;
        const Node& node = nodes_[leaf];
        for (std::size_t i = node.first; i < node.first + node.count; ++i)
            near_log_offset_[i + 1] = pairs - 1;  // less i itself
    }
    for (std::size_t i = 0; i < n; ++i) near_log_offset_[i + 1] += near_log_offset_[i];
    near_log_.resize(near_log_offset_[n]);
    parallel_for(
        leaves_.size(),
        [&](std::size_t l) {
            const Node& node = nodes_[leaves_[l]];
            for (std::size_t i = node.first; i < node.first + node.count; ++i) {
                double* logs = near_log_.data() + near_log_offset_[i];
                for (const std::size_t s : near_[leaves_[l]])
                    for (std::size_t k = nodes_[s].first; k < nodes_[s].first + nodes_[s].count;
                         ++k)
                        if (k != i) *logs++ = 0.5 * std::log(std::norm(points_[i] - points_[k]));
            }
        },
        expensive_grain);
}

std::size_t LogSum::build(std::size_t first, std::size_t count, Complex centre, double half,
                          int depth) {
    const std::size_t index = nodes_.size();
    nodes_.emplace_back();
    nodes_[index].centre = centre;
    nodes_[index].first = first;
    nodes_[index].count = count;
    nodes_[index].depth = depth;
    if (count <= leaf_size || depth >= max_depth || !(half > 0.0)) {
        double radius = 0.0;
        for (std::size_t k = first; k < first + count; ++k)
            radius = std::max(radius, std::abs(points_[k] - centre));
        // Never 0: a box's expansions are scaled by its radius.
        radius = std::max(radius, 1e-3 * half);
        nodes_[index].radius = radius > 0.0 ? radius : 1.0;
        return index;
    }
    // The quadrants in the order (−,−), (+,−), (−,+), (+,+), each keeping its points' order.
    const auto quadrant = [&](std::size_t k) {
        return (points_[k].real() >= centre.real() ? 1 : 0) +
               (points_[k].imag() >= centre.imag() ? 2 : 0);
    };
    std::vector<std::size_t> slot;
    slot.reserve(count);
    std::size_t starts[5] = {0, 0, 0, 0, count};
    for (int q = 0; q < 4; ++q) {
        starts[q] = slot.size();
        for (std::size_t k = first; k < first + count; ++k)
            if (quadrant(k) == q) slot.push_back(k);
    }
    std::vector<Complex> moved(count);
    std::vector<std::size_t> moved_order(count);
    for (std::size_t k = 0; k < count; ++k) {
        moved[k] = points_[slot[k]];
        moved_order[k] = order_[slot[k]];
    }
    std::copy(moved.begin(), moved.end(), points_.begin() + static_cast<std::ptrdiff_t>(first));
    std::copy(moved_order.begin(), moved_order.end(),
              order_.begin() + static_cast<std::ptrdiff_t>(first));
    nodes_[index].leaf = false;
    const double quarter = 0.5 * half;
    double radius = 0.0;
    for (int q = 0; q < 4; ++q) {
        const std::size_t c = starts[q + 1] - starts[q];
        if (c == 0) continue;
        const Complex offset{(q & 1) ? quarter : -quarter, (q & 2) ? quarter : -quarter};
        const std::size_t child = build(first + starts[q], c, centre + offset, quarter, depth + 1);
        nodes_[index].children[q] = child;
        nodes_[child].parent = index;
        radius = std::max(radius, std::abs(nodes_[child].centre - centre) + nodes_[child].radius);
    }
    nodes_[index].radius = radius;
    return index;
}

void LogSum::interact(std::size_t target, std::size_t source) {
    const Node& a = nodes_[target];
    const Node& b = nodes_[source];
    if (a.radius + b.radius <= separation * std::abs(a.centre - b.centre)) {
        far_[target].push_back(source);
    } else if (a.leaf && b.leaf) {
        near_[target].push_back(source);
    } else if (b.leaf || (!a.leaf && a.radius >= b.radius)) {
        for (const std::size_t child : a.children)
            if (child != 0) interact(child, source);
    } else {
        for (const std::size_t child : b.children)
            if (child != 0) interact(target, child);
    }
}

void LogSum::sum(std::span<const double> q_in, std::span<double> potential,
                 std::span<Vec2> field) const {
    const std::size_t n = points_.size(), p = terms_, stride = p + 1, width = 2 * p + 1;
    const auto binomial = [&](std::size_t a, std::size_t b) { return binomial_[a * width + b]; };
    if (!potential.empty()) std::call_once(near_logs_taken_, [this] { take_near_logs(); });
    std::vector<double> q(n);
    for (std::size_t k = 0; k < n; ++k) q[k] = q_in[order_[k]];
    // Multipoles: [0] = Q = Σ q_j, [k] = a_k = −Σ q_j ((z_j − c)/r)^k / k.
    std::vector<Complex> multipole(nodes_.size() * stride), local(nodes_.size() * stride);
    parallel_for(
        leaves_.size(),
        [&](std::size_t l) {
            const Node& node = nodes_[leaves_[l]];
            Complex* m = multipole.data() + leaves_[l] * stride;
            for (std::size_t k = node.first; k < node.first + node.count; ++k) {
                m[0] += q[k];
                const Complex w = (points_[k] - node.centre) / node.radius;
                Complex power = w;
                for (std::size_t t = 1; t <= p; ++t, power *= w)
                    m[t] -= q[k] * power / static_cast<double>(t);
            }
        },
        expensive_grain);
    // Upward: each box's expansion from its children's, deepest first. About the parent's centre
    // c, z0 = c' − c: b_l = −Q (z0/r)^l / l + Σ_{k≤l} a'_k (r'/r)^k (z0/r)^{l−k} C(l−1, k−1).
    for (std::size_t depth = levels_.size(); depth-- > 0;) {
        const std::vector<std::size_t>& level = levels_[depth];
        parallel_for(
            level.size(),
            [&](std::size_t i) {
                const Node& node = nodes_[level[i]];
                if (node.leaf) return;
                Complex* m = multipole.data() + level[i] * stride;
                std::vector<Complex> u_power(p + 1), s_a(p + 1);
                for (const std::size_t child : node.children) {
                    if (child == 0) continue;
                    const Complex* a = multipole.data() + child * stride;
                    const Complex u = (nodes_[child].centre - node.centre) / node.radius;
                    const double s = nodes_[child].radius / node.radius;
                    u_power[0] = 1.0;
                    for (std::size_t t = 1; t <= p; ++t) u_power[t] = u_power[t - 1] * u;
                    double s_power = 1.0;
                    for (std::size_t k = 1; k <= p; ++k) {
                        s_power *= s;
                        s_a[k] = a[k] * s_power;
                    }
                    m[0] += a[0];
                    for (std::size_t l = 1; l <= p; ++l) {
                        Complex b = -a[0] * u_power[l] / static_cast<double>(l);
                        for (std::size_t k = 1; k <= l; ++k)
                            b += s_a[k] * u_power[l - k] * binomial(l - 1, k - 1);
                        m[l] += b;
                    }
                }
            },
            expensive_grain);
    }
    // Across: each box's local expansion from its far sources. About the target's centre c_t,
    // z0 = c_s − c_t, α_k = a_k (−r_s/z0)^k, v = r_t/z0: b_0 = Q log|z0| + Σ α_k,
    // b_l = v^l (−Q/l + Σ_k α_k C(l + k − 1, k − 1)).
    parallel_for(
        nodes_.size(),
        [&](std::size_t t) {
            if (far_[t].empty()) return;
            const Node& target = nodes_[t];
            Complex* b = local.data() + t * stride;
            std::vector<Complex> alpha(p + 1);
            std::vector<double> re(p + 1), im(p + 1);
            for (const std::size_t s : far_[t]) {
                const Node& source = nodes_[s];
                const Complex* a = multipole.data() + s * stride;
                const Complex z0 = source.centre - target.centre;
                const Complex inverse_z0 = inverse(z0);
                const Complex u = -source.radius * inverse_z0, v = target.radius * inverse_z0;
                // The terms this pair needs: ρ^{p'+1}/(1 − ρ) below the tolerance,
                // ρ = (r_s + r_t)/|z0| ≤ 1/2.
                const std::size_t kept = std::min(
                    p, terms_for((source.radius + target.radius) / std::abs(z0), tolerance_));
                Complex power = u, sum = 0.0;
                for (std::size_t k = 1; k <= kept; ++k, power *= u) {
                    alpha[k] = a[k] * power;
                    sum += alpha[k];
                }
                b[0] += a[0] * 0.5 * std::log(std::norm(z0)) + sum;
                // Σ_k α_k C(l + k − 1, k − 1) for every l at once, k outermost (vectorised).
                std::fill(re.begin(), re.end(), 0.0);
                std::fill(im.begin(), im.end(), 0.0);
                for (std::size_t k = 1; k <= kept; ++k) {
                    const double* c = m2l_.data() + k * stride;  // C(l + k − 1, k − 1) at l
                    const double ar = alpha[k].real(), ai = alpha[k].imag();
                    for (std::size_t l = 1; l <= kept; ++l) {
                        re[l] += ar * c[l];
                        im[l] += ai * c[l];
                    }
                }
                Complex v_power = v;
                for (std::size_t l = 1; l <= kept; ++l, v_power *= v)
                    b[l] += v_power * (Complex{re[l], im[l]} - a[0] / static_cast<double>(l));
            }
        },
        expensive_grain);
    // Downward: each box's local expansion shifted to its children. About the child's centre,
    // z1 = c' − c: b'_m = Σ_{l≥m} b_l C(l, m) (r'/r)^m (z1/r)^{l−m}.
    for (std::size_t depth = 1; depth < levels_.size(); ++depth) {
        const std::vector<std::size_t>& level = levels_[depth];
        parallel_for(
            level.size(),
            [&](std::size_t i) {
                const Node& node = nodes_[level[i]];
                const Node& parent = nodes_[node.parent];
                const Complex* b = local.data() + node.parent * stride;
                Complex* own = local.data() + level[i] * stride;
                std::vector<Complex> u_power(p + 1);
                const Complex u = (node.centre - parent.centre) / parent.radius;
                const double s = node.radius / parent.radius;
                u_power[0] = 1.0;
                for (std::size_t t = 1; t <= p; ++t) u_power[t] = u_power[t - 1] * u;
                double s_power = 1.0;
                for (std::size_t m = 0; m <= p; ++m, s_power *= s) {
                    Complex sum = 0.0;
                    for (std::size_t l = m; l <= p; ++l)
                        sum += b[l] * u_power[l - m] * binomial(l, m);
                    own[m] += sum * s_power;
                }
            },
            expensive_grain);
    }
    // Each leaf's points: the local expansion, and the leaves near it directly.
    const auto evaluate = [&]<bool with_potential, bool with_field>() {
        parallel_for(
            leaves_.size(),
            [&](std::size_t l) {
                const std::size_t leaf = leaves_[l];
                const Node& node = nodes_[leaf];
                const Complex* b = local.data() + leaf * stride;
                for (std::size_t i = node.first; i < node.first + node.count; ++i) {
                    const Complex z = points_[i];
                    // Φ = Σ b_l w^l and Φ' = Σ l b_l w^{l−1} / r, w = (z − c)/r.
                    const Complex w = (z - node.centre) / node.radius;
                    Complex phi = 0.0, slope = 0.0;
                    for (std::size_t t = p; t > 0; --t) {
                        if constexpr (with_potential) phi = phi * w + b[t];
                        if constexpr (with_field) slope = slope * w + static_cast<double>(t) * b[t];
                    }
                    double value = (phi * w + b[0]).real();
                    Complex derivative = slope / node.radius;  // Σ q_j / (z − z_j)
                    const double* logs = near_log_.data() + near_log_offset_[i];
                    for (const std::size_t s : near_[leaf]) {
                        const Node& source = nodes_[s];
                        for (std::size_t k = source.first; k < source.first + source.count; ++k) {
                            if (k == i) continue;
                            if constexpr (with_potential) value += q[k] * *logs++;
                            if constexpr (with_field) {
                                const Complex e = z - points_[k];
                                derivative += q[k] * std::conj(e) / std::norm(e);
                            }
                        }
                    }
                    const std::size_t out = order_[i];
                    if constexpr (with_potential) potential[out] = value;
                    // (x − y)/|x − y|² is the conjugate of 1/(z − w).
                    if constexpr (with_field) field[out] = {derivative.real(), -derivative.imag()};
                }
            },
            expensive_grain);
    };
    if (!potential.empty() && !field.empty())
        evaluate.template operator()<true, true>();
    else if (!potential.empty())
        evaluate.template operator()<true, false>();
    else if (!field.empty())
        evaluate.template operator()<false, true>();
}

}  // namespace slc::detail
