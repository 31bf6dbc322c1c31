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
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/parallel.hpp"
#include "slc/velocity/laws.hpp"

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
    /// True when the expression reads the variable `name`.
    bool uses(std::string_view name) const {
        return std::find(used_.begin(), used_.end(), name) != used_.end();
    }
    /// Its value when it reads no variable (muparser's functions are pure, so it is one number
    /// then), else nothing.
    std::optional<double> constant() const {
        if (!used_.empty() || spec_.values != 1) return std::nullopt;
        double value = 0.0;
        for_each(1, [&](Evaluator& e, std::size_t) { value = e.value(); });
        return value;
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

/// Where an expression's variables stand in dimension dim (speed_variables,
/// surface_speed_variables; the field variables are their first dim + 1): the point's
/// coordinates, then t, C and the normal's coordinates.
template <int dim>
struct VariableIndex {
    static constexpr std::size_t t = dim;
    static constexpr std::size_t c = dim + 1;
    static constexpr std::size_t normal = dim + 2;
};

/// Sets the point and the time of an expression's variables.
template <int dim>
void set_point(Evaluator& e, PointOf<dim> p, double t) {
    auto& v = e.variables();
    for (int k = 0; k < dim; ++k) v[k] = p[k];
    v[VariableIndex<dim>::t] = t;
}

/// Sets the normal of a speed expression's variables.
template <int dim>
void set_normal(Evaluator& e, PointOf<dim> n) {
    auto& v = e.variables();
    for (int k = 0; k < dim; ++k) v[VariableIndex<dim>::normal + k] = n[k];
}

/// v(x, t, N): a normal law, evaluated at any point with any normal.
template <int dim>
class SpeedExpression final : public BasicNormalLaw<dim> {
public:
    using Point = PointOf<dim>;
    /// module: where the vertex normals of curves come from; unset for surfaces.
    SpeedExpression(std::shared_ptr<const EvaluatorPool> pool, std::optional<GeometryModule> module)
        : BasicNormalLaw<dim>(module), pool_(std::move(pool)), constant_(pool_->constant()) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    /// A number (no variable read) moves as unit-normal at that speed, and keeps what it keeps.
    Invariants invariants() const override {
        return constant_ ? constant_speed_invariants<dim>(*constant_) : Invariants{};
    }
    std::optional<double> speed_bound() const override {
        return constant_ ? std::optional(std::abs(*constant_)) : std::nullopt;
    }
    std::optional<double> constant_speed() const override { return constant_; }
    void normal_speeds(double t, std::span<const Point> points, std::span<const Point> normals,
                       std::span<double> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            set_point<dim>(e, points[i], t);
            set_normal<dim>(e, normals[i]);
            out[i] = e.value();
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
    std::optional<double> constant_;  ///< the speed when the expression reads no variable
};

/// v(x, t, C, N) with the curvature (the mean curvature of surfaces): known at the vertices only.
template <int dim>
class CurvatureSpeedExpression final : public BasicCurvatureLaw<dim> {
public:
    /// module: where the vertex normals and curvature of curves come from; unset for surfaces.
    CurvatureSpeedExpression(std::shared_ptr<const EvaluatorPool> pool,
                             std::optional<GeometryModule> module)
        : BasicCurvatureLaw<dim>(module), pool_(std::move(pool)) {}
    std::string name() const override { return "speed = " + shown(pool_->spec().text); }
    std::vector<PointOf<dim>> velocities(double t, const ShapeOf<dim>& interface,
                                         const GeometryOf<dim>& g) const override {
        this->require_geometry(interface, g);
        const std::span<const PointOf<dim>> x = vertex_points(interface);
        std::vector<PointOf<dim>> u(x.size());
        std::vector<double> slope(x.size());
        pool_->for_each(u.size(), [&](Evaluator& e, std::size_t i) {
            set_point<dim>(e, x[i], t);
            set_normal<dim>(e, g.normals[i]);
            double& c = e.variables()[VariableIndex<dim>::c];
            // dv/dC by a central difference, for the check below.
            const double h = 0x1p-20 * std::max(1.0, std::abs(g.curvature[i]));
            c = g.curvature[i] + h;
            const double above = e.value();
            c = g.curvature[i] - h;
            const double below = e.value();
            slope[i] = (above - below) / (2.0 * h);
            c = g.curvature[i];
            u[i] = e.value() * g.normals[i];
        });
        require_forward_in_curvature("speed '" + shown(pool_->spec().text) + "'", x, slope);
        return u;
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// u(x, t): a flow field, the expression giving dim values.
template <int dim>
class FieldExpression final : public BasicFlowFieldLaw<dim> {
public:
    using Point = PointOf<dim>;
    explicit FieldExpression(std::shared_ptr<const EvaluatorPool> pool) : pool_(std::move(pool)) {}
    std::string name() const override { return "field = (" + shown(pool_->spec().text) + ")"; }
    void sample(double t, std::span<const Point> points, std::span<Point> out) const override {
        pool_->for_each(points.size(), [&](Evaluator& e, std::size_t i) {
            set_point<dim>(e, points[i], t);
            int count = 0;
            const double* u = e.values(count);
            for (int k = 0; k < dim; ++k) out[i][k] = u[k];
        });
    }

private:
    std::shared_ptr<const EvaluatorPool> pool_;
};

/// The speed law of an expression: a normal law, or a law at the vertices when it reads C.
template <int dim>
std::unique_ptr<BasicVelocityLaw<dim>> speed_law(std::shared_ptr<const EvaluatorPool> pool,
                                                 std::optional<GeometryModule> module) {
    if (pool->uses("C"))
        return std::make_unique<CurvatureSpeedExpression<dim>>(std::move(pool), module);
    return std::make_unique<SpeedExpression<dim>>(std::move(pool), module);
}

}  // namespace

std::unique_ptr<VelocityLaw> speed_expression_law(const std::string& expression,
                                                  const VelocityParams& constants,
                                                  std::optional<GeometryModule> module) {
    return speed_law<2>(std::make_shared<const EvaluatorPool>(ExpressionSpec{
                            expression, "speed expression", speed_variables, constants, 1}),
                        module);
}

std::unique_ptr<VelocityLaw> field_expression_law(const std::string& expression,
                                                  const VelocityParams& constants) {
    return std::make_unique<FieldExpression<2>>(std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "field expression", field_variables, constants, 2}));
}

std::unique_ptr<SurfaceVelocityLaw> surface_speed_expression_law(const std::string& expression,
                                                                 const VelocityParams& constants) {
    return speed_law<3>(std::make_shared<const EvaluatorPool>(ExpressionSpec{
                            expression, "speed expression", surface_speed_variables, constants, 1}),
                        std::nullopt);
}

std::unique_ptr<SurfaceVelocityLaw> surface_field_expression_law(const std::string& expression,
                                                                 const VelocityParams& constants) {
    return std::make_unique<FieldExpression<3>>(std::make_shared<const EvaluatorPool>(
        ExpressionSpec{expression, "field expression", surface_field_variables, constants, 3}));
}

}  // namespace slc
