/// @file
/// Velocity laws (DESIGN §3, paper §3 and §4.3 "Velocity(t, Γ)"): the interface a law implements,
/// the call that hands it the vertex geometry it asks for and checks what it returns, and adapters
/// that turn a small callable into a law. Written once for curves (dim = 2: VelocityLaw) and
/// surfaces (dim = 3: SurfaceVelocityLaw, DESIGN §8); Space<dim> (slc/core/space.hpp) names the
/// types that differ.
#pragma once

#include <concepts>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/core/box3.hpp"
#include "slc/core/names.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/space.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "slc/geometry_modules/embedded.hpp"
#include "slc/geometry_modules/surface_geometry.hpp"
#include "slc/geometry_modules/vertex_geometry.hpp"
#include "slc/velocity/invariants.hpp"

namespace slc {

/// The vertices of curves, in Interface::points() order.
inline std::span<const Vec2> vertex_points(const Interface& curves) { return curves.points(); }
/// The vertices of a surface.
inline std::span<const Vec3> vertex_points(const Surface& surface) { return surface.vertices; }

/// Which geometry module computes the vertex normals and curvature a law on curves needs:
/// intrinsic (paper §3.1, Equations 7, 8; no mesh), embedded (§3.2, Equation 9 on a local mesh;
/// needs a distance tree), or arclength (circumcircle curvature averaged along the curve; no
/// mesh). Surfaces have one module (surface_geometry()), and a law on surfaces leaves it unset.
enum class GeometryModule { intrinsic, embedded, arclength };
/// The modules' names, as --geometry and Python spell them.
inline constexpr Named<GeometryModule> geometry_module_names[] = {
    {"intrinsic", GeometryModule::intrinsic},
    {"embedded", GeometryModule::embedded},
    {"arclength", GeometryModule::arclength}};

/// What a law needs at the vertices besides their positions.
struct GeometryNeeds {
    bool normals = false;    ///< outward unit normals N
    bool curvature = false;  ///< curvature C = −∇·N
    /// Which module computes them; unset: resolved_module().
    std::optional<GeometryModule> module = std::nullopt;
    /// True for a law that fits smooth curves through the vertices itself (the potential laws):
    /// the step then reads the curves as arcs through their vertices, not as chords
    /// (StepOptions::arcs), whose loss of a little each step the law would see as wrinkles.
    bool smooth = false;

    /// True when the law needs normals or curvature.
    bool any() const { return normals || curvature; }
    /// The module as given, or by default the arclength module when curvature is needed (its
    /// step is stable at any k and any h; docs/algorithms/geometry.md) and the intrinsic one for
    /// normals alone.
    GeometryModule resolved_module() const {
        return module.value_or(curvature ? GeometryModule::arclength : GeometryModule::intrinsic);
    }
};

/// A velocity law: the velocity u of every vertex of Γ at time t, points moving with dy/dt = u
/// (DESIGN §1), so u = v·N moves the interface outward for normal speed v > 0. dim = 2 for curves
/// (VelocityLaw), 3 for surfaces (SurfaceVelocityLaw).
template <int dim>
class BasicVelocityLaw {
public:
    using Point = PointOf<dim>;        ///< Vec2 or Vec3
    using Shape = ShapeOf<dim>;        ///< Interface or Surface
    using Region = RegionOf<dim>;      ///< Box or Box3
    using Geometry = GeometryOf<dim>;  ///< VertexGeometry or SurfaceGeometry

    virtual ~BasicVelocityLaw() = default;

    /// The law's name, used in error messages ("rotation", or the user's).
    virtual std::string name() const = 0;
    /// The vertex geometry velocities() needs; the default is none.
    virtual GeometryNeeds needs() const { return {}; }
    /// u at every vertex of the interface at time t. geometry holds normals and curvature (one
    /// per vertex) from the module needs() names when needs().any(), and is empty otherwise.
    /// Must return one vector per vertex.
    virtual std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                                 const GeometryOf<dim>& geometry) const = 0;

    /// True for a law defined everywhere (a flow field such as rotation), which can then be
    /// sampled at any points instead of extended from the vertices.
    virtual bool is_field() const { return false; }
    /// The flow field at time t at every point; out.size() == points.size(). Throws InvalidInput
    /// unless is_field(). field_velocities() calls it and checks the answer.
    virtual void sample(double t, std::span<const PointOf<dim>> points,
                        std::span<PointOf<dim>> out) const;

    /// True for a law whose exact flow keeps the enclosed area (volume, for surfaces): the step
    /// then restores what each contour loses (StepOptions::area_correction).
    virtual bool preserves_area() const { return false; }
    /// What the law's exact motion keeps or cannot do, which the run loop checks after every step
    /// (evolve/guards.hpp). Default: the area when preserves_area(), nothing else.
    virtual Invariants invariants() const { return {.keeps_area = preserves_area()}; }

    /// True for a normal law u = V(t, x, N)·N whose speed V is known for any point x and any unit
    /// normal N (unit-normal, anisotropic, a user's V): the step can then evaluate it off the
    /// interface with the normal of the distance field (Extension::direct), so that corners move
    /// as the exact (viscosity) solution moves them.
    virtual bool is_normal_law() const { return false; }
    /// V(t, points[i], normals[i]) for every i; out.size() == points.size() == normals.size(),
    /// normals of unit length. Throws InvalidInput unless is_normal_law().
    virtual void normal_speeds(double t, std::span<const PointOf<dim>> points,
                               std::span<const PointOf<dim>> normals, std::span<double> out) const;
    /// A bound on |V| over every time, point and unit normal, for a normal law that knows one
    /// (a constant speed: |s|), or nothing. The step of surfaces then settles points far from
    /// the surface without evaluating V or the distance there (SurfaceContourOptions::
    /// distance_slack); the surfaces are the same. A run refuses a bound times its time span
    /// beyond the coordinate limit (the arithmetic would overflow).
    virtual std::optional<double> speed_bound() const { return std::nullopt; }
    /// V, for a normal law whose speed is one number at every time, point and normal
    /// (unit-normal, a speed expression that reads no variable), or nothing. The step's
    /// trapezoidal corrector then gives G = F − k/2 (V + V), the predictor's F − kV to the last
    /// bit, and the predicted contour is the step's.
    virtual std::optional<double> constant_speed() const { return std::nullopt; }

    /// The rate (1/time) at which the law moves the stiffest detail of a curve or surface whose
    /// curvature is `curvature` (its sharpest turn): a step k with k·stiffness ≫ 1 holds such
    /// details rather than moving them (the potential laws' filter of stiff modes). 0 for laws
    /// whose step needs no such bound. A user's run takes enough steps for its start
    /// (default_run_options).
    virtual double stiffness(double curvature) const {
        (void)curvature;
        return 0.0;
    }

    /// The closed box outside which the law is not known (a velocity given on a grid), or
    /// nothing for a law known everywhere. run() refuses initial curves that leave it and ends
    /// with an error when the curves leave it; velocities() and sample() must still answer at
    /// every point, since contouring samples the whole domain.
    virtual std::optional<Region> extent() const { return std::nullopt; }
};

/// A law moving curves in the plane.
using VelocityLaw = BasicVelocityLaw<2>;
/// A law moving surfaces in space.
using SurfaceVelocityLaw = BasicVelocityLaw<3>;

extern template class BasicVelocityLaw<2>;
extern template class BasicVelocityLaw<3>;

/// The first vertex of curves outside law.extent(), or nothing when every vertex lies inside it
/// (always, for a law without an extent). O(number of vertices).
std::optional<std::size_t> vertex_outside_extent(const VelocityLaw& law, const Interface& curves);

/// Throws InvalidInput, naming the law, its extent and the vertex, when a vertex of curves lies
/// outside law.extent().
void require_inside_extent(const VelocityLaw& law, const Interface& curves);

/// Throws InvalidInput, naming the law (`what`, as "speed 'a - C'") and the first vertex x[i]
/// where slope[i] = dv/dC, the normal speed's derivative in the curvature C, is below −1e−6:
/// motion backward in curvature (a − C moves the most convex parts out the fastest) is
/// ill-posed, the heat equation backward in time, its wiggles growing at every scale. The speed
/// expressions and the Python laws that read C both check their slopes here.
void require_forward_in_curvature(const std::string& what, std::span<const Vec2> x,
                                  std::span<const double> slope);
/// As above, at a surface's vertices.
void require_forward_in_curvature(const std::string& what, std::span<const Vec3> x,
                                  std::span<const double> slope);

/// The base of flow fields u = f(t, x) known everywhere (rotation, a lattice, an expression):
/// is_field() is true and the vertex velocities are the field sampled at the vertices. A law
/// implements sample().
template <int dim>
class BasicFlowFieldLaw : public BasicVelocityLaw<dim> {
public:
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>&) const final {
        const std::span<const PointOf<dim>> x = vertex_points(interface);
        std::vector<PointOf<dim>> u(x.size());
        this->sample(t, x, u);
        return u;
    }
    /// True: a flow field.
    bool is_field() const final { return true; }
};
/// A flow field moving curves.
using FlowFieldLaw = BasicFlowFieldLaw<2>;
/// A flow field moving surfaces.
using SurfaceFlowFieldLaw = BasicFlowFieldLaw<3>;

/// The base of normal laws u = V(t, x, N)·N: velocities() evaluates V at the vertices with the
/// normals of the geometry module (the intrinsic one for curves unless told otherwise), and the
/// step may evaluate it anywhere else with other normals. A law implements normal_speeds().
template <int dim>
class BasicNormalLaw : public BasicVelocityLaw<dim> {
public:
    /// module: where the vertex normals of curves come from; unset:
    /// GeometryNeeds::resolved_module(). Surfaces have one module: leave it unset.
    explicit BasicNormalLaw(std::optional<GeometryModule> module = std::nullopt)
        : module_(module) {}
    /// The vertex normals.
    GeometryNeeds needs() const override { return {.normals = true, .module = module_}; }
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& geometry) const override;
    /// True: a normal law.
    bool is_normal_law() const override { return true; }

private:
    std::optional<GeometryModule> module_;
};
/// A normal law moving curves.
using NormalLaw = BasicNormalLaw<2>;
/// A normal law moving surfaces.
using SurfaceNormalLaw = BasicNormalLaw<3>;

extern template class BasicNormalLaw<2>;
extern template class BasicNormalLaw<3>;

/// Where the geometry modules get what they need.
struct GeometryContext {
    /// A distance tree of the same curves: required when a law asks for the embedded module.
    const DistanceTree* tree = nullptr;
    /// M, E and S of the embedded module.
    EmbeddedOptions embedded = {};
    /// σ ≥ 0 of the arclength module: the width, in arc length, over which it averages the
    /// curvature (0: none). advance() sets √k unless StepOptions::arc_width says otherwise.
    double arc_width = 0.0;
    /// k, the step the velocities are for (VertexGeometry::step): advance() sets it.
    double step = 0.0;
};

/// The vertex geometry a law asks for: no normals or curvature when it needs none, else those of
/// its module; its step is context.step. Throws InvalidInput when the embedded module is asked for
/// without a tree, or with a tree of other curves.
VertexGeometry vertex_geometry(const GeometryNeeds& needs, const Interface& curves,
                               const GeometryContext& context);

/// Velocity(t, Γ): computes the geometry the law needs, calls it, and checks the answer.
/// Throws InvalidInput if the law returns the wrong number of vectors, NumericalFailure naming
/// the law, the time and the vertex if a velocity is not finite.
std::vector<Vec2> vertex_velocities(const VelocityLaw& law, double t, const Interface& curves,
                                    const GeometryContext& context = {});

/// The vertex geometry a law on surfaces asks for: empty when it needs none, else normals and
/// (when asked) mean curvature by surface_geometry() with options (its `curvature` set from
/// needs).
SurfaceGeometry vertex_geometry(const GeometryNeeds& needs, const Surface& surface,
                                SurfaceGeometryOptions options);

/// Velocity(t, S) of a surface: as vertex_velocities for curves.
std::vector<Vec3> vertex_velocities(const SurfaceVelocityLaw& law, double t, const Surface& surface,
                                    const SurfaceGeometryOptions& options = {});
/// The same with the geometry already computed (vertex_geometry of the law's needs).
std::vector<Vec3> vertex_velocities(const SurfaceVelocityLaw& law, double t, const Surface& surface,
                                    const SurfaceGeometry& geometry);

/// A flow field sampled at points, checked like vertex_velocities (the message names the point).
std::vector<Vec2> field_velocities(const VelocityLaw& law, double t, std::span<const Vec2> points);
/// @copydoc field_velocities
std::vector<Vec3> field_velocities(const SurfaceVelocityLaw& law, double t,
                                   std::span<const Vec3> points);
/// The same into `out`, one slot a point, without allocating.
void field_velocities(const VelocityLaw& law, double t, std::span<const Vec2> points,
                      std::span<Vec2> out);
/// @copydoc field_velocities(const VelocityLaw&, double, std::span<const Vec2>, std::span<Vec2>)
void field_velocities(const SurfaceVelocityLaw& law, double t, std::span<const Vec3> points,
                      std::span<Vec3> out);

// ---- adapters: a user's law from a small callable ----------------------------------------------

/// What a local law sees at one vertex. normal and curvature are set when the law asked for them.
template <int dim>
struct BasicVertexState {
    std::size_t index = 0;  ///< vertex number
    PointOf<dim> point;     ///< its position
    PointOf<dim> normal;    ///< outward unit normal N, or 0 when not asked for
    /// C = −∇·N (−1/R on a circle, −2/R on a sphere), or 0 when not asked for
    double curvature = 0.0;
};
/// What a local law on curves sees at a vertex.
using VertexState = BasicVertexState<2>;
/// What a local law on surfaces sees at a vertex.
using SurfaceVertexState = BasicVertexState<3>;

/// The dimension of a field callable f(double, Point) -> Point: 2 when it takes a Vec2 (also a
/// generic callable), 3 when it takes only a Vec3.
template <class F>
inline constexpr int field_dimension = std::regular_invocable<const F&, double, Vec2> ? 2 : 3;
/// The dimension of a normal-speed callable f(double, Point, Point) -> double.
template <class F>
inline constexpr int normal_speed_dimension =
    std::regular_invocable<const F&, double, Vec2, Vec2> ? 2 : 3;
/// The dimension of a local callable f(double, const BasicVertexState<dim>&) -> Point.
template <class F>
inline constexpr int local_dimension =
    std::regular_invocable<const F&, double, const VertexState&> ? 2 : 3;
/// The dimension of a nonlocal callable f(double, const Shape&, const Geometry&).
template <class F>
inline constexpr int curve_dimension =
    std::regular_invocable<const F&, double, const Interface&, const VertexGeometry&> ? 2 : 3;

/// A law u = f(t, x) defined everywhere: f(double t, Point x) -> Point, called concurrently.
template <class F, int dim = field_dimension<F>>
requires std::regular_invocable<const F&, double, PointOf<dim>> &&
    std::convertible_to<std::invoke_result_t<const F&, double, PointOf<dim>>, PointOf<dim>>
class FieldLaw final : public BasicFlowFieldLaw<dim> {
public:
    /// name: the law's name in messages; f: the velocity field.
    FieldLaw(std::string name, F f) : name_(std::move(name)), f_(std::move(f)) {}
    std::string name() const override { return name_; }
    /// The field at each point, as the base's sample().
    void sample(double t, std::span<const PointOf<dim>> points,
                std::span<PointOf<dim>> out) const override {
        parallel_for(points.size(), [&](std::size_t i) { out[i] = f_(t, points[i]); });
    }

private:
    std::string name_;
    F f_;
};

/// A normal law u = V(t, x, N)·N from a callable f(double t, Point x, Point N) -> double, called
/// concurrently.
template <class F, int dim = normal_speed_dimension<F>>
requires std::regular_invocable<const F&, double, PointOf<dim>, PointOf<dim>> &&
    std::convertible_to < std::invoke_result_t<const F&, double, PointOf<dim>, PointOf<dim>>,
double > class NormalSpeedLaw final : public BasicNormalLaw<dim> {
public:
    /// name: the law's name in messages; f: the normal speed; module: where vertex normals of
    /// curves come from.
    NormalSpeedLaw(std::string name, F f, std::optional<GeometryModule> module = std::nullopt)
        : BasicNormalLaw<dim>(module), name_(std::move(name)), f_(std::move(f)) {}
    std::string name() const override { return name_; }
    /// The normal speed at each point with its normal, as the base's normal_speeds().
    void normal_speeds(double t, std::span<const PointOf<dim>> points,
                       std::span<const PointOf<dim>> normals,
                       std::span<double> out) const override {
        parallel_for(points.size(), [&](std::size_t i) { out[i] = f_(t, points[i], normals[i]); });
    }

private:
    std::string name_;
    F f_;
};

/// The base of LocalLaw and CurveLaw: a law with the name and the vertex geometry it was given.
template <int dim>
class BasicNamedLaw : public BasicVelocityLaw<dim> {
public:
    /// name: the law's name in messages; needs: the vertex geometry the law reads.
    BasicNamedLaw(std::string name, GeometryNeeds needs) : name_(std::move(name)), needs_(needs) {}
    std::string name() const override { return name_; }
    GeometryNeeds needs() const override { return needs_; }

private:
    std::string name_;
    GeometryNeeds needs_;
};

/// A local law u_i = f(t, state_i) at each vertex: f(double t, const BasicVertexState<dim>&) ->
/// Point, called concurrently.
template <class F, int dim = local_dimension<F>>
requires std::regular_invocable < const F&, double, const BasicVertexState<dim>
& > class LocalLaw final : public BasicNamedLaw<dim> {
public:
    /// name: the law's name in messages; needs: the vertex geometry f reads; f: the law.
    LocalLaw(std::string name, GeometryNeeds needs, F f)
        : BasicNamedLaw<dim>(std::move(name), needs), f_(std::move(f)) {}
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& geometry) const override {
        const std::span<const PointOf<dim>> x = vertex_points(interface);
        std::vector<PointOf<dim>> u(x.size());
        parallel_for(u.size(), [&](std::size_t i) {
            BasicVertexState<dim> s{i, x[i], {}, 0.0};
            if (!geometry.normals.empty()) s.normal = geometry.normals[i];
            if (!geometry.curvature.empty()) s.curvature = geometry.curvature[i];
            u[i] = f_(t, s);
        });
        return u;
    }

private:
    F f_;
};

/// A law that sees the whole interface (nonlocal): f(double t, const Shape&, const Geometry&) ->
/// std::vector<Point>.
template <class F, int dim = curve_dimension<F>>
requires std::regular_invocable < const F&, double, const ShapeOf<dim>
&, const GeometryOf<dim>& > class CurveLaw final : public BasicNamedLaw<dim> {
public:
    /// name: the law's name in messages; needs: the vertex geometry f reads; f: the law, which
    /// must return one velocity per vertex.
    CurveLaw(std::string name, GeometryNeeds needs, F f)
        : BasicNamedLaw<dim>(std::move(name), needs), f_(std::move(f)) {}
    /// The vertex velocities, as the base's velocities().
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& geometry) const override {
        return f_(t, interface, geometry);
    }

private:
    F f_;
};

/// A FieldLaw owning f, for instance a rigid rotation, of curves or of surfaces by the type f
/// takes:
/// @code
/// auto law = field_law("swirl", [](double, Vec2 x) { return Vec2{-x.y, x.x}; });
/// auto spin = field_law("spin", [](double, Vec3 x) { return Vec3{-x.y, x.x, 0.0}; });
/// @endcode
template <class F>
std::unique_ptr<BasicVelocityLaw<field_dimension<F>>> field_law(std::string name, F f) {
    return std::make_unique<FieldLaw<F>>(std::move(name), std::move(f));
}
/// A NormalSpeedLaw owning f, for instance a speed that depends on the normal's direction:
/// @code
/// auto law = normal_law("faceted", [](double, Vec2, Vec2 n) { return 1.0 + 0.2 * n.x * n.x; });
/// @endcode
template <class F>
std::unique_ptr<BasicVelocityLaw<normal_speed_dimension<F>>> normal_law(
    std::string name, F f, std::optional<GeometryModule> module = std::nullopt) {
    return std::make_unique<NormalSpeedLaw<F>>(std::move(name), std::move(f), module);
}
/// A LocalLaw owning f, for instance the normal speed 2 at the vertices (normal_law() is the
/// form the step can also evaluate off the curve):
/// @code
/// auto law = local_law("speed-2", {.normals = true},
///                      [](double, const VertexState& s) { return 2.0 * s.normal; });
/// @endcode
template <class F>
std::unique_ptr<BasicVelocityLaw<local_dimension<F>>> local_law(std::string name,
                                                                GeometryNeeds needs, F f) {
    return std::make_unique<LocalLaw<F>>(std::move(name), needs, std::move(f));
}
/// A CurveLaw owning f, for laws that see the whole interface (an integral over Γ, say):
/// @code
/// auto law = curve_law("mine", {.normals = true},
///                      [](double t, const Interface& c, const VertexGeometry& g) { ... });
/// @endcode
template <class F>
std::unique_ptr<BasicVelocityLaw<curve_dimension<F>>> curve_law(std::string name,
                                                                GeometryNeeds needs, F f) {
    return std::make_unique<CurveLaw<F>>(std::move(name), needs, std::move(f));
}

}  // namespace slc
