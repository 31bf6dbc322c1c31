// Interface files (DESIGN §6): reading and checking {"time": t, "curves": [{"points": [[x, y],
// ...]}, ...]} with nlohmann-json, writing it back with 17 significant digits so that a written
// file reads back bit for bit, and the atomic file write that every output of the tool uses.
#include "slc/io/interface_json.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <system_error>
#include <variant>

#include "slc/core/error.hpp"
#include "slc/core/input_text.hpp"

namespace slc {
namespace {

using Json = nlohmann::json;

/// One step of the path from the root of a JSON document to a value: a key or an array index.
using PathStep = std::variant<std::string, std::size_t>;

/// The base of SAX handlers that follow only the nesting of a document: every scalar is one
/// value, every object or array opens a level and closes it. Handler supplies value(),
/// open(is_array), close(), key() and parse_error().
template <class Handler>
class NestingSax : public nlohmann::json_sax<Json> {
public:
    bool null() override { return self().value(); }
    bool boolean(bool) override { return self().value(); }
    bool number_integer(number_integer_t) override { return self().value(); }
    bool number_unsigned(number_unsigned_t) override { return self().value(); }
    bool number_float(number_float_t, const string_t&) override { return self().value(); }
    bool string(string_t&) override { return self().value(); }
    bool binary(binary_t&) override { return self().value(); }
    bool start_object(std::size_t) override { return self().open(false); }
    bool end_object() override { return self().close(); }
    bool start_array(std::size_t) override { return self().open(true); }
    bool end_array() override { return self().close(); }

private:
    Handler& self() { return static_cast<Handler&>(*this); }
};

/// A SAX handler that only tracks where the parser is, so that when nlohmann-json stops at a number
/// too large for a double (error 406) the message can name the curve and point that hold it.
class PathTracker final : public NestingSax<PathTracker> {
public:
    bool key(string_t& k) override {
        frames_.back().key = k;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        failed_ = true;
        return false;
    }

    /// The path to the value the parser failed on (valid after a failed parse).
    std::vector<PathStep> failed_path() const {
        std::vector<PathStep> path;
        for (std::size_t f = 0; f < frames_.size(); ++f) {
            const Frame& frame = frames_[f];
            // An open element of a lower frame was counted when it started; the failed value
            // on top was never counted.
            const bool top = f + 1 == frames_.size();
            if (frame.is_array) {
                path.emplace_back(top ? frame.count : frame.count - 1);
            } else {
                path.emplace_back(frame.key);
            }
        }
        return path;
    }
    bool failed() const { return failed_; }

private:
    friend NestingSax<PathTracker>;
    struct Frame {
        bool is_array = false;
        std::size_t count = 0;  ///< elements started so far (arrays)
        std::string key;        ///< the latest key (objects)
    };
    bool value() {
        if (!frames_.empty() && frames_.back().is_array) ++frames_.back().count;
        return true;
    }
    bool open(bool is_array) {
        value();
        frames_.push_back({is_array, 0, {}});
        return true;
    }
    bool close() {
        frames_.pop_back();
        return true;
    }
    std::vector<Frame> frames_;
    bool failed_ = false;
};

/// The message for a number that overflows a double: where it is, in the words of the format.
std::string overflow_message(const std::string& text, const std::string& source) {
    PathTracker tracker;
    Json::sax_parse(text, &tracker);
    const std::vector<PathStep> path = tracker.failed_path();
    auto key_is = [&](std::size_t i, const char* k) {
        return i < path.size() && std::holds_alternative<std::string>(path[i]) &&
               std::get<std::string>(path[i]) == k;
    };
    auto index_at = [&](std::size_t i) {
        return i < path.size() && std::holds_alternative<std::size_t>(path[i]);
    };
    if (tracker.failed() && path.size() == 1 && key_is(0, "time")) {
        return fmt::format("{}: \"time\" is not finite", source);
    }
    if (tracker.failed() && path.size() == 5 && key_is(0, "curves") && index_at(1) &&
        key_is(2, "points") && index_at(3) && index_at(4)) {
        return fmt::format("{}: curve {}, point {} has a non-finite coordinate", source,
                           std::get<std::size_t>(path[1]), std::get<std::size_t>(path[3]));
    }
    return fmt::format("{}: a number is too large to be finite", source);
}

/// A SAX handler that counts the points of an interface file (arrays four levels below the root,
/// as in {"curves": [{"points": [[x, y]]}]}) and all its values, and stops the parse beyond
/// max_interface_points or max_interface_values, so that an enormous file is refused before its
/// document is built.
class PointCounter final : public NestingSax<PointCounter> {
public:
    bool key(string_t&) override { return true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }
    std::size_t points() const { return points_; }
    std::size_t values() const { return values_; }

private:
    friend NestingSax<PointCounter>;
    bool value() { return ++values_ <= max_interface_values; }
    bool open(bool is_array) {
        if (is_array && depth_ == 4) ++points_;
        ++depth_;
        return value() && points_ <= max_interface_points;
    }
    bool close() {
        --depth_;
        return true;
    }
    int depth_ = 0;
    std::size_t points_ = 0;
    std::size_t values_ = 0;
};

/// The document as JSON, or InvalidInput naming the source and the byte where parsing failed.
Json parse_document(const std::string& text, const std::string& source) {
    PointCounter counter;
    Json::sax_parse(text, &counter);
    if (counter.points() > max_interface_points) {
        throw InvalidInput(
            fmt::format("{}: more than {} points; split the interface or thin it out", source,
                        max_interface_points));
    }
    if (counter.values() > max_interface_values) {
        throw InvalidInput(
            fmt::format("{}: more than {} JSON values, beyond what {} points need; an interface "
                        "file holds its curves' points and little else",
                        source, max_interface_values, max_interface_points));
    }
    try {
        return Json::parse(text);
    } catch (const Json::parse_error& e) {
        throw InvalidInput(
            fmt::format("{}: not valid JSON (parse error at byte {})", source, e.byte));
    } catch (const Json::out_of_range&) {
        // nlohmann-json refuses numbers beyond the double range (error 406): they would be inf.
        throw InvalidInput(overflow_message(text, source));
    }
}

/// The points of curve c, checked to be pairs of finite numbers.
std::vector<Vec2> parse_curve(const Json& curve, std::size_t c, const std::string& source) {
    if (!curve.is_object() || !curve.contains("points") || !curve["points"].is_array()) {
        throw InvalidInput(fmt::format("{}: curve {} has no \"points\" array", source, c));
    }
    const Json& points = curve["points"];
    std::vector<Vec2> out;
    out.reserve(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) {
        const Json& point = points[p];
        if (!point.is_array() || point.size() != 2 || !point[0].is_number() ||
            !point[1].is_number()) {
            throw InvalidInput(
                fmt::format("{}: curve {}, point {} is not a pair of numbers", source, c, p));
        }
        const Vec2 v{point[0].get<double>(), point[1].get<double>()};
        if (!is_finite(v)) {
            throw InvalidInput(
                fmt::format("{}: curve {}, point {} has a non-finite coordinate", source, c, p));
        }
        out.push_back(v);
    }
    return out;
}

/// A double with 17 significant digits: enough for strtod to give back the same bits. −0 keeps a
/// decimal point, since the parser would read "-0" as the integer 0 and lose the sign.
std::string exact_number(double v) {
    if (v == 0.0 && std::signbit(v)) return "-0.0";
    return fmt::format("{:.17g}", v);
}

}  // namespace

InterfaceFile parse_interface_json(const std::string& text, const std::string& source) {
    const Json doc = parse_document(text, source);
    if (!doc.is_object() || !doc.contains("curves") || !doc["curves"].is_array()) {
        throw InvalidInput(fmt::format("{}: no \"curves\" array", source));
    }
    InterfaceFile out;
    if (doc.contains("time")) {
        const Json& time = doc["time"];
        if (!time.is_number()) {
            throw InvalidInput(fmt::format("{}: \"time\" is not a number", source));
        }
        out.time = time.get<double>();
        if (!std::isfinite(out.time)) {
            throw InvalidInput(fmt::format("{}: \"time\" is not finite", source));
        }
    }
    const Json& curves = doc["curves"];
    out.curves.reserve(curves.size());
    for (std::size_t c = 0; c < curves.size(); ++c) {
        out.curves.push_back(parse_curve(curves[c], c, source));
    }
    return out;
}

InterfaceFile read_interface_json(const std::filesystem::path& path) {
    return parse_interface_json(read_text_file(path), path.string());
}

std::string interface_json(const Interface& curves, double time) {
    // One point per line: readable, and a diff between two files shows the points that moved.
    std::string out = fmt::format("{{\n  \"time\": {},\n  \"curves\": [", exact_number(time));
    for (std::size_t c = 0; c < curves.curve_count(); ++c) {
        out += c == 0 ? "\n    {\"points\": [" : ",\n    {\"points\": [";
        const std::span<const Vec2> points = curves.curve(c);
        for (std::size_t p = 0; p < points.size(); ++p) {
            if (!is_finite(points[p])) {
                throw InvalidInput(fmt::format(
                    "cannot write curve {}, point {} as JSON: non-finite coordinate", c, p));
            }
            out += fmt::format("{}\n      [{}, {}]", p == 0 ? "" : ",", exact_number(points[p].x),
                               exact_number(points[p].y));
        }
        out += "\n    ]}";
    }
    out += curves.curve_count() == 0 ? "]\n}\n" : "\n  ]\n}\n";
    return out;
}

void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path&)>& write) {
    auto fail = [&](const std::string& reason) {
        return InvalidInput(fmt::format("cannot write {}: {}", path.string(), reason));
    };
    std::error_code ec;
    const std::filesystem::path parent = path.parent_path();
    if (!parent.empty()) {
        std::filesystem::create_directories(parent, ec);
        if (ec) throw fail(ec.message());
    }
    // Unique per process and per call, in the same folder so that the rename cannot cross devices.
    static std::atomic<unsigned long> counter{0};
    std::filesystem::path temp = path;
    temp += fmt::format(".tmp{}.{}", static_cast<long>(::getpid()), counter++);
    try {
        write(temp);
    } catch (const std::exception& e) {
        std::filesystem::remove(temp, ec);
        throw fail(e.what());
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        const std::string reason = ec.message();
        std::filesystem::remove(temp, ec);
        throw fail(reason);
    }
}

void write_file_atomic(const std::filesystem::path& path, const std::string& text) {
    write_file_atomic(path, [&text](const std::filesystem::path& temp) {
        std::FILE* file = std::fopen(temp.c_str(), "wb");
        if (file == nullptr) throw std::runtime_error(std::generic_category().message(errno));
        const bool written =
            std::fwrite(text.data(), 1, text.size(), file) == text.size() && std::fflush(file) == 0;
        const int write_error = errno;
        const bool closed = std::fclose(file) == 0;
        if (!written || !closed)
            throw std::runtime_error(
                std::generic_category().message(written ? errno : write_error));
    });
}

std::string read_text_file(const std::filesystem::path& path) {
    auto too_large = [&](std::uintmax_t bytes, const char* more) {
        return InvalidInput(
            fmt::format("{}: {}{} bytes, above the limit of {} bytes ({} MiB) "
                        "for an input file",
                        path.string(), more, bytes, max_input_bytes, max_input_bytes >> 20));
    };
    const std::uintmax_t size = regular_file_size(path);
    if (size > max_input_bytes) throw too_large(size, "");
    std::string text = file_bytes(path, max_input_bytes);
    if (text.size() > max_input_bytes)
        throw too_large(text.size(), "more than ");  // it grew meanwhile
    return text;
}

}  // namespace slc
