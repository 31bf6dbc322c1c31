// Tests of the animated SVG: one group per frame, each visible during its own slot of the loop and
// no other; curves mapped onto the plot with y upward; the trail; bad arguments are InvalidInput.
#include "slc/io/animation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

/// How many times `what` occurs in text.
std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

/// The value of attribute `name` in the first element `<tag ...>` at or after from.
std::string attribute(const std::string& svg, const std::string& tag, const std::string& name,
                      std::size_t from) {
    const std::size_t begin = svg.find("<" + tag + " ", from);
    const std::string e = svg.substr(begin, svg.find('>', begin) + 1 - begin);
    const std::size_t at = e.find(" " + name + "=\"") + name.size() + 3;
    return e.substr(at, e.find('"', at) - at);
}

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> out;
    for (std::size_t a = 0, b = 0; a <= list.size(); a = b + 1) {
        b = std::min(list.find(';', a), list.size());
        out.push_back(list.substr(a, b - a));
    }
    return out;
}

std::vector<double> numbers(const std::string& list) {
    std::vector<double> out;
    for (const std::string& item : split(list)) out.push_back(std::stod(item));
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
    ASSERT_EQ(count(svg, "<g id=\"frame"), static_cast<std::size_t>(n));
    ASSERT_EQ(count(svg, "<animate "), static_cast<std::size_t>(n));
    std::size_t group = 0;
    for (int i = 0; i < n; ++i) {
        group = svg.find("<g id=\"frame", group + 1);
        EXPECT_EQ(attribute(svg, "g", "id", group), "frame" + std::to_string(i));
        EXPECT_EQ(attribute(svg, "animate", "attributeName", group), "visibility");
        EXPECT_EQ(attribute(svg, "animate", "calcMode", group), "discrete");
        const std::vector<std::string> values = split(attribute(svg, "animate", "values", group));
        const std::vector<double> keys = numbers(attribute(svg, "animate", "keyTimes", group));
        ASSERT_EQ(values.size(), keys.size());
        EXPECT_EQ(keys.front(), 0.0);
        EXPECT_EQ(attribute(svg, "animate", "dur", group), "2.5s");  // 5 frames × 0.5 s
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
    EXPECT_EQ(count(trail_group, "<path "), 3u);
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
