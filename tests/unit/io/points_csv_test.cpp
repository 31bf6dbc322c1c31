// Tests of point files: what is accepted (header, blank lines, CRLF, spaces) and one message per
// kind of bad line, naming the file and the line.
#include "slc/io/points_csv.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <initializer_list>
#include <random>

#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;

/// Parses text as "pts.csv", expects InvalidInput, and checks that its message holds every part.
void expect_invalid(const std::string& text, std::initializer_list<std::string> parts) {
    SCOPED_TRACE(text);
    try {
        parse_points_csv(text, "pts.csv");
        ADD_FAILURE() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
        const std::string message = e.what();
        for (const std::string& part : parts) {
            EXPECT_NE(message.find(part), std::string::npos)
                << "message \"" << message << "\" lacks \"" << part << "\"";
        }
    }
}

TEST(PointsCsv, ParsesOnePointPerLine) {
    const std::vector<Vec2> points = parse_points_csv("0,0\n1.5,-2\n-1e-3,4e2", "pts.csv");
    EXPECT_EQ(points, (std::vector<Vec2>{{0.0, 0.0}, {1.5, -2.0}, {-1e-3, 400.0}}));
}

TEST(PointsCsv, SkipsHeaderBlankLinesAndCarriageReturns) {
    const std::string text = "\xEF\xBB\xBF x , Y \r\n\r\n1,2\r\n   \r\n\t3 ,  4\r\n\n";
    EXPECT_EQ(parse_points_csv(text, "pts.csv"), (std::vector<Vec2>{{1.0, 2.0}, {3.0, 4.0}}));
    EXPECT_EQ(parse_points_csv("\n\nx,y\n+1,2\n", "pts.csv"), (std::vector<Vec2>{{1.0, 2.0}}));
    EXPECT_TRUE(parse_points_csv("", "pts.csv").empty());
    EXPECT_TRUE(parse_points_csv("x,y\n", "pts.csv").empty());
}

TEST(PointsCsv, ReadsSeventeenDigitNumbersExactly) {
    const unsigned seed = 77;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1e3, 1e3);
    std::vector<Vec2> points(200);
    std::string text = "x,y\n";
    for (Vec2& p : points) {
        p = {u(rng), u(rng) * 1e-200};
        text += fmt::format("{:.17g},{:.17g}\n", p.x, p.y);
    }
    const std::vector<Vec2> back = parse_points_csv(text, "pts.csv");
    ASSERT_EQ(back.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(back[i].x),
                  std::bit_cast<std::uint64_t>(points[i].x))
            << "seed " << seed << ", point " << i;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(back[i].y),
                  std::bit_cast<std::uint64_t>(points[i].y))
            << "seed " << seed << ", point " << i;
    }
}

TEST(PointsCsv, RejectsWrongColumnCount) {
    expect_invalid("x,y\n0,0\n\n1,2,3\n", {"pts.csv, line 4: expected 2 columns x,y, got 3"});
    expect_invalid("1\n", {"pts.csv, line 1: expected 2 columns x,y, got 1"});
    expect_invalid("1;2\n", {"pts.csv, line 1: expected 2 columns x,y, got 1"});
    expect_invalid("1,2,\n", {"pts.csv, line 1: expected 2 columns x,y, got 3"});
}

TEST(PointsCsv, RejectsFieldsThatAreNotWholeNumbers) {
    expect_invalid("0,0\n1,abc\n", {"pts.csv, line 2:", "y = \"abc\" is not a number"});
    expect_invalid("1.5x,2\n", {"pts.csv, line 1:", "x = \"1.5x\" is not a number"});
    expect_invalid(",2\n", {"pts.csv, line 1:", "x = \"\" is not a number"});
    expect_invalid("1 2,3\n", {"pts.csv, line 1:", "is not a number"});
    expect_invalid("+-1,3\n", {"pts.csv, line 1:", "is not a number"});
    // A header is only a header on the first line with content.
    expect_invalid("1,2\nx,y\n", {"pts.csv, line 2:", "x = \"x\" is not a number"});
}

TEST(PointsCsv, RejectsNonFiniteValues) {
    expect_invalid("inf,0\n", {"pts.csv, line 1:", "x = \"inf\" is not finite"});
    expect_invalid("0,0\n0,nan\n", {"pts.csv, line 2:", "y = \"nan\" is not finite"});
    expect_invalid("0,-1e400\n", {"pts.csv, line 1:", "y = \"-1e400\"", "range"});
}

TEST(PointsCsv, RejectsValuesBeyondTheCoordinateLimit) {
    expect_invalid("1e101,0\n", {"pts.csv, line 1:", "x = \"1e101\"", "coordinate limit"});
    EXPECT_EQ(parse_points_csv("-1e100,1e100\n", "pts.csv"), (std::vector<Vec2>{{-1e100, 1e100}}));
}

TEST(PointsCsv, QuotesGarbageOnOneShortLine) {
    // Control bytes become '?', a long field is cut: the message stays one readable line.
    expect_invalid("\x01\r\x1b[1m,0\n", {"x = \"???[1m\" is not a number"});
    expect_invalid("0," + std::string(1000, 'z') + "\n",
                   {"y = \"" + std::string(24, 'z') + "...\""});
}

TEST(PointsCsv, ReadsAFileAndRejectsAMissingOne) {
    const fs::path dir =
        fs::temp_directory_path() / fmt::format("slc_points_csv_test_{}", ::getpid());
    fs::remove_all(dir);
    const fs::path path = dir / "pts.csv";
    write_file_atomic(path, "x,y\n0.25,-0.5\n");
    EXPECT_EQ(read_points_csv(path), (std::vector<Vec2>{{0.25, -0.5}}));

    write_file_atomic(path, "x,y\n0.25\n");
    try {
        read_points_csv(path);
        ADD_FAILURE() << "expected InvalidInput";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find(path.string() + ", line 2:"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(read_points_csv(dir / "missing.csv"), InvalidInput);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace slc
