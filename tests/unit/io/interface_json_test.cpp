// Tests of interface files: bit-exact round trips, one message per kind of bad input naming the
// file and the place, and the atomic write.
#include "slc/io/interface_json.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>

#include "slc/core/error.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;

/// A fresh folder under the system's temporary folder, removed with everything in it.
using test_support::TempDir;

using test_support::slurp;

/// Runs f, expects InvalidInput, and checks that its message holds every one of parts.
void expect_invalid(const std::function<void()>& f, std::initializer_list<std::string> parts) {
    try {
        f();
        ADD_FAILURE() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        for (const std::string& part : parts) {
            EXPECT_NE(message.find(part), std::string::npos)
                << "message \"" << message << "\" lacks \"" << part << "\"";
        }
    }
}

void expect_parse_error(const std::string& text, std::initializer_list<std::string> parts) {
    SCOPED_TRACE(text);
    expect_invalid([&] { parse_interface_json(text, "shape.json"); }, parts);
}

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

std::vector<Vec2> triangle() { return {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}; }

TEST(InterfaceJson, RoundTripsBitExactly) {
    const unsigned seed = 20240611;
    std::mt19937 rng(seed);
    // Magnitudes from 1e-300 to 1e300, both signs: every digit of the 17 matters somewhere.
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    std::uniform_int_distribution<int> count(3, 40);
    std::vector<std::vector<Vec2>> raw;
    for (int c = 0; c < 20; ++c) {
        std::vector<Vec2>& curve = raw.emplace_back();
        for (int p = count(rng); p > 0; --p) {
            curve.push_back({std::ldexp(mantissa(rng), exponent(rng) / 4),
                             mantissa(rng) * std::pow(10.0, exponent(rng))});
        }
    }
    // Edge cases: signed zero, the smallest subnormal, the largest double, an integer-valued one.
    raw.push_back({{-0.0, 0.0},
                   {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max()},
                   {-std::numeric_limits<double>::max(), 12345678901234567.0}});
    const Interface curves(raw);
    const double time = mantissa(rng);

    const InterfaceFile back = parse_interface_json(interface_json(curves, time), "mem");
    EXPECT_TRUE(same_bits(back.time, time)) << "seed " << seed;
    ASSERT_EQ(back.curves.size(), raw.size()) << "seed " << seed;
    for (std::size_t c = 0; c < raw.size(); ++c) {
        ASSERT_EQ(back.curves[c].size(), raw[c].size()) << "seed " << seed;
        for (std::size_t p = 0; p < raw[c].size(); ++p) {
            EXPECT_TRUE(same_bits(back.curves[c][p].x, raw[c][p].x) &&
                        same_bits(back.curves[c][p].y, raw[c][p].y))
                << "seed " << seed << ", curve " << c << ", point " << p << ": "
                << back.curves[c][p].x << " " << raw[c][p].x;
        }
    }
}

TEST(InterfaceJson, WritesOnePointPerLine) {
    const Interface curves({triangle(), triangle()});
    const std::string text = interface_json(curves, 0.5);
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 15) << text;
    EXPECT_NE(text.find("\"time\": 0.5"), std::string::npos) << text;
    EXPECT_NE(text.find("\n      [1, 0],\n"), std::string::npos) << text;
}

TEST(InterfaceJson, ParsesTimeAndCurvesAndDefaultsTimeToZero) {
    const InterfaceFile a = parse_interface_json(
        R"({"time": 2.5, "curves": [{"points": [[0, 0], [1, 0], [0.5, 1e-3]]}], "note": "x"})",
        "a.json");
    EXPECT_EQ(a.time, 2.5);
    ASSERT_EQ(a.curves.size(), 1u);
    ASSERT_EQ(a.curves[0].size(), 3u);
    EXPECT_EQ(a.curves[0][2], (Vec2{0.5, 1e-3}));

    const InterfaceFile b = parse_interface_json(R"({"curves": []})", "b.json");
    EXPECT_EQ(b.time, 0.0);
    EXPECT_TRUE(b.curves.empty());
}

TEST(InterfaceJson, RejectsInvalidJsonNamingTheByte) {
    expect_parse_error(R"({"curves": [1, 2,, ]})", {"shape.json: not valid JSON", "byte 18"});
    expect_parse_error("", {"shape.json: not valid JSON", "byte"});
    expect_parse_error(R"({"curves": [NaN]})", {"shape.json: not valid JSON"});
}

TEST(InterfaceJson, RejectsMissingCurvesArray) {
    for (const char* text : {R"({"time": 0})", R"({"curves": {}})", "[]", "3"}) {
        expect_parse_error(text, {"shape.json: no \"curves\" array"});
    }
}

TEST(InterfaceJson, RejectsCurveWithoutPoints) {
    expect_parse_error(R"({"curves": [{"points": [[0, 0]]}, {"points": []}, {"pts": []}]})",
                       {"shape.json: curve 2 has no \"points\" array"});
    expect_parse_error(R"({"curves": [[[0, 0]]]})", {"shape.json: curve 0 has no \"points\""});
}

TEST(InterfaceJson, RejectsPointThatIsNotAPairOfNumbers) {
    for (const char* point : {"[1]", "[1, 2, 3]", "[\"1\", 2]", "[true, 1]", "[null, 1]",
                              "{\"x\": 1, \"y\": 2}", "4"}) {
        expect_parse_error(
            fmt::format(R"({{"curves": [{{"points": [[0, 0], [1, 0], [1, 1], {}]}}]}})", point),
            {"shape.json: curve 0, point 3 is not a pair of numbers"});
    }
}

TEST(InterfaceJson, RejectsCoordinatesThatOverflowToInfinity) {
    expect_parse_error(R"({"curves": [{"points": [[0, 0], [1, 0], [1, 1], [1e400, 0]]}]})",
                       {"shape.json: curve 0, point 3 has a non-finite coordinate"});
    expect_parse_error(
        R"({"time": 1, "curves": [{"points": [[0, 0]]}, {"points": [[0, 0], [1, -2e308]]}]})",
        {"shape.json: curve 1, point 1 has a non-finite coordinate"});
}

TEST(InterfaceJson, RejectsTimeThatIsNotAFiniteNumber) {
    expect_parse_error(R"({"time": 1e999, "curves": []})", {"shape.json: \"time\" is not finite"});
    expect_parse_error(R"({"time": "soon", "curves": []})",
                       {"shape.json: \"time\" is not a number"});
    // A huge number anywhere else still names the source.
    expect_parse_error(R"({"other": [1e999], "curves": []})", {"shape.json:", "finite"});
}

TEST(InterfaceJson, ReadNamesTheFileAndRejectsAMissingOne) {
    const TempDir dir;
    const fs::path good = dir.path() / "good.json";
    write_file_atomic(good, interface_json(Interface({triangle()}), 1.0));
    EXPECT_EQ(read_interface_json(good).curves.at(0), triangle());

    const fs::path bad = dir.path() / "bad.json";
    write_file_atomic(bad, R"({"curves": [{}]})");
    expect_invalid([&] { read_interface_json(bad); },
                   {bad.string() + ": curve 0 has no \"points\" array"});
    expect_invalid([&] { read_interface_json(dir.path() / "missing.json"); },
                   {"cannot read", "missing.json", "No such file"});
    expect_invalid([&] { read_interface_json(dir.path()); }, {"cannot read"});
}

TEST(WriteFileAtomic, ReplacesTheOldContentAndLeavesNoTemporaryFile) {
    const TempDir dir;
    const fs::path path = dir.path() / "x.json";
    write_file_atomic(path, "old content, longer than the new one");
    write_file_atomic(path, "new");
    EXPECT_EQ(slurp(path), "new");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir.path())) files.push_back(entry.path());
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0], path);
}

TEST(WriteFileAtomic, CreatesMissingParentFolders) {
    const TempDir dir;
    const fs::path path = dir.path() / "out" / "deeper" / "x.json";
    write_file_atomic(path, "{}");
    EXPECT_EQ(slurp(path), "{}");
}

TEST(WriteFileAtomic, FolderThatIsAFileIsInvalidInput) {
    const TempDir dir;
    // A parent that is a regular file cannot hold anything, even for root.
    const fs::path file = dir.path() / "file";
    write_file_atomic(file, "x");
    expect_invalid([&] { write_file_atomic(file / "x.json", "{}"); },
                   {"cannot write", (file / "x.json").string()});
}

TEST(WriteFileAtomic, ReadOnlyFolderIsInvalidInput) {
    const TempDir dir;
    // Only meaningful where permissions are enforced (not for root).
    const fs::path locked = dir.path() / "locked";
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    if (::access(locked.c_str(), W_OK) == 0) GTEST_SKIP() << "running with write access anywhere";
    expect_invalid([&] { write_file_atomic(locked / "x.json", "{}"); },
                   {"cannot write", "x.json", "Permission denied"});
    EXPECT_TRUE(fs::is_empty(locked));
}

TEST(InterfaceJson, RefusesMoreThanTheLimitOfPointsBeforeBuildingTheDocument) {
    std::string text = R"({"curves": [{"points": [[0, 0])";
    for (std::size_t p = 0; p < max_interface_points; ++p) text += ",[0,0]";
    text += "]}]}";
    expect_invalid([&] { parse_interface_json(text, "big.json"); },
                   {"big.json: more than 2000000 points"});
}

TEST(InterfaceJson, RefusesAFilePaddedWithOtherValuesBeforeBuildingTheDocument) {
    std::string text = R"({"curves": [{"points": [[0, 0], [1, 0], [0, 1]]}], "pad": [0)";
    for (std::size_t v = 0; v < max_interface_values; ++v) text += ",0";
    text += "]}";
    expect_invalid([&] { parse_interface_json(text, "padded.json"); },
                   {"padded.json: more than 8000000 JSON values"});
}

TEST(ReadTextFile, RefusesDevicesAndFoldersBeforeReading) {
    // /dev/zero never ends: it must be refused before a byte is read.
    expect_invalid([] { read_text_file("/dev/zero"); },
                   {"cannot read /dev/zero: not a regular file"});
    const TempDir dir;
    expect_invalid([&] { read_text_file(dir.path()); }, {"not a regular file"});
}

TEST(ReadTextFile, RefusesAFileAboveTheLimitBeforeReadingIt) {
    const TempDir dir;
    const fs::path big = dir.path() / "big.json";
    { std::ofstream out(big); }
    fs::resize_file(big, max_input_bytes + 1);  // sparse: no disk space taken
    expect_invalid([&] { read_text_file(big); },
                   {"big.json: 134217729 bytes, above the limit of 134217728 bytes (128 MiB)"});
    fs::resize_file(big, 3);
    EXPECT_EQ(read_text_file(big), std::string(3, '\0'));
}

}  // namespace
}  // namespace slc
