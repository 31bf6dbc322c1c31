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

#include "predictor_corrector.hpp"
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

/// How a step reads a surface beyond its triangles: the vertex normals the field normal uses,
/// the corners, and each triangle's edge bulges β for curved patches (SurfaceStepOptions::patches).
struct PatchReading {
    std::vector<Vec3> normals;  ///< the fitted normals, angle-weighted within two rings of a corner
    std::vector<char> corner;   ///< vertices at a corner or sharp edge
    std::vector<std::array<double, 3>> bulge;  ///< β of each triangle's edges; empty: flat
    double max_bulge = 0.0;  ///< a bound on the patches' height over their triangles, max|β|/3
};

/// The reading of `surface` with fitted vertex normals `normals` and its pseudo-normals.
PatchReading read_patches(const Surface& surface, std::vector<Vec3> normals,
                          const PseudoNormals& pseudo, bool patches) {
    PatchReading r;
    // Corners: a triangle turns more than corner_angle from the angle-weighted normal (the
    // tree's vertex pseudo-normal, scaled to unit length). The fitted normals are second
    // order on smooth parts, but a fit across a corner tilts them: within two rings of a
    // corner the angle-weighted normal (the face's own on a flat face) is kept.
    std::vector<Vec3> weighted = pseudo.vertex;
    for (Vec3& n : weighted)
        if (const double length = norm(n); length > 0.0) n = n / length;
    const std::vector<Vec3>& face = pseudo.face;
    const double limit = std::cos(corner_angle);
    const std::size_t n = surface.triangles.size();
    std::vector<std::uint8_t> turned(n);  // bit c: corner c turns from the face
    parallel_for(n, [&](std::size_t f) {
        unsigned bits = 0;
        for (int c = 0; c < 3; ++c)
            if (dot(face[f], weighted[surface.triangles[f][c]]) < limit) bits |= 1u << c;
        turned[f] = static_cast<std::uint8_t>(bits);
    });
    r.corner.assign(surface.vertices.size(), 0);
    for (std::size_t f = 0; f < n; ++f)
        for (int c = 0; c < 3; ++c)
            if (turned[f] >> c & 1u) r.corner[surface.triangles[f][c]] = 1;
    const VertexRings rings = vertex_rings(surface);
    parallel_for(surface.vertices.size(), [&](std::size_t v) {
        bool near = r.corner[v] != 0;
        for (const std::uint32_t w : rings.of(v)) {
            near = near || r.corner[w];
            for (const std::uint32_t u : rings.of(w)) near = near || r.corner[u];
        }
        if (near) normals[v] = weighted[v];
    });
    if (patches) {
        const double patch_limit = std::cos(patch_angle);
        r.bulge.resize(n);
        parallel_for(n, [&](std::size_t f) {
            const TriangleIndices& tri = surface.triangles[f];
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = tri[e], b = tri[(e + 1) % 3];
                // Flat at a corner, and where the normals turn too fast along the edge for a
                // quadric to follow.
                const bool flat =
                    r.corner[a] || r.corner[b] || dot(normals[a], normals[b]) < patch_limit;
                r.bulge[f][e] = flat ? 0.0
                                     : 0.5 * dot(normals[b] - normals[a],
                                                 surface.vertices[b] - surface.vertices[a]);
            }
        });
        for (const std::array<double, 3>& beta : r.bulge)
            for (const double b : beta) r.max_bulge = std::max(r.max_bulge, std::abs(b) / 3.0);
    }
    r.normals = std::move(normals);
    return r;
}

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
        std::vector<Vec3> fitted = geometry.normals.empty()
                                       ? surface_geometry(surface, {.curvature = false}).normals
                                       : std::move(geometry.normals);
        read_ = read_patches(surface, std::move(fitted), tree_.normals(), options.patches);
    }

    /// The largest speed of the vertex velocities (nearest-point extension; 0 without them): the
    /// extension interpolates them, so |W(x)| never exceeds it.
    double max_speed() const { return max_speed_; }
    /// A normal law's bound on |V|, when it gives one.
    std::optional<double> normal_speed_bound() const { return law_.speed_bound(); }
    /// A normal law's speed when it is one number everywhere (VelocityLaw::constant_speed).
    std::optional<double> constant_speed() const { return law_.constant_speed(); }
    /// Adds the normal speed s to every vertex velocity, along the fitted normals: a move of the
    /// mean of a nonlocal law, whose speeds are V − mean.
    void add_normal_speed(double s) {
        max_speed_ = 0.0;
        for (std::size_t v = 0; v < u_.size(); ++v) {
            u_[v] += s * read_.normals[v];
            max_speed_ = std::max(max_speed_, norm(u_[v]));
        }
    }
    /// A bound on the patches' height over their triangles, |F − the triangles' distance| (0
    /// without patches): Σ w_a w_b β_ab ≤ max|β| Σ w_a w_b ≤ max|β|/3.
    double max_bulge() const { return read_.max_bulge; }

    /// F(x): the signed distance to this level's surface read as curved patches
    /// (SurfaceStepOptions::patches), or to its triangles.
    double distance(Vec3 x) const { return distance(tree_.closest_point(x)); }
    /// The exact signed distance to this level's triangles, whatever SurfaceStepOptions::patches
    /// says.
    double chord_distance(Vec3 x) const { return tree_.closest_point(x).distance; }
    /// W(x): the vertex velocities at the nearest point of the surface (nearest-point extension).
    Vec3 velocity(Vec3 x) const {
        return nearest_point_extension<Vec3>(surface_, u_, tree_.nearest_point(x));
    }
    /// W(x) for the corrector's end of the characteristic that brought `arriving`: W(x), since
    /// the nearest-point extension of surfaces keeps no sides of shocks apart (the step of
    /// curves does, step.cpp).
    Vec3 velocity(Vec3 x, Vec3 /*arriving*/) const { return velocity(x); }
    /// The closest point of this level's triangles and W(x), from one closest-point query.
    std::pair<SurfacePoint, Vec3> closest_point_and_velocity(Vec3 x) const {
        const SurfacePoint p = tree_.closest_point(x);
        return {p, nearest_point_extension<Vec3>(surface_, u_, p)};
    }

    /// F and the normal a normal law sees (field_normal) at a batch of points, in parallel.
    void distances_and_normals(std::span<const Vec3> xs, std::span<double> f,
                               std::span<Vec3> n) const {
        detail::distances_and_normals(
            tree_, xs, f, n, [this](const SurfacePoint& p) { return distance(p); },
            [this](Vec3 x, const SurfacePoint& p) { return field_normal(x, p); });
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
        if (read_.bulge.empty()) return p.distance;
        const std::array<double, 3>& beta = read_.bulge[p.triangle];
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
            if (p.weights[c] > 0.0 && read_.corner[tri[c]]) smooth = false;
        if (smooth) {
            const Vec3 sum = p.weights[0] * read_.normals[tri[0]] +
                             p.weights[1] * read_.normals[tri[1]] +
                             p.weights[2] * read_.normals[tri[2]];
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
    std::vector<Vec3> u_;  ///< vertex velocities, for the nearest-point extension
    PatchReading read_;    ///< vertex normals (for a normal law), corners, patches' bulges
    double max_speed_ = 0.0;
};

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
    const auto make_level = [&](const Surface& s, double time) {
        return SurfaceLevel(s, time, k, law, domain, options, extension);
    };
    if (extension == Extension::direct && law.is_normal_law()) {
        return detail::advance_normal_law<SurfaceStepResult>(surface, t, k, domain, options.contour,
                                                             make_level);
    }
    SurfaceLevel now(surface, t, k, law, domain, options, extension);
    if (extension == Extension::direct) {
        return detail::advance_flow<SurfaceStepResult>(surface, t, k, law, domain, options.contour,
                                                       now);
    }
    return detail::advance_extended<SurfaceStepResult>(
        surface, t, k, law, domain, options.contour, now, make_level,
        [](const Surface& s) { return std::pair(volume(s), area(s)); },
        options.resolved_volume_correction(law));
}

}  // namespace

double step_volume(const Surface& surface, const SurfaceStepOptions& options) {
    const double triangles = volume(surface);
    if (!options.patches || surface.empty()) return triangles;
    const PatchReading reading =
        read_patches(surface, surface_geometry(surface, {.curvature = false}).normals,
                     pseudo_normals(surface), true);
    // The patch over a triangle rises Σ w_a w_b β_ab above it, and ∫ w_a w_b dA = A/12.
    double bulges = 0.0;
    for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
        const std::array<double, 3>& beta = reading.bulge[f];
        bulges += area(surface.triangle(f)) / 12.0 * (beta[0] + beta[1] + beta[2]);
    }
    return triangles + bulges;
}

SurfaceStepResult advance(const Surface& surface, double t, double k, const SurfaceVelocityLaw& law,
                          const Box3& domain, const SurfaceStepOptions& options) {
    SurfaceStepResult result = advance_contours(surface, t, k, law, domain, options);
    if (options.resolved_volume_correction(law) && !result.surface.empty()) {
        // Each vertex moves along its angle-weighted normal, by at most a quarter of its shortest
        // edge; a vertex is held once the moved surface meets itself at one of its triangles
        // (exact predicates), as a fold of edges far shorter than the shift would.
        const auto shifts = [](const Surface& s, const std::vector<double>& missing) {
            const double delta = missing[0] / area(s);
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
            return shift;
        };
        const auto moved = [](const Surface& s, const std::vector<Vec3>& shift,
                              const std::vector<bool>& held) {
            Surface out = s;
            for (std::size_t i = 0; i < s.vertices.size(); ++i)
                if (!held[i]) out.vertices[i] += shift[i];
            return out;
        };
        auto [out, added] = detail::restored_measure(
            result.surface, {volume(surface)},
            [](const Surface& s) { return std::vector<double>{volume(s)}; }, shifts, moved,
            [](const Surface& s) { return find_self_intersection(s); },
            [](const Surface& s, std::uint32_t f) { return s.triangles[f]; });
        result.surface = std::move(out);
        result.stats.volume_correction = added;
    }
    return result;
}

}  // namespace slc
