/// @file
/// Potentials harmonic off closed curves, from their values on the curves (boundary integral
/// equations; docs/algorithms/potential.md): what the Mullins–Sekerka law of coarsening needs
/// (laws in slc/velocity/potential_laws.hpp).
///
/// Each curve is first made smooth and periodic: a periodic cubic spline through its vertices,
/// parameterised by chord length, sampled at M points equally spaced in τ ∈ [0, 2π), the curvature
/// at each sample fitted to the nine nearest vertices (degree 6, error O(h⁵)). On that
/// sampling the single-layer potential S of the logarithm is discretised with Kress's product
/// quadrature for the logarithmic singularity (spectrally accurate on smooth curves: R. Kress,
/// Linear Integral Equations, §12.3) and the trapezoidal rule between curves. Values at the
/// curves' own vertices are read back by trigonometric interpolation in τ.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// Closed curves sampled smoothly: sample j of curve c is at τ_j = 2πj/M_c on a periodic cubic
/// spline through the curve's vertices (chord-length parameter s = Lτ/2π). Samples of all curves
/// are stored flat, curve after curve, as Interface stores vertices.
struct SmoothCurves {
    std::vector<std::size_t> offsets;  ///< first sample of each curve; back() = sample count
    std::vector<double> length;        ///< L_c, the length of each curve's spline polygon
    std::vector<double> area;          ///< the signed area of each curve's polygon (ccw > 0)
    std::vector<Vec2> x;               ///< γ(τ_j)
    std::vector<double> speed;         ///< |γ'(τ_j)|, τ-derivative
    std::vector<Vec2> normal;          ///< outward unit normal N (right of the direction of travel)
    /// C = −∇·N (−1/R on a counterclockwise circle), of a polynomial of degree 6 fitted to the
    /// nine vertices nearest the sample (the spline's own where the curve has fewer than 12)
    std::vector<double> curvature;
    /// The first vertex of each curve in Interface::points(); back() = vertex count.
    std::vector<std::size_t> vertex_offsets;
    /// τ of each vertex of the curves, indexed like Interface::points().
    std::vector<double> vertex_tau;
    /// The outward unit normal of the spline at each vertex, indexed like Interface::points().
    std::vector<Vec2> vertex_normal;

    /// Number of samples of curve c.
    std::size_t count(std::size_t c) const { return offsets[c + 1] - offsets[c]; }
    /// Number of curves.
    std::size_t curve_count() const { return offsets.size() - 1; }
};

/// The smooth sampling of every curve of `curves`: M_c = max(min_samples, the even number at or
/// above samples_per_vertex times the curve's vertex count) samples. O(total samples + vertices).
/// Throws InvalidInput when two consecutive vertices coincide.
SmoothCurves smooth_curves(const Interface& curves, double samples_per_vertex = 1.0,
                           std::size_t min_samples = 32);

/// ∫_c g ds over each curve c of the periodic samples g (trapezoidal rule in τ: spectrally
/// accurate for smooth g).
std::vector<double> curve_integrals(const SmoothCurves& s, std::span<const double> g);

/// The values at the vertices of curve c (vertex_tau) of the trigonometric interpolant of the
/// periodic samples g of that curve (g.size() == count(c)). O(M_c · vertices of c).
std::vector<double> interpolate_at_vertices(const SmoothCurves& s, std::size_t c,
                                            std::span<const double> g);

/// The exterior–interior problem of two-phase Mullins–Sekerka: u harmonic off the curves,
/// u = f on them, bounded at infinity. Written as u = Sμ + u∞ with ∫μ ds = 0, μ the single layer's
/// density, which is the jump of the normal derivative: ∂u_out/∂N − ∂u_in/∂N = −μ.
/// With groups of curves (interior problems, one per region: Hele-Shaw), each group is solved
/// alone, its own constant and ∫μ ds = 0 over its own curves: u = S_g μ + c_g inside it.
struct SingleLayerSolution {
    std::vector<double> density;    ///< μ at the samples
    double u_infinity = 0.0;        ///< the value of u at infinity (the first group's constant)
    std::vector<double> constants;  ///< c_g of each group
    int iterations = 0;             ///< GMRES iterations, or 0 for the direct solve
};

/// How the single-layer and adjoint double-layer operators are summed: as dense matrices
/// (O(M²) memory and work), by the fast summation (a treecode of the logarithm and, on each curve,
/// Kress's correction to the trapezoidal rule by FFT: O(M) memory, O(M log M) work, products
/// accurate to about 1e−14 relative), or dense up to 3,000 samples and fast beyond (automatic).
enum class Summation { automatic, dense, fast };

/// The single-layer system of curves s, set up once for as many boundary values f as wanted:
/// Sμ + u∞ = f at the samples with ∫μ ds = 0. Dense: a direct LU solve up to 600 samples, Eigen's
/// GMRES beyond to a relative residual of 1e−13, O(M²) memory, refused (NumericalFailure) beyond
/// 10,000 samples (800 MB). Fast: GMRES to 1e−12 over the fast summation. GMRES is preconditioned
/// by each curve's own block (O(Σ M_c³) to set up) and the curves' charges. group: the group of
/// each curve (0, 1, …), curves of different groups not seen by each other; empty: one group.
/// s must outlive the system.
class SingleLayerSystem {
public:
    explicit SingleLayerSystem(const SmoothCurves& s, std::span<const std::size_t> group = {},
                               Summation how = Summation::automatic);
    ~SingleLayerSystem();
    SingleLayerSystem(const SingleLayerSystem&) = delete;
    SingleLayerSystem& operator=(const SingleLayerSystem&) = delete;

    /// One solution per f (f.size() == s.x.size()). Throws NumericalFailure when GMRES does not
    /// converge.
    std::vector<SingleLayerSolution> solve(std::span<const std::vector<double>> fs) const;

    /// Whether the system is summed fast.
    bool sums_fast() const;

private:
    struct Factored;
    const SmoothCurves& s_;
    std::size_t groups_ = 1;
    std::unique_ptr<Factored> factored_;
};

/// One f solved on one system, for one group.
SingleLayerSolution solve_single_layer(const SmoothCurves& s, std::span<const double> f);

/// The solution of the small dense system a x = b (a row-major, b.size() unknowns) by Eigen's
/// fully pivoted LU, or nothing when a is singular.
std::optional<std::vector<double>> solve_dense(std::span<const double> a,
                                               std::span<const double> b);

/// The single-layer operator's matrix A, row-major, A[i·n + j] the weight of φ_j = μ_j |γ'(τ_j)|
/// in (Sμ)(x_i): Kress's quadrature on a sample's own curve, the trapezoidal rule on others.
/// For tests and for the solver.
std::vector<double> single_layer_matrix(const SmoothCurves& s);

/// The single-layer operator's product with φ (φ_j = μ_j |γ'(τ_j)|) by the fast summation: the
/// product of single_layer_matrix(s) with φ to about 1e−14 relative. O(M log M).
std::vector<double> apply_single_layer(const SmoothCurves& s, std::span<const double> phi);

/// K'μ at the samples: the adjoint double layer ∫ ∂G(x_i, y)/∂N(x_i) μ(y) ds_y of the density μ
/// (trapezoidal rule; its kernel is smooth, C(x)/4π on the diagonal). The normal derivatives of
/// u = Sμ are ∂u_out/∂N = K'μ − μ/2 and ∂u_in/∂N = K'μ + μ/2. O(M²) dense, O(M log M) fast.
/// group: as SingleLayerSystem's, curves of other groups not seen; empty: one group.
std::vector<double> adjoint_double_layer(const SmoothCurves& s, std::span<const double> density,
                                         std::span<const std::size_t> group = {},
                                         Summation how = Summation::automatic);

/// Multiplies each Fourier mode m of the periodic samples g of curve c by filter(ξ), ξ = 2π|m|/L_c
/// the mode's wavenumber in arc length. O(M_c log M_c).
void filter_modes(const SmoothCurves& s, std::size_t c, std::span<double> g,
                  const std::function<double(double)>& filter);

}  // namespace slc
