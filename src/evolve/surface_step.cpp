// The predictor–corrector step of surfaces (paper §1.2 Eqs. 4, 5 with d = 3).
#include "slc/evolve/surface_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/distance/surface_distance_tree.hpp"
#include "slc/distance/surface_extension.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/geometry_modules/surface_geometry.hpp"
#include "step_common.hpp"

namespace slc {

Extension SurfaceStepOptions::resolved_extension(const SurfaceVelocityLaw& law) const {
    if (extension) return *extension;
    return law.is_field() || law.is_normal_law() ? Extension::direct : Extension::nearest_point;
}

namespace {

/// A vertex where some incident triangle's normal turns more than this (radians) from the vertex
/// normal is a corner for the field normal of a normal law.
constexpr double corner_angle = 0.5;
/// An edge along which the vertex normals turn more than this (radians) is read flat: the
/// surface bends there faster than the fitted normals follow (a radius below about three edges).
constexpr double patch_angle = 0.35;

/// Everything a step reads of the surface at one time: its distance tree, and the vertex
/// velocities (nearest-point extension) or vertex normals (normal laws) it extends.
class SurfaceLevel {
public:
    SurfaceLevel(const Surface& surface, double t, double k, const SurfaceVelocityLaw& law,
                 const Box3& domain, const SurfaceStepOptions& options, Extension extension)
        : surface_(surface),
          tree_(surface, domain,
                {.depth = options.tree_depth > 0
                              ? options.tree_depth
                              : SurfaceDistanceTree::default_depth(surface, domain)}),
          law_(law),
          t_(t) {
        // The fitted normals, from the geometry the law's velocities need when it needs any.
        SurfaceGeometry geometry;
        if (extension == Extension::nearest_point) {
            geometry =
                vertex_geometry(law.needs(), surface, {.smoothing = options.resolved_smoothing(k)});
            u_ = vertex_velocities(law, t, surface, geometry);
            for (const Vec3& u : u_) max_speed_ = std::max(max_speed_, norm(u));
        }
        normals_ = geometry.normals.empty()
                       ? surface_geometry(surface, {.curvature = false}).normals
                       : std::move(geometry.normals);
        // Corners: a triangle turns more than corner_angle from the angle-weighted normal (the
        // tree's vertex pseudo-normal, scaled to unit length). The fitted normals are second
        // order on smooth parts, but a fit across a corner tilts them: within two rings of a
        // corner the angle-weighted normal (the face's own on a flat face) is kept.
        std::vector<Vec3> weighted = tree_.normals().vertex;
        for (Vec3& n : weighted)
            if (const double length = norm(n); length > 0.0) n = n / length;
        const std::vector<Vec3>& face = tree_.normals().face;
        const double limit = std::cos(corner_angle);
        const std::size_t n = surface.triangles.size();
        std::vector<std::uint8_t> turned(n);  // bit c: corner c turns from the face
        parallel_for(n, [&](std::size_t f) {
            unsigned bits = 0;
            for (int c = 0; c < 3; ++c)
                if (dot(face[f], weighted[surface.triangles[f][c]]) < limit) bits |= 1u << c;
            turned[f] = static_cast<std::uint8_t>(bits);
        });
        corner_.assign(surface.vertices.size(), 0);
        for (std::size_t f = 0; f < n; ++f)
            for (int c = 0; c < 3; ++c)
                if (turned[f] >> c & 1u) corner_[surface.triangles[f][c]] = 1;
        const VertexRings rings = vertex_rings(surface);
        parallel_for(surface.vertices.size(), [&](std::size_t v) {
            bool near = corner_[v] != 0;
            for (const std::uint32_t w : rings.of(v)) {
                near = near || corner_[w];
                for (const std::uint32_t u : rings.of(w)) near = near || corner_[u];
            }
            if (near) normals_[v] = weighted[v];
        });
        if (options.patches) {
            const double patch_limit = std::cos(patch_angle);
            bulge_.resize(n);
            parallel_for(n, [&](std::size_t f) {
                const TriangleIndices& tri = surface.triangles[f];
                for (int e = 0; e < 3; ++e) {
                    const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
                    // Flat at a corner, and where the normals turn too fast along the edge
                    // for a quadric to follow.
                    const bool flat =
                        corner_[a] || corner_[b] || dot(normals_[a], normals_[b]) < patch_limit;
                    bulge_[f][e] = flat ? 0.0
                                        : 0.5 * dot(normals_[b] - normals_[a],
                                                    surface.vertices[b] - surface.vertices[a]);
                }
            });
            for (const std::array<double, 3>& beta : bulge_)
                for (const double b : beta) max_bulge_ = std::max(max_bulge_, std::abs(b) / 3.0);
        }
    }

    /// The largest speed of the vertex velocities (nearest-point extension; 0 without them): the
    /// extension interpolates them, so |W(x)| never exceeds it.
    double max_speed() const { return max_speed_; }
    /// Adds the normal speed s to every vertex velocity, along the fitted normals: a move of the
    /// mean of a nonlocal law, whose speeds are V − mean.
    void add_normal_speed(double s) {
        max_speed_ = 0.0;
        for (std::size_t v = 0; v < u_.size(); ++v) {
            u_[v] += s * normals_[v];
            max_speed_ = std::max(max_speed_, norm(u_[v]));
        }
    }
    /// A bound on the patches' height over their triangles, |F − the triangles' distance| (0
    /// without patches): Σ w_a w_b β_ab ≤ max|β| Σ w_a w_b ≤ max|β|/3.
    double max_bulge() const { return max_bulge_; }

    /// F(x): the signed distance to this level's surface read as curved patches
    /// (SurfaceStepOptions::patches), or to its triangles.
    double distance(Vec3 x) const { return distance(tree_.closest_point(x)); }
    /// W(x): the vertex velocities at the nearest point of the surface (nearest-point extension).
    Vec3 velocity(Vec3 x) const {
        return nearest_point_extension<Vec3>(surface_, u_, tree_.nearest_point(x));
    }

    /// F and the normal a normal law sees (field_normal) at a batch of points, in parallel.
    void distances_and_normals(std::span<const Vec3> xs, std::span<double> f,
                               std::span<Vec3> n) const {
        parallel_for(
            xs.size(),
            [&](std::size_t i) {
                const SurfacePoint p = tree_.closest_point(xs[i]);
                f[i] = distance(p);
                n[i] = field_normal(xs[i], p);
            },
            expensive_grain);
    }
    /// V(t, x_i, n_i) at this level's time for a batch, one call of the law; NumericalFailure
    /// naming the point unless all are finite.
    void normal_speeds(std::span<const Vec3> xs, std::span<const Vec3> n,
                       std::span<double> v) const {
        detail::checked_normal_speeds(law_, t_, xs, n, v);
    }

private:
    /// F at a point whose closest point of the triangles is p: p's distance less the height of
    /// the patch over p's triangle, Σ w_a w_b β_ab over its edges ab, β_ab = ½ (N_b − N_a)·(x_b −
    /// x_a) (zero at corners), with w p's barycentric weights. For a quadric through the vertices
    /// with normals N, the height of the surface over the plane of three of its points is this
    /// sum to O(h³); it is zero at the vertices and depends only on an edge's ends along it, so
    /// the patches meet continuously.
    double distance(const SurfacePoint& p) const {
        if (bulge_.empty()) return p.distance;
        const std::array<double, 3>& beta = bulge_[p.triangle];
        const std::array<double, 3>& w = p.weights;
        return p.distance - (w[0] * w[1] * beta[0] + w[1] * w[2] * beta[1] + w[2] * w[0] * beta[2]);
    }

    /// The normal of the distance field at x, p its closest point: the vertex normals
    /// interpolated at p where p's triangle has no corner among the vertices p depends on, so
    /// that a direction-dependent speed does not jump across the planes where ∇F turns from one
    /// triangle to the next on a smooth surface; at corners and sharp edges the exact ∇F, the
    /// fan of normals (x − p)/F, which rounds a growing edge and keeps a shrinking one sharp.
    Vec3 field_normal(Vec3 x, const SurfacePoint& p) const {
        const TriangleIndices& tri = surface_.triangles[p.triangle];
        bool smooth = true;
        for (int c = 0; c < 3; ++c)
            if (p.weights[c] > 0.0 && corner_[tri[c]]) smooth = false;
        if (smooth) {
            const Vec3 sum = p.weights[0] * normals_[tri[0]] + p.weights[1] * normals_[tri[1]] +
                             p.weights[2] * normals_[tri[2]];
            const double s = norm(sum);
            if (s > 0.0) return sum / s;
        }
        const Vec3 d = x - p.point;
        const double length = norm(d);
        if (length > 0.0) return (p.distance < 0.0 ? -1.0 : 1.0) * d / length;
        return tree_.normals().face[p.triangle];
    }

    const Surface& surface_;
    SurfaceDistanceTree tree_;
    const SurfaceVelocityLaw& law_;
    double t_;
    std::vector<Vec3> u_;        ///< vertex velocities, for the nearest-point extension
    std::vector<Vec3> normals_;  ///< vertex normals, for a normal law
    std::vector<char> corner_;   ///< vertices at a corner or sharp edge
    std::vector<std::array<double, 3>> bulge_;  ///< β of each triangle's edges, for patches
    double max_speed_ = 0.0;
    double max_bulge_ = 0.0;
};

/// A normal law's step with the distance field's normal N: F(x − k V N) = F(x) − k V along the
/// normal line, which also holds where the foot would cross the medial axis, so the level set is
/// the exact offset. The trapezoidal rule averages V at the foot at t and at x at t + k.
SurfaceStepResult advance_normal(const Surface& surface, double t, double k,
                                 const SurfaceVelocityLaw& law, const Box3& domain,
                                 const SurfaceStepOptions& options) {
    SurfaceStepResult result;
    const SurfaceLevel now(surface, t, k, law, domain, options, Extension::direct);
    // With |V| ≤ S, both G = F − kV and the corrector's F − k/2 (V + V') move at most kS from
    // F, which is within b of a distance: |G(x) − G(y)| ≤ |x − y| + 2 (kS + b).
    SurfaceContourOptions contour_options = options.contour;
    if (const std::optional<double> s = law.speed_bound())
        contour_options.distance_slack = 2.0 * (k * *s + now.max_bulge());
    const auto predictor = [&](std::span<const Vec3> xs, std::span<double> g) {
        detail::normal_predictor(now, k, xs, g);
    };
    SurfaceContour predicted = contour_surface(predictor, domain, contour_options);
    result.stats.predictor = predicted.stats;
    if (predicted.surface.empty()) return result;

    const SurfaceLevel next(predicted.surface, t + k, k, law, domain, options, Extension::direct);
    const auto corrector = [&](std::span<const Vec3> xs, std::span<double> g) {
        detail::normal_corrector(now, next, k, xs, g);
    };
    SurfaceContour corrected = contour_surface(corrector, domain, contour_options);
    result.stats.corrector = corrected.stats;
    result.surface = std::move(corrected.surface);
    return result;
}

/// The surface moved along its vertex normals (angle-weighted) by δ = (target − V)/A, each
/// vertex by at most a quarter of its shortest edge, which makes its volume target to O(δ²), the
/// vertices marked in `held` staying where they are. A vertex is held once the moved surface
/// meets itself at one of its triangles (exact predicates), as a fold of edges far shorter than
/// the shift would. Returns the surface and the volume added, or the surface itself and 0 when
/// no vertex is left to move.
std::pair<Surface, double> corrected_volume(const Surface& s, double target,
                                            std::vector<bool>& held) {
    const double v = volume(s);
    const double delta = (target - v) / area(s);
    const std::vector<Vec3> n = angle_weighted_normals(s);
    const VertexRings rings = vertex_rings(s);
    std::vector<Vec3> shift(s.vertices.size());
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        double shortest = std::numeric_limits<double>::infinity();
        for (const std::uint32_t j : rings.of(i))
            shortest = std::min(shortest, distance(s.vertices[i], s.vertices[j]));
        if (rings.of(i).empty()) continue;
        const double reach = 0.25 * shortest;
        shift[i] = std::clamp(delta, -reach, reach) * n[i];
    }
    for (int attempt = 0; attempt < 16; ++attempt) {
        Surface moved = s;
        for (std::size_t i = 0; i < s.vertices.size(); ++i)
            if (!held[i]) moved.vertices[i] += shift[i];
        const auto contact = find_self_intersection(moved);
        if (!contact) {
            const double added = volume(moved) - v;
            return {std::move(moved), added};
        }
        bool newly_held = false;
        for (const std::uint32_t t : {contact->first, contact->second}) {
            for (const std::uint32_t i : s.triangles[t]) {
                newly_held = newly_held || !held[i];
                held[i] = true;
            }
        }
        if (!newly_held) break;
    }
    return {s, 0.0};
}

/// A foot point's velocity, checked (detail::checked_velocity), as curves' steps check it.
Vec3 finite(Vec3 w, const SurfaceVelocityLaw& law, double t, Vec3 x) {
    return detail::checked_velocity(w, law.name(), t, x);
}

SurfaceStepResult advance_contours(const Surface& surface, double t, double k,
                                   const SurfaceVelocityLaw& law, const Box3& domain,
                                   const SurfaceStepOptions& given) {
    SurfaceStepOptions options = given;
    options.contour.eta = given.resolved_eta();
    if (!(k > 0.0) || !std::isfinite(k))
        throw InvalidInput(fmt::format("time step must be positive and finite, got {}", k));
    if (surface.empty()) throw InvalidInput("the surface to advance has no triangles");
    const Extension extension = options.resolved_extension(law);
    if (extension == Extension::whitney)
        throw InvalidInput("the Whitney extension is for curves: use nearest-point or direct");
    if (extension == Extension::direct && !law.is_field() && !law.is_normal_law()) {
        throw InvalidInput(
            fmt::format("velocity '{}' is not defined off the surface: use the nearest-point "
                        "extension",
                        law.name()));
    }
    if (extension == Extension::direct && law.is_normal_law())
        return advance_normal(surface, t, k, law, domain, options);

    SurfaceStepResult result;
    SurfaceLevel now(surface, t, k, law, domain, options, extension);
    if (extension == Extension::direct) {
        // A flow field: G(x) = F(foot of the characteristic through x), one contour, the feet
        // traced to a tenth of ε.
        const int substeps = detail::departure_substeps(
            law, t, k, std::span<const Vec3>(surface.vertices),
            detail::departure_tolerance * options.contour.resolved_eps());
        const auto g = [&](std::span<const Vec3> xs, std::span<double> values) {
            const std::vector<Vec3> feet = detail::runge_kutta_feet(law, t, k, xs, substeps);
            parallel_for(
                xs.size(), [&](std::size_t i) { values[i] = now.distance(feet[i]); },
                expensive_grain);
        };
        SurfaceContour traced = contour_surface(g, domain, options.contour);
        result.stats.corrector = traced.stats;
        result.surface = std::move(traced.surface);
        return result;
    }

    // Predictor (Eq. 4): G̃(x) = F(x − k W(x); S(t)). F is within b of an exact distance (the
    // patches' bulge) and |W| ≤ max|W|, so |G̃(x) − G̃(y)| ≤ |x − y| + 2 (k max|W| + b): points
    // far from the surface are settled by their neighbours without a query.
    SurfaceContourOptions contour_options = options.contour;
    contour_options.distance_slack = 2.0 * (k * now.max_speed() + now.max_bulge());
    const auto predictor = [&](std::span<const Vec3> xs, std::span<double> values) {
        parallel_for(
            xs.size(),
            [&](std::size_t i) {
                values[i] = now.distance(xs[i] - k * finite(now.velocity(xs[i]), law, t, xs[i]));
            },
            expensive_grain);
    };
    SurfaceContour predicted = contour_surface(predictor, domain, contour_options);
    result.stats.predictor = predicted.stats;
    if (predicted.surface.empty()) return result;  // everything vanished within the step

    // Corrector (Eq. 5): the trapezoidal rule along the characteristic through x, whose foot
    // moves at most k/2 (max|W(t)| + max|W(t + k)|) from x.
    SurfaceLevel next(predicted.surface, t + k, k, law, domain, options, extension);
    const auto corrector = [&](std::span<const Vec3> xs, std::span<double> values) {
        parallel_for(
            xs.size(),
            [&](std::size_t i) {
                const Vec3 x = xs[i];
                const Vec3 foot = x - k * finite(now.velocity(x), law, t, x);
                const Vec3 w_foot = finite(now.velocity(foot), law, t, foot);
                const Vec3 w_next = finite(next.velocity(x), law, t + k, x);
                values[i] = now.distance(x - (0.5 * k) * (w_foot + w_next));
            },
            expensive_grain);
    };
    const auto contour_corrector = [&] {
        contour_options.distance_slack =
            2.0 * (0.5 * k * (now.max_speed() + next.max_speed()) + now.max_bulge());
        return contour_surface(corrector, domain, contour_options);
    };
    SurfaceContour corrected = contour_corrector();
    if (law.preserves_area() && !corrected.surface.empty()) {
        // The nonlocal law's mean, fixed on the surface the step produces as for curves
        // (docs/algorithms/evolve.md): moved by the volume the corrector's surface gained over
        // k times its area, at both levels, and the corrector contoured again.
        const double gained = volume(corrected.surface) - volume(surface);
        const double s = -gained / (k * area(corrected.surface));
        now.add_normal_speed(s);
        next.add_normal_speed(s);
        const std::size_t first_evals = corrected.stats.g_evals;
        corrected = contour_corrector();
        corrected.stats.g_evals += first_evals;  // both contours' cost
    }
    result.stats.corrector = corrected.stats;
    result.surface = std::move(corrected.surface);
    return result;
}

}  // namespace

SurfaceStepResult advance(const Surface& surface, double t, double k, const SurfaceVelocityLaw& law,
                          const Box3& domain, const SurfaceStepOptions& options) {
    SurfaceStepResult result = advance_contours(surface, t, k, law, domain, options);
    if (options.resolved_volume_correction(law) && !result.surface.empty()) {
        // Each shift leaves O(δ²) of the volume to give back, more where vertices were held
        // back: a few more shifts leave rounding.
        const double target = volume(surface);
        std::vector<bool> held(result.surface.vertices.size(), false);
        for (int shift = 0; shift < 8; ++shift) {
            auto [moved, added] = corrected_volume(result.surface, target, held);
            if (added == 0.0) break;
            result.surface = std::move(moved);
            result.stats.volume_correction += added;
        }
    }
    return result;
}

}  // namespace slc
