// The exact signed distance to a union of discs or balls: candidates on faces, edges and corners.
#include "slc/geometry/balls.hpp"

#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <utility>

namespace slc {
namespace {

template <int dim>
using Balls = std::span<const Ball<dim>>;

/// The nearest boundary point so far, from candidates that may be covered by another ball.
template <int dim>
class Nearest {
public:
    Nearest(Balls<dim> balls, PointOf<dim> x) : balls_(balls), x_(x) {}

    /// Takes p, a point on the spheres of the balls listed in own, if no other ball covers it.
    void offer(PointOf<dim> p, std::initializer_list<std::size_t> own) {
        const double d = distance(x_, p);
        if (!(d < best_)) return;
        for (std::size_t j = 0; j < balls_.size(); ++j) {
            bool mine = false;
            for (std::size_t i : own) mine = mine || i == j;
            // A relative margin keeps the corner itself, which lies on the spheres of its balls
            // to rounding.
            const Ball<dim>& b = balls_[j];
            if (!mine && distance(p, b.centre) < b.radius * (1.0 - 1e-12)) return;
        }
        best_ = d;
    }
    double best() const { return best_; }

private:
    Balls<dim> balls_;
    PointOf<dim> x_;
    double best_ = std::numeric_limits<double>::infinity();
};

/// Where the spheres of a and b meet: the centre q of their circle (or point pair), its radius
/// h and the unit axis u from a to b; none when they do not cross.
template <int dim>
struct Crossing {
    PointOf<dim> q, u;
    double h;
};

template <int dim>
std::optional<Crossing<dim>> crossing(const Ball<dim>& a, const Ball<dim>& b) {
    if (!(a.radius > 0.0) || !(b.radius > 0.0)) return std::nullopt;
    const double d = distance(a.centre, b.centre);
    if (!(d > 0.0) || d >= a.radius + b.radius || d <= std::abs(a.radius - b.radius))
        return std::nullopt;
    const PointOf<dim> u = (b.centre - a.centre) / d;
    const double along = (d * d + a.radius * a.radius - b.radius * b.radius) / (2.0 * d);
    const double h2 = a.radius * a.radius - along * along;
    if (!(h2 > 0.0)) return std::nullopt;
    return Crossing<dim>{a.centre + along * u, u, std::sqrt(h2)};
}

/// The corners and edges of the union (its faces are offered by the caller).
void offer_edges_and_corners(Balls<2> balls, Vec2 /*x*/, Nearest<2>& nearest) {
    for (std::size_t i = 0; i < balls.size(); ++i)
        for (std::size_t j = i + 1; j < balls.size(); ++j)
            if (const auto c = crossing(balls[i], balls[j]))
                for (double side : {-1.0, 1.0})
                    nearest.offer(c->q + side * c->h * perp(c->u), {i, j});
}

void offer_edges_and_corners(Balls<3> balls, Vec3 x, Nearest<3>& nearest) {
    for (std::size_t i = 0; i < balls.size(); ++i)
        for (std::size_t j = i + 1; j < balls.size(); ++j) {
            const auto c = crossing(balls[i], balls[j]);
            if (!c) continue;
            // An orthonormal frame (n1, n2) of the circle's plane.
            const Vec3 e = cross(c->u, std::abs(c->u.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
            const Vec3 n1 = e / norm(e), n2 = cross(c->u, n1);
            // The nearest point of the circle: x's offset from the axis, scaled to h. On the
            // axis every point of the circle is as near, and its corners (below) as well.
            const Vec3 w = (x - c->q) - dot(x - c->q, c->u) * c->u;
            nearest.offer(c->q + c->h * (norm(w) > 0.0 ? w / norm(w) : n1), {i, j});
            // The corners, where a third sphere crosses the circle: c->q + h (cos φ n1 + sin φ n2)
            // with |p − c_k|² = r_k², that is A cos φ + B sin φ = C.
            for (std::size_t k = j + 1; k < balls.size(); ++k) {
                if (!(balls[k].radius > 0.0)) continue;
                const Vec3 m = c->q - balls[k].centre;
                const double a = 2.0 * c->h * dot(m, n1), b = 2.0 * c->h * dot(m, n2);
                const double rhs = balls[k].radius * balls[k].radius - norm2(m) - c->h * c->h;
                const double ab = std::hypot(a, b);
                if (!(ab > 0.0) || std::abs(rhs) > ab) continue;
                const double phi0 = std::atan2(b, a), spread = std::acos(rhs / ab);
                for (double phi : {phi0 - spread, phi0 + spread})
                    nearest.offer(c->q + c->h * (std::cos(phi) * n1 + std::sin(phi) * n2),
                                  {i, j, k});
            }
        }
}

}  // namespace

template <int dim>
double union_of_balls_distance(std::span<const Ball<dim>> balls, PointOf<dim> x) {
    // A ball of radius ≤ 0 has no sphere, crosses nothing and covers nothing.
    bool inside = false;
    Nearest<dim> nearest(balls, x);
    for (std::size_t i = 0; i < balls.size(); ++i) {
        const Ball<dim>& b = balls[i];
        if (!(b.radius > 0.0)) continue;
        const double r = distance(x, b.centre);
        inside = inside || r < b.radius;
        // The radial projection (from the centre itself, any point of the sphere is as near).
        PointOf<dim> towards{};
        towards.x = 1.0;
        if (r > 0.0) towards = (x - b.centre) / r;
        nearest.offer(b.centre + b.radius * towards, {i});
    }
    offer_edges_and_corners(balls, x, nearest);
    return inside ? -nearest.best() : nearest.best();
}

template double union_of_balls_distance<2>(std::span<const Ball<2>>, Vec2);
template double union_of_balls_distance<3>(std::span<const Ball<3>>, Vec3);

}  // namespace slc
