// Closed curves made smooth (periodic cubic splines sampled evenly), the single-layer potential of
// the logarithm on them by Kress's quadrature, and its first-kind equation solved by Eigen.
#include "slc/potential/boundary_integral.hpp"

#include <fmt/format.h>

// Results must not depend on the number of threads: Eigen's own threading stays off; the
// matrix is assembled by slc's parallel_for, one entry per iteration.
#define EIGEN_DONT_PARALLELIZE
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <unsupported/Eigen/FFT>
#include <unsupported/Eigen/IterativeSolvers>

#include "log_sum.hpp"
#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc::detail {

/// The single-layer system's matrix, row by row contiguous.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A square operator as GMRES sees it: its product with a vector is apply(x, y), y = A x, the
/// dense matrix's a row per iteration of slc's parallel_for or the fast summation's, either the
/// same whatever the number of threads (Eigen's own product runs on one core).
class LinearOperator;

}  // namespace slc::detail

namespace Eigen::internal {
template <>
struct traits<slc::detail::LinearOperator> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace slc::detail {

class LinearOperator : public Eigen::EigenBase<LinearOperator> {
public:
    using Scalar = double;
    using RealScalar = double;
    using StorageIndex = int;
    using Apply = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;
    enum {
        ColsAtCompileTime = Eigen::Dynamic,
        MaxColsAtCompileTime = Eigen::Dynamic,
        IsRowMajor = false
    };
    LinearOperator(Eigen::Index n, Apply apply) : n_(n), apply_(std::move(apply)) {}
    Eigen::Index rows() const { return n_; }
    Eigen::Index cols() const { return n_; }
    template <class Rhs>
    Eigen::Product<LinearOperator, Rhs, Eigen::AliasFreeProduct> operator*(
        const Eigen::MatrixBase<Rhs>& x) const {
        return Eigen::Product<LinearOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
    }
    void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { apply_(x, y); }

private:
    Eigen::Index n_;
    Apply apply_;
};

}  // namespace slc::detail

namespace Eigen::internal {
template <class Rhs>
struct generic_product_impl<slc::detail::LinearOperator, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<slc::detail::LinearOperator, Rhs,
                                generic_product_impl<slc::detail::LinearOperator, Rhs>> {
    using Scalar = typename Product<slc::detail::LinearOperator, Rhs>::Scalar;
    template <class Dest>
    static void scaleAndAddTo(Dest& dst, const slc::detail::LinearOperator& lhs, const Rhs& rhs,
                              const Scalar& alpha) {
        const Eigen::VectorXd x = rhs;
        Eigen::VectorXd y(x.size());
        lhs.apply(x, y);
        dst += alpha * y;
    }
};
}  // namespace Eigen::internal

namespace slc {

using detail::LinearOperator;
using detail::RowMajorMatrix;
namespace {

using std::numbers::pi;

/// Vertices closer than this fraction of a curve's mean spacing to the vertex before are left
/// out of its spline (their values are still read back at their place).
constexpr double min_vertex_gap = 0.01;

/// Beyond this many samples the dense system (8 bytes times its square: 800 MB) is refused.
constexpr std::size_t max_samples = 10000;

/// Up to this many samples the equation is solved by LU, beyond it by GMRES.
constexpr std::size_t direct_solve_limit = 600;

/// Beyond this many samples the operators are summed fast (Summation::automatic).
constexpr std::size_t fast_summation_from = 3000;

/// GMRES's relative residual over the dense matrix, and over the fast summation (whose products
/// are accurate to about 1e−14 relative).
constexpr double dense_tolerance = 1e-13;
constexpr double fast_tolerance = 1e-12;

/// Solves the cyclic tridiagonal system a_i x_{i−1} + b_i x_i + c_i x_{i+1} = r_i (indices mod
/// n, n ≥ 3), diagonally dominant, by the Sherman–Morrison form of the Thomas algorithm.
std::vector<double> solve_cyclic(const std::vector<double>& a, const std::vector<double>& b,
                                 const std::vector<double>& c, const std::vector<double>& r) {
    const std::size_t n = b.size();
    const double alpha = a[0], beta = c[n - 1], gamma = -b[0];
    std::vector<double> bb = b;
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    auto thomas = [&](std::vector<double> d) {
        std::vector<double> cp(n);
        cp[0] = c[0] / bb[0];
        d[0] /= bb[0];
        for (std::size_t i = 1; i < n; ++i) {
            const double m = bb[i] - a[i] * cp[i - 1];
            cp[i] = c[i] / m;
            d[i] = (d[i] - a[i] * d[i - 1]) / m;
        }
        for (std::size_t i = n - 1; i-- > 0;) d[i] -= cp[i] * d[i + 1];
        return d;
    };
    std::vector<double> x = thomas(r);
    std::vector<double> u(n, 0.0);
    u[0] = gamma;
    u[n - 1] = beta;
    const std::vector<double> z = thomas(u);
    const double f = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
    for (std::size_t i = 0; i < n; ++i) x[i] -= f * z[i];
    return x;
}

/// A periodic cubic spline through points p_i at chord-length knots s_i, of period L.
class PeriodicSpline {
public:
    explicit PeriodicSpline(std::span<const Vec2> p) : p_(p.begin(), p.end()) {
        const std::size_t n = p.size();
        s_.resize(n + 1);
        s_[0] = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double h = norm(p[(i + 1) % n] - p[i]);
            if (!(h > 0.0))
                throw InvalidInput(fmt::format(
                    "a curve's vertices {} and {} coincide at ({}, {}): no smooth curve through "
                    "them",
                    i, (i + 1) % n, p[i].x, p[i].y));
            s_[i + 1] = s_[i] + h;
        }
        std::vector<double> a(n), b(n), c(n), rx(n), ry(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t im = (i + n - 1) % n, ip = (i + 1) % n;
            const double hm = h(im), hp = h(i);
            a[i] = hm;
            b[i] = 2.0 * (hm + hp);
            c[i] = hp;
            const Vec2 r = 6.0 * ((p[ip] - p[i]) / hp - (p[i] - p[im]) / hm);
            rx[i] = r.x;
            ry[i] = r.y;
        }
        const std::vector<double> mx = solve_cyclic(a, b, c, rx), my = solve_cyclic(a, b, c, ry);
        m_.resize(n);
        for (std::size_t i = 0; i < n; ++i) m_[i] = {mx[i], my[i]};
    }

    /// The period L (the polygon's length).
    double length() const { return s_.back(); }
    /// The knot of point i.
    double knot(std::size_t i) const { return s_[i]; }
    /// Point i the spline goes through.
    Vec2 point(std::size_t i) const { return p_[i]; }
    /// The number of points.
    std::size_t knot_count() const { return p_.size(); }

    /// γ, γ_s and γ_ss at s in [s_i, s_{i+1}].
    struct Jet {
        Vec2 x, d1, d2;
    };
    Jet at(double s) const { return at(span(s), s); }
    /// The span i with s in [s_i, s_{i+1}].
    std::size_t span(double s) const {
        const auto above = std::upper_bound(s_.begin(), s_.end() - 1, s);
        return static_cast<std::size_t>(std::max<std::ptrdiff_t>(above - s_.begin() - 1, 0));
    }
    Jet at(std::size_t i, double s) const {
        const std::size_t n = p_.size(), ip = (i + 1) % n;
        const double hi = h(i), A = (s_[i + 1] - s) / hi, B = (s - s_[i]) / hi;
        const Vec2 mi = m_[i], mp = m_[ip];
        return {A * p_[i] + B * p_[ip] +
                    (hi * hi / 6.0) * ((A * A * A - A) * mi + (B * B * B - B) * mp),
                (p_[ip] - p_[i]) / hi +
                    (hi / 6.0) * ((1.0 - 3.0 * A * A) * mi + (3.0 * B * B - 1.0) * mp),
                A * mi + B * mp};
    }

private:
    double h(std::size_t i) const { return s_[i + 1] - s_[i]; }

    std::vector<Vec2> p_;
    std::vector<double> s_;  // knots, s_[n] = L
    std::vector<Vec2> m_;    // second derivatives at the knots
};

/// The outward unit normal and C of a spline jet (right of the direction of travel).
std::pair<Vec2, double> normal_and_curvature(const PeriodicSpline::Jet& j) {
    const double speed = norm(j.d1);
    const Vec2 n = Vec2{j.d1.y, -j.d1.x} / speed;
    const double kappa = (j.d1.x * j.d2.y - j.d1.y * j.d2.x) / (speed * speed * speed);
    return {n, -kappa};
}

/// C at x, a point of span i of the spline with outward normal n, from the points the spline goes
/// through: the least-squares polynomial of degree 6 through the nine points nearest x (four on
/// each side of the nearer end of span i), as a graph η(ξ) over the tangent at x, gives
/// C = η''/(1 + η'²)^{3/2} at ξ = 0 with an error O(h⁵). The spline's own curvature is O(h²),
/// alternating from span to span, which the Mullins–Sekerka map multiplies by about 1/h. Nothing
/// when the curve has fewer than 12 points or is not a graph over the tangent there.
std::optional<double> fitted_curvature(const PeriodicSpline& spline, std::size_t i, Vec2 x,
                                       Vec2 n) {
    constexpr int half = 4, degree = 6;
    const std::size_t count = spline.knot_count();
    if (count < 12) return std::nullopt;
    const std::size_t next = (i + 1) % count;
    const std::size_t centre = norm(spline.point(next) - x) < norm(spline.point(i) - x) ? next : i;
    const Vec2 t{-n.y, n.x};
    const double h = norm(spline.point(next) - spline.point(i));
    Eigen::Matrix<double, 2 * half + 1, degree + 1> v;
    Eigen::Matrix<double, 2 * half + 1, 1> eta;
    double last = -std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 2 * half; ++k) {
        const Vec2 q =
            spline.point((centre + count + static_cast<std::size_t>(k) - half) % count) - x;
        const double xi = dot(q, t) / h;
        if (!(xi > last)) return std::nullopt;
        last = xi;
        double power = 1.0;
        for (int e = 0; e <= degree; ++e, power *= xi) v(k, e) = power;
        eta(k) = dot(q, n);
    }
    const Eigen::Matrix<double, degree + 1, 1> a = v.householderQr().solve(eta);
    const double slope = a(1) / h;
    return 2.0 * a(2) / (h * h) / std::pow(1.0 + slope * slope, 1.5);
}

/// Kress's weights R_d, d = 0 … M − 1, for ∫_0^{2π} log(4 sin²((t − τ)/2)) g(τ) dτ at t = τ_i,
/// d = i − j mod M, M = 2n samples.
std::vector<double> kress_weights(std::size_t m_samples) {
    const std::size_t n = m_samples / 2;
    const double dn = static_cast<double>(n);
    std::vector<double> r(m_samples);
    for (std::size_t d = 0; d < m_samples; ++d) {
        double sum = 0.0;
        for (std::size_t m = 1; m < n; ++m)
            sum +=
                std::cos(static_cast<double>(m * d % m_samples) * pi / dn) / static_cast<double>(m);
        r[d] = -(2.0 * pi / dn) * sum - (pi / (dn * dn)) * (d % 2 == 0 ? 1.0 : -1.0);
    }
    return r;
}

/// The vertices of a curve the spline goes through: each at least `gap` from the one kept before
/// it and from the first. Contours can place two vertices a rounding error apart; a spline
/// through both would turn sharply between them.
std::vector<Vec2> spaced_vertices(std::span<const Vec2> p, double gap) {
    std::vector<Vec2> kept{p[0]};
    for (std::size_t i = 1; i < p.size(); ++i)
        if (norm(p[i] - kept.back()) >= gap && norm(p[i] - p[0]) >= gap) kept.push_back(p[i]);
    if (kept.size() < 3) return {p.begin(), p.end()};
    return kept;
}

}  // namespace

SmoothCurves smooth_curves(const Interface& curves, double samples_per_vertex,
                           std::size_t min_samples) {
    SmoothCurves s;
    s.offsets.push_back(0);
    s.vertex_offsets.assign(curves.offsets().begin(), curves.offsets().end());
    s.vertex_tau.resize(curves.size());
    s.vertex_normal.resize(curves.size());
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        const std::span<const Vec2> p = curves.curve(c);
        const PeriodicSpline spline(
            spaced_vertices(p, min_vertex_gap * length(p) / static_cast<double>(p.size())));
        const double wanted = std::ceil(samples_per_vertex * static_cast<double>(p.size()) / 2.0);
        const std::size_t m = std::max(min_samples, 2 * static_cast<std::size_t>(wanted));
        const double length = spline.length();
        s.length.push_back(length);
        s.area.push_back(signed_area(p));
        for (std::size_t j = 0; j < m; ++j) {
            const double at = length * static_cast<double>(j) / static_cast<double>(m);
            const std::size_t span = spline.span(at);
            const PeriodicSpline::Jet jet = spline.at(span, at);
            const auto [n, curvature] = normal_and_curvature(jet);
            s.x.push_back(jet.x);
            s.speed.push_back(norm(jet.d1) * length / (2.0 * pi));
            s.normal.push_back(n);
            s.curvature.push_back(fitted_curvature(spline, span, jet.x, n).value_or(curvature));
        }
        // Each vertex at its chord length from the last vertex the spline goes through.
        const std::size_t first = curves.offsets()[c];
        std::size_t knot = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (knot + 1 < spline.knot_count() && p[i] == spline.point(knot + 1)) ++knot;
            const double at = std::min(spline.knot(knot) + norm(p[i] - spline.point(knot)),
                                       std::nextafter(length, 0.0));
            s.vertex_tau[first + i] = 2.0 * pi * at / length;
            s.vertex_normal[first + i] = normal_and_curvature(spline.at(at)).first;
        }
        s.offsets.push_back(s.x.size());
    }
    return s;
}

std::vector<double> curve_integrals(const SmoothCurves& s, std::span<const double> g) {
    std::vector<double> out;
    for (std::size_t c = 0; c < s.curve_count(); ++c) {
        double sum = 0.0;
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j) sum += g[j] * s.speed[j];
        out.push_back(sum * 2.0 * pi / static_cast<double>(s.count(c)));
    }
    return out;
}

std::vector<double> interpolate_at_vertices(const SmoothCurves& s, std::size_t c,
                                            std::span<const double> g) {
    const std::size_t m = s.count(c);
    if (g.size() != m)
        throw InvalidInput(
            fmt::format("interpolate_at_vertices: {} values for {} samples", g.size(), m));
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, std::vector<double>(g.begin(), g.end()));
    const std::size_t half = m / 2;
    const double scale = 1.0 / static_cast<double>(m);
    std::vector<double> out;
    for (std::size_t v = s.vertex_offsets[c]; v < s.vertex_offsets[c + 1]; ++v) {
        // g(τ) = (1/M)(c_0 + 2 Re Σ_{0<k<M/2} c_k e^{ikτ} + c_{M/2} cos(Mτ/2)), summed with the
        // rotation e^{iτ} applied k times.
        const std::complex<double> step = std::polar(1.0, s.vertex_tau[v]);
        std::complex<double> turn = step;
        double sum = spectrum[0].real();
        for (std::size_t k = 1; k < half; ++k, turn *= step)
            sum += 2.0 * (spectrum[k] * turn).real();
        sum +=
            (spectrum[half] * std::polar(1.0, static_cast<double>(half) * s.vertex_tau[v])).real();
        out.push_back(scale * sum);
    }
    return out;
}

namespace {

/// The group of each sample (group: of each curve, or empty for one group), and the number of
/// groups.
std::pair<std::vector<std::size_t>, std::size_t> sample_groups(const SmoothCurves& s,
                                                               std::span<const std::size_t> group) {
    std::vector<std::size_t> of(s.x.size(), 0);
    if (group.empty()) return {std::move(of), 1};
    if (group.size() != s.curve_count())
        throw InvalidInput(
            fmt::format("the potential: {} groups for {} curves", group.size(), s.curve_count()));
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j) of[j] = group[c];
    return {std::move(of), *std::max_element(group.begin(), group.end()) + 1};
}

/// Kress's weights R_d of each curve's sample count, and the curve of each sample.
struct KressTables {
    std::vector<std::size_t> curve_of;
    std::vector<std::vector<double>> weights;

    explicit KressTables(const SmoothCurves& s) : curve_of(s.x.size()), weights(s.curve_count()) {
        for (std::size_t c = 0; c < s.curve_count(); ++c) {
            weights[c] = kress_weights(s.count(c));
            for (std::size_t i = s.offsets[c]; i < s.offsets[c + 1]; ++i) curve_of[i] = c;
        }
    }
};

/// The single-layer operator's weight of φ_j in (Sμ)(x_i) for samples i, j of one curve c:
/// Kress's −(1/4π) [R_{i−j} + (2π/M) log(|x_i − x_j|² / (4 sin²((τ_i − τ_j)/2)))], the log of
/// the speed² on the diagonal.
double own_curve_weight(const SmoothCurves& s, const KressTables& kress, std::size_t c,
                        std::size_t i, std::size_t j) {
    const std::size_t first = s.offsets[c], m = s.count(c);
    const std::size_t d = (i - first + m - (j - first)) % m;
    double smooth;
    if (d == 0) {
        smooth = std::log(s.speed[i] * s.speed[i]);
    } else {
        const double sine = std::sin(pi * static_cast<double>(d) / static_cast<double>(m));
        smooth = std::log(norm2(s.x[i] - s.x[j]) / (4.0 * sine * sine));
    }
    return -(kress.weights[c][d] + (2.0 * pi / static_cast<double>(m)) * smooth) / (4.0 * pi);
}

/// The single-layer operator's weight of φ_j in (Sμ)(x_i) for samples i, j of different curves,
/// j on curve cj: −(1/2π) log|x_i − x_j| times the trapezoidal weight 2π/M of curve cj.
double other_curve_weight(const SmoothCurves& s, std::size_t i, std::size_t j, std::size_t cj) {
    return -std::log(norm(s.x[i] - s.x[j])) / static_cast<double>(s.count(cj));
}

/// Calls f(j, g, w) for every sample j, of group g: the augmented system's constant of group g
/// enters row j with weight 1, and φ_j enters group g's charge row, ∫μ ds = Σ w φ_j, with the
/// trapezoidal weight w = 2π/M of its curve.
template <class F>
void for_each_constraint(const SmoothCurves& s, std::span<const std::size_t> sample_group, F&& f) {
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j)
            f(j, sample_group[j], 2.0 * pi / static_cast<double>(s.count(c)));
}

/// Calls write(i, j, A_ij) for every pair of samples of one group: the single-layer operator's
/// weight of φ_j in (Sμ)(x_i), Kress's quadrature on a sample's own curve, the trapezoidal rule
/// on others. Rows in parallel, each written by one thread.
template <class Write>
void assemble_single_layer(const SmoothCurves& s, std::span<const std::size_t> sample_group,
                           Write&& write) {
    const std::size_t n = s.x.size();
    const KressTables kress(s);
    parallel_for(n, [&](std::size_t i) {
        const std::size_t ci = kress.curve_of[i];
        for (std::size_t j = 0; j < n; ++j) {
            if (sample_group[j] != sample_group[i]) continue;
            const std::size_t cj = kress.curve_of[j];
            const double w =
                cj != ci ? other_curve_weight(s, i, j, cj) : own_curve_weight(s, kress, ci, i, j);
            write(i, j, w);
        }
    });
}

/// The block of curve c with itself of the single-layer operator's matrix.
Eigen::MatrixXd own_curve_block(const SmoothCurves& s, const KressTables& kress, std::size_t c) {
    const auto m = static_cast<Eigen::Index>(s.count(c));
    Eigen::MatrixXd block(m, m);
    const std::size_t first = s.offsets[c];
    for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index j = 0; j < m; ++j)
            block(i, j) = own_curve_weight(s, kress, c, first + static_cast<std::size_t>(i),
                                           first + static_cast<std::size_t>(j));
    return block;
}

/// The single-layer operator summed fast (docs/algorithms/potential.md): the trapezoidal rule's
/// logarithms over every sample of a group by the treecode (LogSum), then on each curve what
/// Kress's quadrature adds to the trapezoidal rule there: a circulant (its weights depend on
/// i − j mod M alone: −R_d/4π + log(4 sin²(πd/M))/2M), applied by FFT, and −log|γ'(τ_i)|/M on
/// the diagonal. O(M log M) a product.
class FastSingleLayer {
public:
    FastSingleLayer(const SmoothCurves& s, std::span<const std::size_t> sample_group)
        : s_(s), sum_(s.x, sample_group) {
        Eigen::FFT<double> fft;
        for (std::size_t c = 0; c < s.curve_count(); ++c) {
            const std::size_t m = s.count(c);
            const std::vector<double> r = kress_weights(m);
            // The circulant's weights c_d as a linear convolution's kernel c̃_e = c_{(e − M + 1)
            // mod M}, e in [0, 2M − 2], zero-padded to a power of two at or above 2M − 1.
            std::size_t padded = 1;
            while (padded < 2 * m - 1) padded *= 2;
            std::vector<double> kernel(padded, 0.0);
            for (std::size_t e = 0; e + 1 < 2 * m; ++e) {
                const std::size_t d = (e + 1) % m;  // e − (M − 1) mod M
                double w = -r[d] / (4.0 * pi);
                if (d != 0) {
                    const double sine =
                        std::sin(pi * static_cast<double>(d) / static_cast<double>(m));
                    w += std::log(4.0 * sine * sine) / (2.0 * static_cast<double>(m));
                }
                kernel[e] = w;
            }
            spectrum_.emplace_back();
            fft.fwd(spectrum_.back(), kernel);
        }
    }

    /// y = Sφ at the samples, φ_j = μ_j |γ'(τ_j)|.
    void apply(std::span<const double> phi, std::span<double> y) const {
        const std::size_t n = s_.x.size();
        std::vector<double> q(n);
        for (std::size_t c = 0; c < s_.curve_count(); ++c)
            for (std::size_t j = s_.offsets[c]; j < s_.offsets[c + 1]; ++j)
                q[j] = -phi[j] / static_cast<double>(s_.count(c));
        sum_.sum(q, y, {});
        Eigen::FFT<double> fft;
        std::vector<std::complex<double>> spectrum;
        std::vector<double> padded, convolved;
        for (std::size_t c = 0; c < s_.curve_count(); ++c) {
            const std::size_t first = s_.offsets[c], m = s_.count(c);
            padded.assign(spectrum_[c].size(), 0.0);
            std::copy_n(phi.begin() + static_cast<std::ptrdiff_t>(first), m, padded.begin());
            fft.fwd(spectrum, padded);
            for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] *= spectrum_[c][k];
            fft.inv(convolved, spectrum);
            for (std::size_t i = 0; i < m; ++i)
                y[first + i] += convolved[i + m - 1] - std::log(s_.speed[first + i]) *
                                                           phi[first + i] / static_cast<double>(m);
        }
    }

private:
    const SmoothCurves& s_;
    detail::LogSum sum_;
    std::vector<std::vector<std::complex<double>>> spectrum_;  // each curve's padded kernel's
};

/// Whether the fast summation is used for `samples` samples.
bool fast_for(Summation how, std::size_t samples) {
    return how == Summation::fast || (how == Summation::automatic && samples > fast_summation_from);
}

}  // namespace

std::vector<double> single_layer_matrix(const SmoothCurves& s) {
    const std::size_t n = s.x.size();
    std::vector<double> a(n * n);
    assemble_single_layer(s, std::vector<std::size_t>(n, 0),
                          [&](std::size_t i, std::size_t j, double w) { a[i * n + j] = w; });
    return a;
}

std::vector<double> apply_single_layer(const SmoothCurves& s, std::span<const double> phi) {
    std::vector<double> y(s.x.size());
    FastSingleLayer(s, std::vector<std::size_t>(s.x.size(), 0)).apply(phi, y);
    return y;
}

namespace {

/// GMRES's preconditioner for many curves: each curve's own augmented system (its block of S,
/// its constant and its charge Q_c = ∫_c μ ds) solved exactly, the curves coupled through their
/// charges alone, curve d's unit charge raising the potential on curve c by G_cd, the mean over
/// c of S applied to d's equilibrium density. What is left, the curves' dipoles and higher
/// moments on each other, shrinks as (size/distance)^m, so GMRES's iterations do not grow with
/// the number of curves (docs/notes/potential.md). Set up in O(Σ M_c³ + curves³) and the G_cd.
class CurveBlockPreconditioner {
public:
    template <class Matrix>
    CurveBlockPreconditioner& analyzePattern(const Matrix&) {
        return *this;
    }
    template <class Matrix>
    CurveBlockPreconditioner& factorize(const Matrix&) {
        return *this;
    }
    template <class Matrix>
    CurveBlockPreconditioner& compute(const Matrix&) {
        return *this;
    }
    Eigen::ComputationInfo info() const { return Eigen::Success; }

    /// From each curve's own block of S (own_block(c)) and the potential on curve c of d's
    /// equilibrium density (coupling(c, d, density of d at its samples)).
    template <class OwnBlock, class Coupling>
    void set_up(const SmoothCurves& s, std::span<const std::size_t> sample_group,
                std::size_t groups, OwnBlock&& own_block, Coupling&& coupling) {
        const std::size_t curves = s.curve_count();
        offsets_ = s.offsets;
        groups_ = groups;
        local_.assign(curves, Eigen::PartialPivLU<Eigen::MatrixXd>());
        unit_.assign(curves, Eigen::VectorXd());
        parallel_for(
            curves,
            [&](std::size_t c) {
                const auto m = static_cast<Eigen::Index>(s.count(c));
                Eigen::MatrixXd block = Eigen::MatrixXd::Zero(m + 1, m + 1);
                block.topLeftCorner(m, m) = own_block(c);
                block.col(m).head(m).setOnes();
                block.row(m).head(m).setConstant(2.0 * pi / static_cast<double>(m));
                local_[c].compute(block);
                unit_[c] = local_[c].solve(Eigen::VectorXd::Unit(m + 1, m));
            },
            expensive_grain);
        // G_cd: the mean over curve c of S applied to curve d's equilibrium density.
        Eigen::MatrixXd g = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(curves),
                                                  static_cast<Eigen::Index>(curves));
        parallel_for(curves, [&](std::size_t c) {
            for (std::size_t d = 0; d < curves; ++d) {
                if (d == c || sample_group[s.offsets[d]] != sample_group[s.offsets[c]]) continue;
                const auto md = static_cast<Eigen::Index>(s.count(d));
                g(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(d)) =
                    coupling(c, d, unit_[d].head(md));
            }
        });
        // The charges' system: b_c Q_c − Σ_d G_cd Q_d − C_g = −a_c for each curve (a_c + b_c Q_c
        // the constant its own system gives it), Σ_{c in g} Q_c = r_g for each group.
        const auto k = static_cast<Eigen::Index>(curves + groups);
        Eigen::MatrixXd charges = -g;
        charges.conservativeResize(k, k);
        charges.rightCols(k - static_cast<Eigen::Index>(curves)).setZero();
        charges.bottomRows(k - static_cast<Eigen::Index>(curves)).setZero();
        for (std::size_t c = 0; c < curves; ++c) {
            const auto ci = static_cast<Eigen::Index>(c);
            const auto gi = static_cast<Eigen::Index>(curves + sample_group[s.offsets[c]]);
            charges(ci, ci) = unit_[c](unit_[c].size() - 1);
            charges(ci, gi) = -1.0;
            charges(gi, ci) = 1.0;
        }
        charges_.compute(charges);
    }

    template <class Rhs>
    Eigen::VectorXd solve(const Rhs& r) const {
        const std::size_t curves = local_.size();
        Eigen::VectorXd out(r.size());
        Eigen::VectorXd rhs(static_cast<Eigen::Index>(curves + groups_));
        std::vector<Eigen::VectorXd> own(curves);
        for (std::size_t c = 0; c < curves; ++c) {
            const auto m = static_cast<Eigen::Index>(offsets_[c + 1] - offsets_[c]);
            Eigen::VectorXd b(m + 1);
            b.head(m) = r.segment(static_cast<Eigen::Index>(offsets_[c]), m);
            b(m) = 0.0;
            own[c] = local_[c].solve(b);
            rhs(static_cast<Eigen::Index>(c)) = -own[c](m);
        }
        for (std::size_t g = 0; g < groups_; ++g)
            rhs(static_cast<Eigen::Index>(curves + g)) =
                r(static_cast<Eigen::Index>(offsets_.back() + g));
        const Eigen::VectorXd q = charges_.solve(rhs);
        for (std::size_t c = 0; c < curves; ++c) {
            const auto m = static_cast<Eigen::Index>(offsets_[c + 1] - offsets_[c]);
            out.segment(static_cast<Eigen::Index>(offsets_[c]), m) =
                own[c].head(m) + q(static_cast<Eigen::Index>(c)) * unit_[c].head(m);
        }
        for (std::size_t g = 0; g < groups_; ++g)
            out(static_cast<Eigen::Index>(offsets_.back() + g)) =
                q(static_cast<Eigen::Index>(curves + g));
        return out;
    }

private:
    std::vector<std::size_t> offsets_;
    std::size_t groups_ = 1;
    std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> local_;
    std::vector<Eigen::VectorXd>
        unit_;  // each curve's response to a unit charge, its constant last
    Eigen::PartialPivLU<Eigen::MatrixXd> charges_;
};

}  // namespace

/// The system's matrix and its factorisation (LU), or its GMRES solver over the dense matrix or
/// the fast summation.
struct SingleLayerSystem::Factored {
    RowMajorMatrix matrix;  // empty with the fast summation
    std::optional<FastSingleLayer> fast;
    std::optional<Eigen::PartialPivLU<RowMajorMatrix>> lu;
    std::optional<LinearOperator> product;  // GMRES's view of the system
    std::optional<Eigen::GMRES<LinearOperator, CurveBlockPreconditioner>> gmres;
};

SingleLayerSystem::SingleLayerSystem(const SmoothCurves& s, std::span<const std::size_t> group,
                                     Summation how)
    : s_(s), factored_(std::make_unique<Factored>()) {
    const std::size_t n = s.x.size();
    const auto [sample_group, groups] = sample_groups(s, group);
    groups_ = groups;
    const auto size = static_cast<Eigen::Index>(n + groups);
    // The unknowns: φ_j = μ_j |γ'(τ_j)| and each group's constant; the group's last row is
    // ∫μ ds = Σ (2π/M_c) φ_j = 0 over its curves. Curves of other groups are not seen.
    Factored& f = *factored_;
    const KressTables kress(s);
    const auto preconditioner = [&]() -> CurveBlockPreconditioner& {
        return f.gmres->preconditioner();
    };
    if (fast_for(how, n)) {
        f.fast.emplace(s, sample_group);
        f.product.emplace(
            size, [this, n, sample_group](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
                factored_->fast->apply(std::span(x.data(), n), std::span(y.data(), n));
                for (std::size_t g = 0; g < groups_; ++g) y(static_cast<Eigen::Index>(n + g)) = 0.0;
                for_each_constraint(s_, sample_group, [&](std::size_t j, std::size_t g, double w) {
                    const auto row = static_cast<Eigen::Index>(j);
                    const auto charge = static_cast<Eigen::Index>(n + g);
                    y(row) += x(charge);
                    y(charge) += w * x(row);
                });
            });
        f.gmres.emplace(*f.product);
        // Curves far apart (centroids more than 4 times their radii's sum apart) see each other's
        // unit charge as a point's, −log|c_c − c_d|/2π; nearer ones by the trapezoidal rule.
        std::vector<Vec2> centroid(s.curve_count());
        std::vector<double> radius(s.curve_count(), 0.0);
        for (std::size_t c = 0; c < s.curve_count(); ++c) {
            for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j) centroid[c] += s.x[j];
            centroid[c] = centroid[c] / static_cast<double>(s.count(c));
            for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j)
                radius[c] = std::max(radius[c], norm(s.x[j] - centroid[c]));
        }
        preconditioner().set_up(
            s, sample_group, groups, [&](std::size_t c) { return own_curve_block(s, kress, c); },
            [&](std::size_t c, std::size_t d, const auto& unit) {
                const double apart = norm(centroid[c] - centroid[d]);
                if (apart > 4.0 * (radius[c] + radius[d])) return -std::log(apart) / (2.0 * pi);
                double sum = 0.0;
                for (std::size_t i = s.offsets[c]; i < s.offsets[c + 1]; ++i)
                    for (std::size_t j = s.offsets[d]; j < s.offsets[d + 1]; ++j)
                        sum += other_curve_weight(s, i, j, d) *
                               unit(static_cast<Eigen::Index>(j - s.offsets[d]));
                return sum / static_cast<double>(s.count(c));
            });
        f.gmres->setTolerance(fast_tolerance);
    } else {
        if (n > max_samples)
            throw NumericalFailure(fmt::format(
                "the potential's dense integral equation on {} points (curves of {} vertices) "
                "would need {:.1f} GB, more than 0.8: the fast summation (or fewer vertices)",
                n, s.vertex_offsets.back(),
                8e-9 * static_cast<double>(n) * static_cast<double>(n)));
        RowMajorMatrix& system = f.matrix;
        system = RowMajorMatrix::Zero(size, size);
        assemble_single_layer(s, sample_group,
                              [&](std::size_t i, std::size_t j, double w) { system(i, j) = w; });
        for_each_constraint(s, sample_group, [&](std::size_t j, std::size_t g, double w) {
            system(j, n + g) = 1.0;
            system(n + g, j) = w;
        });
        if (n <= direct_solve_limit) {
            f.lu.emplace(system);
            return;
        }
        f.product.emplace(size, [&system](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
            parallel_for(static_cast<std::size_t>(system.rows()), [&](std::size_t i) {
                const auto r = static_cast<Eigen::Index>(i);
                y(r) = system.row(r).dot(x);
            });
        });
        f.gmres.emplace(*f.product);
        preconditioner().set_up(
            s, sample_group, groups,
            [&](std::size_t c) {
                const auto m = static_cast<Eigen::Index>(s.count(c));
                const auto first = static_cast<Eigen::Index>(s.offsets[c]);
                return Eigen::MatrixXd(system.block(first, first, m, m));
            },
            [&](std::size_t c, std::size_t d, const auto& unit) {
                const auto m = static_cast<Eigen::Index>(s.count(c));
                const auto first = static_cast<Eigen::Index>(s.offsets[c]);
                const auto md = static_cast<Eigen::Index>(s.count(d));
                const auto first_d = static_cast<Eigen::Index>(s.offsets[d]);
                return (system.block(first, first_d, m, md) * unit).mean();
            });
        f.gmres->setTolerance(dense_tolerance);
    }
    f.gmres->set_restart(300);
    f.gmres->setMaxIterations(3000);
}

SingleLayerSystem::~SingleLayerSystem() = default;

bool SingleLayerSystem::sums_fast() const { return factored_->fast.has_value(); }

std::vector<SingleLayerSolution> SingleLayerSystem::solve(
    std::span<const std::vector<double>> fs) const {
    const std::size_t n = s_.x.size();
    std::vector<SingleLayerSolution> out;
    for (const std::vector<double>& f : fs) {
        if (f.size() != n)
            throw InvalidInput(
                fmt::format("the potential: {} boundary values for {} samples", f.size(), n));
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n + groups_));
        for (std::size_t i = 0; i < n; ++i) rhs(i) = f[i];
        SingleLayerSolution solution;
        Eigen::VectorXd phi;
        if (factored_->lu) {
            phi = factored_->lu->solve(rhs);
        } else {
            auto& gmres = *factored_->gmres;
            phi = gmres.solve(rhs);
            if (gmres.info() != Eigen::Success)
                throw NumericalFailure(fmt::format(
                    "the potential's integral equation on {} points did not converge in {} GMRES "
                    "iterations (residual {:.2g}): curves too close for their sampling",
                    n, gmres.iterations(), gmres.error()));
            solution.iterations = static_cast<int>(gmres.iterations());
        }
        solution.density.resize(n);
        for (std::size_t j = 0; j < n; ++j) solution.density[j] = phi(j) / s_.speed[j];
        for (std::size_t g = 0; g < groups_; ++g) solution.constants.push_back(phi(n + g));
        solution.u_infinity = solution.constants[0];
        out.push_back(std::move(solution));
    }
    return out;
}

std::optional<std::vector<double>> solve_dense(std::span<const double> a,
                                               std::span<const double> b) {
    const auto n = static_cast<Eigen::Index>(b.size());
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            a.data(), n, n));
    if (!lu.isInvertible()) return std::nullopt;
    const Eigen::VectorXd x = lu.solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
    return std::vector<double>(x.data(), x.data() + n);
}

SingleLayerSolution solve_single_layer(const SmoothCurves& s, std::span<const double> f) {
    const std::vector<double> one(f.begin(), f.end());
    return std::move(SingleLayerSystem(s).solve(std::span(&one, 1)).front());
}

std::vector<double> adjoint_double_layer(const SmoothCurves& s, std::span<const double> density,
                                         std::span<const std::size_t> group, Summation how) {
    const std::size_t n = s.x.size();
    const std::vector<std::size_t> sample_group = sample_groups(s, group).first;
    std::vector<double> phi(n), out(n);
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j)
            phi[j] = density[j] * s.speed[j] * 2.0 * pi / static_cast<double>(s.count(c));
    // ∂G/∂N(x_i) = −(1/2π) (x_i − y)·N_i / |x_i − y|²; its limit on the diagonal, C_i/4π.
    if (fast_for(how, n)) {
        std::vector<Vec2> field(n);
        detail::LogSum(s.x, sample_group).sum(phi, {}, field);
        for (std::size_t i = 0; i < n; ++i)
            out[i] =
                -dot(field[i], s.normal[i]) / (2.0 * pi) + s.curvature[i] / (4.0 * pi) * phi[i];
        return out;
    }
    parallel_for(n, [&](std::size_t i) {
        double sum = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            if (sample_group[j] != sample_group[i]) continue;
            const Vec2 d = s.x[i] - s.x[j];
            const double kernel =
                j == i ? s.curvature[i] / (4.0 * pi) : -dot(d, s.normal[i]) / (2.0 * pi * norm2(d));
            sum += kernel * phi[j];
        }
        out[i] = sum;
    });
    return out;
}

void filter_modes(const SmoothCurves& s, std::size_t c, std::span<double> g,
                  const std::function<double(double)>& filter) {
    const std::size_t m = s.count(c);
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, std::vector<double>(g.begin(), g.end()));
    for (std::size_t k = 0; k < m; ++k) {
        const double mode = static_cast<double>(k <= m / 2 ? k : m - k);
        spectrum[k] *= filter(2.0 * pi * mode / s.length[c]);
    }
    std::vector<double> back;
    fft.inv(back, spectrum);
    std::copy(back.begin(), back.end(), g.begin());
}

}  // namespace slc
