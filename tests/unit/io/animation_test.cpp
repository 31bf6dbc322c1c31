// Tests of the animated SVG: one group per frame, each visible during its own slot of the loop and
// no other; curves mapped onto the plot with y upward; the trail; bad arguments are InvalidInput.
#include "slc/io/animation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "slc/core/error.hpp"

namespace slc {
namespace {

std::vector<AnimationFrame> squares(int n) {
    std::vector<AnimationFrame> frames;
    for (int i = 0; i < n; ++i) {
        const double s = 0.2 * (i + 1);
        frames.push_back({0.5 * i, Interface({{{-s, -s}, {s, -s}, {s, s}, {-s, s}}})});
    }
    return frames;
}

std::vector<std::smatch> all_matches(const std::string& text, const std::regex& re) {
    std::vector<std::smatch> out;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
         ++it)
        out.push_back(*it);
    return out;
}

std::vector<double> numbers(const std::string& list) {
    std::vector<double> out;
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t end = std::min(list.find(';', start), list.size());
        out.push_back(std::stod(list.substr(start, end - start)));
        start = end + 1;
    }
    return out;
}

/// Which of "hidden"/"visible" a discrete animation gives at loop fraction f.
std::string value_at(const std::vector<std::string>& values, const std::vector<double>& keys,
                     double f) {
    std::string v = values.front();
    for (std::size_t k = 0; k < keys.size(); ++k)
        if (keys[k] <= f) v = values[k];
    return v;
}

TEST(AnimatedSvg, EachFrameShowsDuringItsOwnSlotOnly) {
    const int n = 5;
    const std::string svg = animated_svg(squares(n), Box::centered_square(1.0), {0.5, "", false});
    const auto anims = all_matches(
        svg, std::regex("<g id=\"frame(\\d+)\"[\\s\\S]*?<animate attributeName=\"visibility\" "
                        "calcMode=\"discrete\" values=\"([^\"]*)\" keyTimes=\"([^\"]*)\" "
                        "dur=\"([^\"]*)s\""));
    ASSERT_EQ(anims.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        EXPECT_EQ(std::stoi(anims[i][1]), i);
        std::vector<std::string> values;
        const std::string v = anims[i][2];
        for (std::size_t a = 0, b; a < v.size(); a = b + 1) {
            b = std::min(v.find(';', a), v.size());
            values.push_back(v.substr(a, b - a));
        }
        const std::vector<double> keys = numbers(anims[i][3]);
        ASSERT_EQ(values.size(), keys.size());
        EXPECT_EQ(keys.front(), 0.0);
        EXPECT_DOUBLE_EQ(std::stod(anims[i][4]), 0.5 * n);
        // Sample the middle of every slot: visible in slot i only.
        for (int slot = 0; slot < n; ++slot) {
            const double f = (slot + 0.5) / n;
            EXPECT_EQ(value_at(values, keys, f), slot == i ? "visible" : "hidden")
                << "frame " << i << " in slot " << slot;
        }
    }
}

TEST(AnimatedSvg, MapsThePlaneOntoThePlotWithYUpward) {
    // One triangle in the view [0, 2]²: (0, 0) is the plot's bottom-left corner, (2, 2) its top
    // right; the plot is 560 px wide from x = 20, y = 44.
    const std::vector<AnimationFrame> frames = {
        {0.0, Interface({{{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}}})}};
    const std::string svg = animated_svg(frames, Box{{0.0, 0.0}, {2.0, 2.0}}, {1.0, "", false});
    EXPECT_NE(svg.find("d=\"M20.00 604.00L580.00 604.00L580.00 44.00Z\""), std::string::npos)
        << svg;
}

TEST(AnimatedSvg, TrailHoldsEveryNonEmptyFrame) {
    std::vector<AnimationFrame> frames = squares(3);
    frames.push_back({2.0, Interface{}});  // vanished
    const std::string svg = animated_svg(frames, Box::centered_square(1.0), {});
    const std::size_t trail = svg.find("<g id=\"trail\"");
    ASSERT_NE(trail, std::string::npos);
    const std::string trail_group = svg.substr(trail, svg.find("</g>", trail) - trail);
    EXPECT_EQ(all_matches(trail_group, std::regex("<path ")).size(), 3u);
    EXPECT_NE(svg.find("t = 2 (nothing left)"), std::string::npos);
}

TEST(AnimatedSvg, TitleIsEscaped) {
    const std::string svg =
        animated_svg(squares(1), Box::centered_square(1.0), {0.25, "a < b & c", true});
    EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
}

TEST(AnimatedSvg, BadArgumentsAreInvalid) {
    const Box view = Box::centered_square(1.0);
    EXPECT_THROW(animated_svg({}, view), InvalidInput);
    EXPECT_THROW(animated_svg(squares(2), Box{{0, 0}, {0, 0}}), InvalidInput);
    EXPECT_THROW(animated_svg(squares(2), view, {0.0, "", true}), InvalidInput);
    EXPECT_THROW(animated_svg(squares(2), view, {std::nan(""), "", true}), InvalidInput);
    std::vector<AnimationFrame> bad = squares(2);
    bad[1].time = std::numeric_limits<double>::infinity();
    EXPECT_THROW(animated_svg(bad, view), InvalidInput);
}

}  // namespace
}  // namespace slc
