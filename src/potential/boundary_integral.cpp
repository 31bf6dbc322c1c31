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
#include <limits>
#include <numbers>
#include <optional>
#include <unsupported/Eigen/FFT>
#include <unsupported/Eigen/IterativeSolvers>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc::detail {

/// The single-layer system's matrix, row by row contiguous.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// RowMajorMatrix as GMRES sees it: its products with a vector computed a row per iteration of
/// slc's parallel_for, each row's sum in one order whatever the number of threads (Eigen's own
/// product runs on one core).
class ParallelDense;

}  // namespace slc::detail

namespace Eigen::internal {
template <>
struct traits<slc::detail::ParallelDense> : public traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace slc::detail {

class ParallelDense : public Eigen::EigenBase<ParallelDense> {
public:
    using Scalar = double;
    using RealScalar = double;
    using StorageIndex = int;
    enum {
        ColsAtCompileTime = Eigen::Dynamic,
        MaxColsAtCompileTime = Eigen::Dynamic,
        IsRowMajor = false
    };
    explicit ParallelDense(const RowMajorMatrix& m) : m_(&m) {}
    Eigen::Index rows() const { return m_->rows(); }
    Eigen::Index cols() const { return m_->cols(); }
    template <class Rhs>
    Eigen::Product<ParallelDense, Rhs, Eigen::AliasFreeProduct> operator*(
        const Eigen::MatrixBase<Rhs>& x) const {
        return Eigen::Product<ParallelDense, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
    }
    const RowMajorMatrix& matrix() const { return *m_; }

private:
    const RowMajorMatrix* m_;
};

}  // namespace slc::detail

namespace Eigen::internal {
template <class Rhs>
struct generic_product_impl<slc::detail::ParallelDense, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<slc::detail::ParallelDense, Rhs,
                                generic_product_impl<slc::detail::ParallelDense, Rhs>> {
    using Scalar = typename Product<slc::detail::ParallelDense, Rhs>::Scalar;
    template <class Dest>
    static void scaleAndAddTo(Dest& dst, const slc::detail::ParallelDense& lhs, const Rhs& rhs,
                              const Scalar& alpha) {
        const slc::detail::RowMajorMatrix& m = lhs.matrix();
        const Eigen::VectorXd x = rhs;
        slc::parallel_for(static_cast<std::size_t>(m.rows()), [&](std::size_t i) {
            const auto r = static_cast<Eigen::Index>(i);
            dst(r) += alpha * m.row(r).dot(x);
        });
    }
};
}  // namespace Eigen::internal

namespace slc {

using detail::ParallelDense;
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

/// Calls write(i, j, A_ij) for every pair of samples of one group: the single-layer operator's
/// weight of φ_j in (Sμ)(x_i), Kress's quadrature on a sample's own curve, the trapezoidal rule
/// on others. Rows in parallel, each written by one thread.
template <class Write>
void assemble_single_layer(const SmoothCurves& s, std::span<const std::size_t> sample_group,
                           Write&& write) {
    const std::size_t n = s.x.size();
    std::vector<std::size_t> curve_of(n);
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        for (std::size_t i = s.offsets[c]; i < s.offsets[c + 1]; ++i) curve_of[i] = c;
    std::vector<std::vector<double>> kress(s.curve_count());
    for (std::size_t c = 0; c < s.curve_count(); ++c) kress[c] = kress_weights(s.count(c));
    parallel_for(n, [&](std::size_t i) {
        const std::size_t ci = curve_of[i], first = s.offsets[ci], m = s.count(ci);
        const double half = static_cast<double>(m / 2);
        for (std::size_t j = 0; j < n; ++j) {
            if (sample_group[j] != sample_group[i]) continue;
            const std::size_t cj = curve_of[j];
            double w;
            if (cj != ci) {
                // −(1/2π) log|x_i − x_j| times the trapezoidal weight 2π/M of curve cj.
                w = -std::log(norm(s.x[i] - s.x[j])) / static_cast<double>(s.count(cj));
            } else {
                // Kress: −(1/4π) [R_{i−j} + (π/n) log(|x_i − x_j|² / (4 sin²((τ_i − τ_j)/2)))],
                // the log of the speed² on the diagonal.
                const std::size_t d = (i - first + m - (j - first)) % m;
                double smooth;
                if (d == 0) {
                    smooth = std::log(s.speed[i] * s.speed[i]);
                } else {
                    const double sine =
                        std::sin(pi * static_cast<double>(d) / static_cast<double>(m));
                    smooth = std::log(norm2(s.x[i] - s.x[j]) / (4.0 * sine * sine));
                }
                w = -(kress[ci][d] + (pi / half) * smooth) / (4.0 * pi);
            }
            write(i, j, w);
        }
    });
}

}  // namespace

std::vector<double> single_layer_matrix(const SmoothCurves& s) {
    const std::size_t n = s.x.size();
    std::vector<double> a(n * n);
    assemble_single_layer(s, std::vector<std::size_t>(n, 0),
                          [&](std::size_t i, std::size_t j, double w) { a[i * n + j] = w; });
    return a;
}

namespace {

/// GMRES's preconditioner for many curves: each curve's own augmented system (its block of S,
/// its constant and its charge Q_c = ∫_c μ ds) solved exactly, the curves coupled through their
/// charges alone, curve d's unit charge raising the potential on curve c by G_cd, the mean over
/// c of S applied to d's equilibrium density. What is left, the curves' dipoles and higher
/// moments on each other, shrinks as (size/distance)^m, so GMRES's iterations do not grow with
/// the number of curves (docs/notes/potential.md). Set up in O(M² + Σ M_c³ + curves³).
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

    /// From the system's matrix (the samples' rows and columns, then a constant and a charge row
    /// for each group).
    void set_up(const RowMajorMatrix& system, const SmoothCurves& s,
                std::span<const std::size_t> sample_group, std::size_t groups) {
        const std::size_t curves = s.curve_count();
        offsets_ = s.offsets;
        groups_ = groups;
        local_.clear();
        unit_.assign(curves, Eigen::VectorXd());
        for (std::size_t c = 0; c < curves; ++c) {
            const auto m = static_cast<Eigen::Index>(s.count(c));
            const auto first = static_cast<Eigen::Index>(s.offsets[c]);
            Eigen::MatrixXd block = Eigen::MatrixXd::Zero(m + 1, m + 1);
            block.topLeftCorner(m, m) = system.block(first, first, m, m);
            block.col(m).head(m).setOnes();
            block.row(m).head(m).setConstant(2.0 * pi / static_cast<double>(m));
            local_.emplace_back(block);
            unit_[c] = local_.back().solve(Eigen::VectorXd::Unit(m + 1, m));
        }
        // G_cd: the mean over curve c of S applied to curve d's equilibrium density.
        Eigen::MatrixXd coupling = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(curves),
                                                         static_cast<Eigen::Index>(curves));
        parallel_for(curves, [&](std::size_t c) {
            const auto m = static_cast<Eigen::Index>(s.count(c));
            const auto first = static_cast<Eigen::Index>(s.offsets[c]);
            for (std::size_t d = 0; d < curves; ++d) {
                if (d == c || sample_group[s.offsets[d]] != sample_group[s.offsets[c]]) continue;
                const auto md = static_cast<Eigen::Index>(s.count(d));
                const auto first_d = static_cast<Eigen::Index>(s.offsets[d]);
                coupling(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(d)) =
                    (system.block(first, first_d, m, md) * unit_[d].head(md)).mean();
            }
        });
        // The charges' system: b_c Q_c − Σ_d G_cd Q_d − C_g = −a_c for each curve (a_c + b_c Q_c
        // the constant its own system gives it), Σ_{c in g} Q_c = r_g for each group.
        const auto k = static_cast<Eigen::Index>(curves + groups);
        Eigen::MatrixXd charges = -coupling;
        charges.conservativeResize(k, k);
        charges.rightCols(k - static_cast<Eigen::Index>(curves)).setZero();
        charges.bottomRows(k - static_cast<Eigen::Index>(curves)).setZero();
        for (std::size_t c = 0; c < curves; ++c) {
            const auto ci = static_cast<Eigen::Index>(c);
            const auto g = static_cast<Eigen::Index>(curves + sample_group[s.offsets[c]]);
            charges(ci, ci) = unit_[c](unit_[c].size() - 1);
            charges(ci, g) = -1.0;
            charges(g, ci) = 1.0;
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

/// The system's matrix and its factorisation (LU) or its iterative solver (GMRES).
struct SingleLayerSystem::Factored {
    RowMajorMatrix matrix;
    std::optional<Eigen::PartialPivLU<RowMajorMatrix>> lu;
    std::optional<ParallelDense> product;  // GMRES's view of matrix
    std::optional<Eigen::GMRES<ParallelDense, CurveBlockPreconditioner>> gmres;
};

SingleLayerSystem::SingleLayerSystem(const SmoothCurves& s, std::span<const std::size_t> group)
    : s_(s), factored_(std::make_unique<Factored>()) {
    const std::size_t n = s.x.size();
    if (n > max_samples)
        throw NumericalFailure(fmt::format(
            "the potential's integral equation on {} points (curves of {} vertices) would need "
            "{:.1f} GB, more than 0.8: fewer vertices (a lower --thin-depth or -K; if the curves "
            "wrinkled, more steps N) or fewer particles",
            n, s.vertex_offsets.back(), 8e-9 * static_cast<double>(n) * static_cast<double>(n)));
    const auto [sample_group, groups] = sample_groups(s, group);
    groups_ = groups;
    // The unknowns: φ_j = μ_j |γ'(τ_j)| and each group's constant; the group's last row is
    // ∫μ ds = Σ (2π/M_c) φ_j = 0 over its curves. Curves of other groups are not seen.
    RowMajorMatrix& system = factored_->matrix;
    system = RowMajorMatrix::Zero(static_cast<Eigen::Index>(n + groups),
                                  static_cast<Eigen::Index>(n + groups));
    assemble_single_layer(s, sample_group,
                          [&](std::size_t i, std::size_t j, double w) { system(i, j) = w; });
    for (std::size_t c = 0; c < s.curve_count(); ++c) {
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j) {
            system(j, n + sample_group[j]) = 1.0;
            system(n + sample_group[j], j) = 2.0 * pi / static_cast<double>(s.count(c));
        }
    }
    if (n <= direct_solve_limit) {
        factored_->lu.emplace(system);
    } else {
        factored_->product.emplace(system);
        factored_->gmres.emplace(*factored_->product);
        factored_->gmres->preconditioner().set_up(system, s, sample_group, groups);
        factored_->gmres->set_restart(300);
        factored_->gmres->setTolerance(1e-13);
        factored_->gmres->setMaxIterations(3000);
    }
}

SingleLayerSystem::~SingleLayerSystem() = default;

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
                                         std::span<const std::size_t> group) {
    const std::size_t n = s.x.size();
    const std::vector<std::size_t> sample_group = sample_groups(s, group).first;
    std::vector<double> phi(n), out(n);
    for (std::size_t c = 0; c < s.curve_count(); ++c)
        for (std::size_t j = s.offsets[c]; j < s.offsets[c + 1]; ++j)
            phi[j] = density[j] * s.speed[j] * 2.0 * pi / static_cast<double>(s.count(c));
    parallel_for(n, [&](std::size_t i) {
        double sum = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            if (sample_group[j] != sample_group[i]) continue;
            // ∂G/∂N(x_i) = −(1/2π) (x_i − y)·N_i / |x_i − y|²; its limit on the diagonal, C_i/4π.
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
