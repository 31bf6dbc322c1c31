// The weighted mean of vertex values, internal to the geometry modules: the arc-length mean over
// curves and the area mean over a surface (the C̄ of the volume-preserving flow, paper Eq. 13)
// differ only in their weights.
#pragma once

#include <cstddef>
#include <span>

namespace slc {

/// Σ g_i w_i / Σ w_i, both sums in vertex order. Precondition: g.size() == w.size() > 0 and
/// Σ w_i > 0. O(n).
inline double weighted_mean(std::span<const double> g, std::span<const double> w) {
    double integral = 0.0, total = 0.0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        integral += g[i] * w[i];
        total += w[i];
    }
    return integral / total;
}

}  // namespace slc
