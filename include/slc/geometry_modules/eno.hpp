/// @file
/// One-dimensional ENO kernels on a uniform line of samples (paper §3.2, after Harten, Engquist,
/// Osher and Chakravarthy [10]): differentiation at the nodes, interpolation between them, and the
/// cosine (1-2-1) smoothing pass. The embedded geometry module applies them along the x- and
/// y-intervals of its local mesh.
///
/// An ENO stencil of order E holds E + 1 consecutive samples. It is grown one point at a time from
/// its starting points ({k} for a derivative at node k, {i, i + 1} for interpolation in [x_i,
/// x_{i+1}]), each time on the side where the next undivided difference is smaller in magnitude, so
/// that it avoids the kinks of the data (Eq. 10 oscillates when its stencil crosses one). A
/// stencil never leaves the line: near an end it is one-sided, with the same order as long as the
/// line holds E + 1 samples (fewer samples lower the order to what they allow).
#pragma once

#include <cstddef>
#include <span>

/// One-dimensional ENO kernels on a uniform line of samples (paper §3.2).
namespace slc::eno {

/// Highest ENO order supported (stencils of up to max_order + 1 samples).
inline constexpr int max_order = 5;

/// The stencil chosen by the ENO rule: samples [first, first + points).
struct Stencil {
    std::size_t first = 0;  ///< index of its first sample
    int points = 0;         ///< its number of samples, order + 1 unless the line is shorter
};

/// Grows the stencil [lo, hi] (0 <= lo <= hi < f.size()) by the ENO rule until it holds
/// order + 1 samples or the whole line. A tie between the two sides goes to the side that keeps
/// the stencil centred, so that symmetric data gives symmetric stencils. O(order²).
Stencil stencil(std::span<const double> f, std::size_t lo, std::size_t hi, int order);

/// The derivative at every node of samples f (spacing h > 0) by ENO differences of order
/// `order` (1..max_order): exact for polynomials of degree `order`, error O(h^order) for smooth
/// f. out.size() == f.size(); a line of one sample has derivative 0. O(n order²).
///
/// `bias` > 1 biases the rule (after Shu's biased ENO): each point joins on a preferred side
/// unless the other side's difference is smaller by more than the factor `bias`, the preferred
/// side being the one that brings the stencil nearer its node's centre, and where both leave it
/// equally far off, the left one in one rule and the right one in another; the derivative is
/// the mean of the two rules' (one where their stencils agree), so that no direction is
/// preferred. 1 is the plain rule. A bias keeps the stencils of neighbouring nodes alike across
/// a kink of small angle, where the two differences are nearly equal and the plain rule's
/// choice flips with the kink's place between the nodes; a kink of large angle (a medial axis)
/// is still avoided. It costs a second stencil per node.
void derivative(std::span<const double> f, double h, int order, std::span<double> out,
                double bias = 1.0);

/// The ENO interpolant of order `order` (degree `order`, 1..max_order) at x_i + theta·h,
/// 0 <= i < f.size() − 1 and theta in [0, 1]: exact for polynomials of degree `order`, error
/// O(h^(order+1)) for smooth f. O(order²).
double interpolate(std::span<const double> f, std::size_t i, double theta, int order);

/// interpolate() once the stencil is known: the polynomial through the samples of s at
/// x_i + theta·h, for callers that reuse the stencil of interval i (it does not depend on theta).
/// O(s.points).
double interpolate(std::span<const double> f, const Stencil& s, std::size_t i, double theta);

/// One pass of cosine smoothing, out_k = (f_{k−1} + 2 f_k + f_{k+1}) / 4, which multiplies the
/// Fourier mode e^{iξx} by cos²(ξh/2): the sawtooth is removed, smooth data moves by
/// (h²/4) f'' + O(h⁴). The two end samples are copied unchanged. out.size() == f.size(), and out
/// must not alias f.
void smooth(std::span<const double> f, std::span<double> out);

}  // namespace slc::eno
