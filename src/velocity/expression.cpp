// Velocity laws typed as text: a normal speed v(x, y, t, C, nx, ny) and a flow field
// (u, v)(x, y, t) for curves, v(x, y, z, t, C, nx, ny, nz) and (u, v, w)(x, y, z, t) for
// surfaces, parsed and evaluated by muparser, one parser per worker thread.
#include "slc/velocity/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"

namespace slc {
namespace {

/// An expression, what it is for messages ("speed expression"), its variables, the caller's
/// named constants, and how many values it must give (1: a speed, 2 or 3: a field).
struct ExpressionSpec {
    std::string text;
    std::string what;
    std::span<const std::string_view> variables;
    VelocityParams constants;
    int values = 1;
};

/// The most variables of any expression: a speed on surfaces.
constexpr std::size_t max_variables = surface_speed_variables.size();
static_assert(max_variables >= speed_variables.size());

/// Why a field gives the wrong number of values: "a flow field needs two, u and v, ...".
std::string field_count_message(int wanted, int count) {
    return fmt::format("gives {} value{}; a flow field needs {} separated by commas ({})", count,
                       count == 1 ? "" : "s", wanted == 2 ? "two, u and v," : "three, u, v and w,",
                       wanted == 2 ? "\"-y, x\"" : "\"-y, x, 0\"");
}

/// The expression as shown in a message: on one line.
std::string shown(const std::string& text) {
    std::string s = text;
    std::replace_if(
        s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    return s;
}

/// "x, y, t" and the constants' names.
std::string names_known(const ExpressionSpec& spec) {
    std::string s;
    for (std::string_view v : spec.variables) s += (s.empty() ? "" : ", ") + std::string(v);
    s = "the variables are " + s;
    if (!spec.constants.empty()) {
        std::string c;
        for (const auto& [name, value] : spec.constants) c += (c.empty() ? "" : ", ") + name;
        s += "; the constants " + c;
    }
    return s;
}

InvalidInput bad_expression(const ExpressionSpec& spec, const std::string& why) {
    return InvalidInput(fmt::format("{} '{}': {}", spec.what, shown(spec.text), why));
}

/// muparser's message as part of ours: "unknown name 'z' at position 0 (the variables are ...)"
/// for the commonest mistake, else its own text without the capital and the full stop.
std::string parser_message(const ExpressionSpec& spec, const mu::Parser::exception_type& e) {
    if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN) {
        return fmt::format("unknown name '{}' at position {} ({})", e.GetToken(), e.GetPos(),
                           names_known(spec));
    }
    std::string m = e.GetMsg();
    if (!m.empty()) m[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(m[0])));
    while (!m.empty() && (m.back() == '.' || m.back() == ' ')) m.pop_back();
    return m;
}

bool is_identifier(const std::string& name) {
    if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
}

/// One muparser parser with its own variables, for one thread at a time. Not movable: the parser
/// holds pointers to the variables.
class Evaluator {
public:
    explicit Evaluator(const ExpressionSpec& spec) {
        for (std::size_t i = 0; i < spec.variables.size(); ++i)
            parser_.DefineVar(std::string(spec.variables[i]), &variables_[i]);
        for (const auto& [name, value] : spec.constants) parser_.DefineConst(name, value);
        parser_.SetExpr(spec.text);
    }
    Evaluator(const Evaluator&) = delete;
    Evaluator& operator=(const Evaluator&) = delete;

    /// The variables, in the order of ExpressionSpec::variables.
    std::array<double, max_variables>& variables() { return variables_; }
    /// The expression's values at the current variables; count: how many.
    const double* values(int& count) { return parser_.Eval(count); }
    /// The value of a one-valued expression at the current variables.
    double value() { return parser_.Eval(); }
    /// The names the expression reads.
    mu::varmap_type used() { return parser_.GetUsedVar(); }
    /// muparser's functions, which a constant must not shadow.
    bool is_function(const std::string& name) const { return parser_.GetFunDef().count(name) != 0; }

private:
    std::array<double, max_variables> variables_{};
    mu::Parser parser_;
};

/// The parsers of one law: a batch is split into contiguous chunks, one per worker thread, each
/// evaluated by a parser taken from the pool and given back, so that concurrent calls never share
/// one. Every point is evaluated alone by the same byte code, so the values do not depend on how
/// the batch was split.
class EvaluatorPool {
public:
    /// Checks the expression (InvalidInput naming what is wrong) and keeps its first parser.
    explicit EvaluatorPool(ExpressionSpec spec) : spec_(std::move(spec)) {
        if (spec_.text.find_first_not_of(" \t\r\n") == std::string::npos)
            throw InvalidInput(fmt::format("{} is empty", spec_.what));
        check_constants();
        std::unique_ptr<Evaluator> e;
        try {
            e = std::make_unique<Evaluator>(spec_);
            int count = 0;
            e->values(count);  // parses
            if (count != spec_.values) {
                throw bad_expression(
                    spec_, spec_.values == 1
                               ? fmt::format("gives {} values separated by commas; a normal "
                                             "speed is one",
                                             count)
                               : field_count_message(spec_.values, count));
            }
            for (const auto& [name, address] : e->used()) used_.push_back(name);
        } catch (const mu::Parser::exception_type& error) {
            throw bad_expression(spec_, parser_message(spec_, error));
        }
        free_.push_back(std::move(e));
    }

    const ExpressionSpec& spec() const { return spec_; }
    /// True when the expression reads the variable or constant `name`.
    bool uses(std::string_view name) const {
        return std::find(used_.begin(), used_.end(), name) != used_.end();
    }

    /// Calls body(evaluator, i) for every i in [0, n), on all worker threads for large n; body
    /// sets the evaluator's variables for point i and reads its value. A muparser error while
    /// evaluating (none is expected once parsed) becomes a NumericalFailure.
    template <class Body>
    void for_each(std::size_t n, Body&& body) const {
        // A chunk per thread, of parallel_grain points at least: starting threads costs more
        // than evaluating fewer.
        const std::size_t threads = static_cast<std::size_t>(std::max(thread_count(), 1));
        const std::size_t chunks = std::clamp<std::size_t>(n / parallel_grain, 1, threads);
        parallel_for(
            chunks,
            [&](std::size_t c) {
                Lease lease(*this);
                const std::size_t begin = n * c / chunks, end = n * (c + 1) / chunks;
                try {
                    for (std::size_t i = begin; i < end; ++i) body(*lease.evaluator, i);
                } catch (const mu::Parser::exception_type& error) {
                    throw NumericalFailure(fmt::format("{} '{}' failed: {}", spec_.what,
                                                       shown(spec_.text),
                                                       parser_message(spec_, error)));
                }
            },
            2);
    }

private:
    /// A parser taken from the pool (a new one when none is free) and given back when done.
    struct Lease {
        explicit Lease(const EvaluatorPool& p) : pool(p) {
            std::lock_guard lock(pool.mutex_);
            if (pool.free_.empty()) {
                evaluator = std::make_unique<Evaluator>(pool.spec_);
            } else {
                evaluator = std::move(pool.free_.back());
                pool.free_.pop_back();
            }
        }
        ~Lease() {
            std::lock_guard lock(pool.mutex_);
            pool.free_.push_back(std::move(evaluator));
        }
        Lease(const Lease&) = delete;
        Lease& operator=(const Lease&) = delete;

        const EvaluatorPool& pool;
        std::unique_ptr<Evaluator> evaluator;
    };

    void check_constants() const {
        const Evaluator probe(ExpressionSpec{"0", spec_.what, spec_.variables, {}, 1});
        for (const auto& [name, value] : spec_.constants) {
            const bool variable = std::find(spec_.variables.begin(), spec_.variables.end(), name) !=
                                  spec_.variables.end();
            std::string why;
            if (!is_identifier(name))
                why = "is not a name (letters, digits and _, not starting with a digit)";
            else if (variable)
                why = "is a variable of the expression";
            else if (probe.is_function(name))
                why = "is a function of the expressions";
            else if (!std::isfinite(value))
                why = fmt::format("must be finite, got {}", value);
            if (!why.empty())
                throw bad_expression(spec_, fmt::format("the constant '{}' {}", name, why));
        }
    }

    ExpressionSpec spec_;
    std::vector<std::string> used_;
    mutable std::mutex mutex_;
    mutable std::vector<std::unique_ptr<Evaluator>> free_;
};

/// Variable indices in speed_variables (field_variables are its first three).
enum Variable : std::size_t { var_x, var_y, var_t, var_c, var_nx, var_ny };

/// v(x, y, t, nx, ny): a normal law, evaluated at any point with any normal.
class SpeedExpression final : public NormalLaw {
public:
    SpeedExpression(std::shared_ptr<const EvaluatorPool> pool, std::optional<GeometryModule> module)
        : NormalLaw(module), pool_(std::move(pool)) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    void normal_speeds(double t, std::span<const Vec2> points, std::span<const Vec2> normals,
                       std::span<double> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            auto& v = e.variables();
            v[var_x] = points[i].x;
            v[var_y] = points[i].y;
            v[var_t] = t;
            v[var_nx] = normals[i].x;
            v[var_ny] = normals[i].y;
            out[i] = e.value();
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// v(x, y, t, C, nx, ny) with the curvature: known at the vertices only.
class CurvatureSpeedExpression final : public VelocityLaw {
public:
    CurvatureSpeedExpression(std::shared_ptr<const EvaluatorPool> pool,
                             std::optional<GeometryModule> module)
        : pool_(std::move(pool)), module_(module) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    GeometryNeeds needs() const override {
        return {.normals = true, .curvature = true, .module = module_};
    }
    std::vector<Vec2> velocities(double t, const Interface& curves,
                                 const VertexGeometry& g) const override {
        if (g.normals.size() != curves.size() || g.curvature.size() != curves.size()) {
            throw InvalidInput(
                fmt::format("velocity '{}' needs the normals and curvature at the vertices "
                            "(vertex_velocities computes them)",
                            name()));
        }
        std::vector<Vec2> u(curves.size());
        pool_->for_each(u.size(), [&](Evaluator& e, std::size_t i) {
            auto& v = e.variables();
            v[var_x] = curves.point(i).x;
            v[var_y] = curves.point(i).y;
            v[var_t] = t;
            v[var_c] = g.curvature[i];
            v[var_nx] = g.normals[i].x;
            v[var_ny] = g.normals[i].y;
            u[i] = e.value() * g.normals[i];
        });
        return u;
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
    std::optional<GeometryModule> module_;
};

/// (u, v)(x, y, t): a flow field.
class FieldExpression final : public FlowFieldLaw {
public:
    explicit FieldExpression(std::shared_ptr<const EvaluatorPool> pool) : pool_(std::move(pool)) {}
    std::string name() const override { return "field = (" + shown(pool_->spec().text) + ")"; }
    void sample(double t, std::span<const Vec2> points, std::span<Vec2> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            auto& v = e.variables();
            v[var_x] = points[i].x;
            v[var_y] = points[i].y;
            v[var_t] = t;
            int count = 0;
            const double* uv = e.values(count);
            out[i] = {uv[0], uv[1]};
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// Variable indices in surface_speed_variables (surface_field_variables are its first four).
enum SurfaceVariable : std::size_t { sv_x, sv_y, sv_z, sv_t, sv_c, sv_nx, sv_ny, sv_nz };

/// Sets the point and time of a surface expression's variables.
void set_point(Evaluator& e, Vec3 p, double t) {
    auto& v = e.variables();
    v[sv_x] = p.x;
    v[sv_y] = p.y;
    v[sv_z] = p.z;
    v[sv_t] = t;
}

/// v(x, y, z, t, nx, ny, nz): a normal law of surfaces, evaluated at any point with any normal.
class SurfaceSpeedExpression final : public SurfaceNormalLaw {
public:
    explicit SurfaceSpeedExpression(std::shared_ptr<const EvaluatorPool> pool)
        : pool_(std::move(pool)) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    void normal_speeds(double t, std::span<const Vec3> points, std::span<const Vec3> normals,
                       std::span<double> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            set_point(e, points[i], t);
            auto& v = e.variables();
            v[sv_nx] = normals[i].x;
            v[sv_ny] = normals[i].y;
            v[sv_nz] = normals[i].z;
            out[i] = e.value();
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// v(x, y, z, t, C, nx, ny, nz) with the mean curvature: known at the vertices only.
class SurfaceCurvatureSpeedExpression final : public SurfaceVelocityLaw {
public:
    explicit SurfaceCurvatureSpeedExpression(std::shared_ptr<const EvaluatorPool> pool)
        : pool_(std::move(pool)) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    GeometryNeeds needs() const override { return {.normals = true, .curvature = true}; }
    std::vector<Vec3> velocities(double t, const Surface& surface,
                                 const SurfaceGeometry& g) const override {
        const std::size_t n = surface.vertices.size();
        if (g.normals.size() != n || g.curvature.size() != n) {
            throw InvalidInput(
                fmt::format("velocity '{}' needs the normals and curvature at the vertices "
                            "(vertex_velocities computes them)",
                            name()));
        }
        std::vector<Vec3> u(n);
        pool_->for_each(n, [&](Evaluator& e, std::size_t i) {
            set_point(e, surface.vertices[i], t);
            auto& v = e.variables();
            v[sv_c] = g.curvature[i];
            v[sv_nx] = g.normals[i].x;
            v[sv_ny] = g.normals[i].y;
            v[sv_nz] = g.normals[i].z;
            u[i] = e.value() * g.normals[i];
        });
        return u;
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// (u, v, w)(x, y, z, t): a flow field in space.
class SurfaceFieldExpression final : public SurfaceFlowFieldLaw {
public:
    explicit SurfaceFieldExpression(std::shared_ptr<const EvaluatorPool> pool)
        : pool_(std::move(pool)) {}
    std::string name() const override { return "field = (" + shown(pool_->spec().text) + ")"; }
    void sample(double t, std::span<const Vec3> points, std::span<Vec3> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            set_point(e, points[i], t);
            int count = 0;
            const double* uvw = e.values(count);
            out[i] = {uvw[0], uvw[1], uvw[2]};
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

}  // namespace

std::unique_ptr<VelocityLaw> speed_expression_law(const std::string& expression,
                                                  const VelocityParams& constants,
                                                  std::optional<GeometryModule> module) {
    auto pool = std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "speed expression", speed_variables, constants, 1});
    if (pool->uses("C")) return std::make_unique<CurvatureSpeedExpression>(std::move(pool), module);
    return std::make_unique<SpeedExpression>(std::move(pool), module);
}

std::unique_ptr<VelocityLaw> field_expression_law(const std::string& expression,
                                                  const VelocityParams& constants) {
    return std::make_unique<FieldExpression>(std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "field expression", field_variables, constants, 2}));
}

std::unique_ptr<SurfaceVelocityLaw> surface_speed_expression_law(const std::string& expression,
                                                                 const VelocityParams& constants) {
    auto pool = std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "speed expression", surface_speed_variables, constants, 1});
    if (pool->uses("C")) return std::make_unique<SurfaceCurvatureSpeedExpression>(std::move(pool));
    return std::make_unique<SurfaceSpeedExpression>(std::move(pool));
}

std::unique_ptr<SurfaceVelocityLaw> surface_field_expression_law(const std::string& expression,
                                                                 const VelocityParams& constants) {
    return std::make_unique<SurfaceFieldExpression>(std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "field expression", surface_field_variables, constants, 3}));
}

}  // namespace slc
