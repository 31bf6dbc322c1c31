// The embedded geometry module: the steps BuildLocalMesh, Distance, EmbeddedGeometry and
// Interpolate of paper §4.3, with Eq. 9 evaluated by ENO differences (§3.2).
#include "slc/geometry_modules/embedded.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "slc/geometry_modules/eno.hpp"

namespace slc {
namespace {

/// Largest accepted M: keeps lattice indices of a curve inside its domain far below 2^30.
constexpr int max_mesh_size = 1 << 24;
/// Points interpolated together on one thread, reusing the stencils of the lattice cells they
/// share.
constexpr std::size_t points_per_block = 64;
/// Largest accepted S: far beyond what stabilizes any curvature flow (the paper uses 0..4).
constexpr int max_smoothing = 64;

void validate(const EmbeddedOptions& o) {
    if (o.mesh < 2 || o.mesh > max_mesh_size)
        throw InvalidInput(fmt::format("embedded mesh size M must be in 2..2^24, got {}", o.mesh));
    if (o.eno_order < 1 || o.eno_order > eno::max_order)
        throw InvalidInput(
            fmt::format("ENO order E must be in 1..{}, got {}", eno::max_order, o.eno_order));
    if (!(o.average >= 0.0) || !std::isfinite(o.average))
        throw InvalidInput(fmt::format(
            "embedded curvature's averaging width must be finite and >= 0, got {}", o.average));
    if (!(o.eno_bias >= 1.0) || !std::isfinite(o.eno_bias))
        throw InvalidInput(fmt::format(
            "ENO bias of the embedded module must be finite and >= 1, got {}", o.eno_bias));
    if (o.smoothing < 0 || o.smoothing > max_smoothing)
        throw InvalidInput(
            fmt::format("smoothing passes S must be in 0..{}, got {}", max_smoothing, o.smoothing));
}

/// N = ∇F/|∇F| by ENO differences of order E with the given bias, then S smoothing passes and
/// renormalization.
std::vector<Vec2> mesh_normals(const LocalMesh& mesh, std::span<const double> f, int order,
                               double bias, int passes) {
    std::vector<double> nx = derivative(mesh, f, Axis::x, order, bias);
    std::vector<double> ny = derivative(mesh, f, Axis::y, order, bias);
    auto normalize = [&](std::size_t k) {
        const double length = std::hypot(nx[k], ny[k]);
        if (length > 0.0) {
            nx[k] /= length;
            ny[k] /= length;
        }
    };
    parallel_for(mesh.size(), normalize);
    if (passes > 0) {
        nx = smoothed(mesh, nx, passes);
        ny = smoothed(mesh, ny, passes);
        parallel_for(mesh.size(), normalize);
    }
    std::vector<Vec2> n(mesh.size());
    for (std::size_t k = 0; k < n.size(); ++k) n[k] = {nx[k], ny[k]};
    return n;
}

/// C = −∇·N by ENO differences of order E, then S smoothing passes.
std::vector<double> mesh_curvature(const LocalMesh& mesh, std::span<const Vec2> n, int order,
                                   int passes) {
    std::vector<double> nx(n.size()), ny(n.size());
    for (std::size_t k = 0; k < n.size(); ++k) {
        nx[k] = n[k].x;
        ny[k] = n[k].y;
    }
    const std::vector<double> dx = derivative(mesh, nx, Axis::x, order);
    const std::vector<double> dy = derivative(mesh, ny, Axis::y, order);
    std::vector<double> c(n.size());
    for (std::size_t k = 0; k < c.size(); ++k) c[k] = -(dx[k] + dy[k]);
    return passes > 0 ? smoothed(mesh, c, passes) : c;
}

}  // namespace

int default_mesh_size(int depth) {
    if (depth < 0 || depth > 29)
        throw InvalidInput(fmt::format("tree depth K must be in 0..29, got {}", depth));
    return 1 << (depth + 1);
}

EmbeddedFields embedded_fields(const DistanceTree& tree, const EmbeddedOptions& options) {
    validate(options);
    const Box domain = tree.tree().root_box();
    const double h = domain.width() / options.mesh;
    // Cell-centred: contour vertices lie on the contouring tree's cell edges, and at the default
    // M = 2^(K+1) a lattice anchored at the corner would put them on its lines, where ENO
    // stencils see the polygon's kinks in step with the mesh: the Table 7 cell 80/1/5/0 has
    // E∞ = 0.0449 with the lattice anchored at the corner, 0.0111 offset.
    EmbeddedFields out;
    out.mesh = LocalMesh(tree.curves(), domain.lo + Vec2{0.5 * h, 0.5 * h}, h,
                         options.eno_order + options.smoothing);
    out.distance = tree.signed_distances(out.mesh.points());
    out.normals = mesh_normals(out.mesh, out.distance, options.eno_order, options.eno_bias,
                               options.smoothing);
    out.curvature = mesh_curvature(out.mesh, out.normals, options.eno_order, options.smoothing);
    return out;
}

VertexGeometry interpolate_geometry(const EmbeddedFields& fields, std::span<const Vec2> points,
                                    int order) {
    if (order < 1 || order > eno::max_order)
        throw InvalidInput(
            fmt::format("ENO order E must be in 1..{}, got {}", eno::max_order, order));
    const std::size_t n = fields.normals.size();
    std::vector<double> nx(n), ny(n);
    for (std::size_t k = 0; k < n; ++k) {
        nx[k] = fields.normals[k].x;
        ny[k] = fields.normals[k].y;
    }
    VertexGeometry g{std::vector<Vec2>(points.size()), std::vector<double>(points.size())};
    std::vector<char> missing(points.size(), 0);
    // In blocks of consecutive points, which often share a lattice cell and so its stencils.
    const std::array<std::span<const double>, 3> values{nx, ny, fields.curvature};
    const std::size_t blocks = (points.size() + points_per_block - 1) / points_per_block;
    parallel_for(
        blocks,
        [&](std::size_t b) {
            CellStencils cell;
            const std::size_t end = std::min(points.size(), (b + 1) * points_per_block);
            for (std::size_t i = b * points_per_block; i < end; ++i) {
                std::array<double, 3> at;
                if (!interpolate(fields.mesh, values, points[i], order, at, &cell)) {
                    missing[i] = 1;
                    continue;
                }
                const Vec2 v{at[0], at[1]};
                const double length = norm(v);
                g.normals[i] = length > 0.0 ? v / length : v;
                g.curvature[i] = at[2];
            }
        },
        2);
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (missing[i] != 0) {
            throw NumericalFailure(
                fmt::format("embedded geometry: point {} ({}, {}) lies outside the local mesh "
                            "around the interface",
                            i, points[i].x, points[i].y));
        }
    }
    return g;
}

VertexGeometry embedded_geometry(const DistanceTree& tree, const EmbeddedOptions& options) {
    const EmbeddedFields fields = embedded_fields(tree, options);
    VertexGeometry g = interpolate_geometry(fields, tree.curves().points(), options.eno_order);
    if (options.average > 0.0) {
        g.curvature = average_along_curves(tree.curves(), g.curvature,
                                           options.average * fields.mesh.spacing());
    }
    return g;
}

VertexGeometry embedded_geometry(const Interface& curves, Box domain,
                                 const EmbeddedOptions& options) {
    validate(options);
    const int depth = static_cast<int>(std::lround(std::log2(static_cast<double>(options.mesh))));
    const DistanceTree tree(curves, domain,
                            {.depth = std::clamp(depth, 1, 16), .triangulate = false});
    return embedded_geometry(tree, options);
}

}  // namespace slc
