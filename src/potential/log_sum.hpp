/// @file
/// Sums of logarithmic potentials over many points in O(M log M): the fast summation of the
/// boundary integral operators beyond a few thousand samples (docs/algorithms/potential.md).
#pragma once

#include <complex>
#include <cstddef>
#include <mutex>
#include <span>
#include <vector>

#include "slc/core/vec2.hpp"

namespace slc::detail {

/// Charges q_j at points x_j, summed at the points themselves: the potential
/// Σ_{j≠i} q_j log|x_i − x_j| and the field Σ_{j≠i} q_j (x_i − x_j)/|x_i − x_j|², over the points
/// of i's own group only.
///
/// A fast multipole method (Greengard and Rokhlin's complex expansions, lists of interactions by a
/// dual traversal of the tree): each group's points in an adaptive quadtree (leaves of at most 64
/// points), each box with its multipole expansion Q log(z − c) + Σ_k a_k (r/(z − c))^k about its
/// centre c (r its radius, bounding its points); two boxes whose radii sum to ρ ≤ 1/2 of the
/// distance between their centres interact through their expansions, truncated after the p terms
/// that bring ρ^{p+1}/(1 − ρ) below `tolerance` (relative to the charges' Σ|q|); other pairs of
/// leaves directly. The lists are built once, O(M log M), and the logarithms of the near pairs
/// at the first sum of potentials (about 500 a point on curves: 4 kB); a sum is
/// O(M (p²/64 + 500)), and each point's value is summed in one order whatever the number of
/// threads. One sum at a time.
class LogSum {
public:
    /// group: the group of each point (0, 1, …), or empty for one group.
    explicit LogSum(std::span<const Vec2> points, std::span<const std::size_t> group = {},
                    double tolerance = 1e-14);

    /// The potential and the field at every point of the charges q (q.size() == points).
    /// Either output may be empty, and is then not computed.
    void sum(std::span<const double> q, std::span<double> potential, std::span<Vec2> field) const;

private:
    struct Node {
        std::complex<double> centre;
        double radius = 0.0;                     // bounds |z − centre| over its points
        std::size_t first = 0, count = 0;        // its points: order_[first, first + count)
        std::size_t children[4] = {0, 0, 0, 0};  // 0: none (the root is nobody's child)
        std::size_t parent = 0;
        int depth = 0;
        bool leaf = true;
    };
    std::size_t build(std::size_t first, std::size_t count, std::complex<double> centre,
                      double half, int depth);
    void interact(std::size_t target, std::size_t source);

    std::vector<std::complex<double>> points_;  // in tree order
    std::vector<std::size_t> order_;            // the input index of each point in tree order
    std::vector<Node> nodes_;
    std::vector<std::vector<std::size_t>> levels_;  // the nodes of each depth
    std::vector<std::vector<std::size_t>> far_;     // each node's sources through expansions
    std::vector<std::vector<std::size_t>> near_;    // each leaf's leaves summed directly
    std::vector<std::size_t> leaves_;
    // log|z_i − z_k| over each point's near leaves, and where point i's begin (tree order):
    // taken at the first sum of potentials.
    void take_near_logs() const;
    mutable std::once_flag near_logs_taken_;
    mutable std::vector<double> near_log_;
    mutable std::vector<std::size_t> near_log_offset_;
    double tolerance_;
    std::size_t terms_;             // p, the most terms a pair takes
    std::vector<double> binomial_;  // C(n, k) at n·(2p + 1) + k, n, k ≤ 2p
    std::vector<double> m2l_;       // C(l + k − 1, k − 1) at k·(p + 1) + l, l, k ≤ p
};

}  // namespace slc::detail
