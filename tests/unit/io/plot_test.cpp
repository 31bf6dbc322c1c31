// Tests of line plots: both formats are written; each axis is scaled to its own data, so a line
// passes where its numbers say; degenerate data still draws; bad arguments are InvalidInput.
#include "slc/io/plot.hpp"

#include <cairo.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "slc/core/error.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;

// The page layout of plot.cpp with narrow y tick labels: an 80 px left margin, 560 px wide panels
// 240 px high and 16 px apart, 30 px on the right, 20 px above (and 34 more for a title), 60 px
// below; PNG at twice that.
constexpr int plot_left = 80;
constexpr int plot_width = 560;
constexpr int panel_height = 240;
constexpr int panel_gap = 16;
constexpr int top = 20;
constexpr int title_room = 34;
constexpr int png_scale = 2;

using test_support::TempDir;

using test_support::slurp;

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

SurfacePtr read_png(const fs::path& path) {
    SurfacePtr image(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS) << path;
    return image;
}

/// The colour of PNG pixel (x, y), y down, as 0xRRGGBB.
std::uint32_t pixel(cairo_surface_t* image, int x, int y) {
    cairo_surface_flush(image);
    const unsigned char* row =
        cairo_image_surface_get_data(image) + y * cairo_image_surface_get_stride(image);
    return reinterpret_cast<const std::uint32_t*>(row)[x] & 0xffffffu;
}

std::uint32_t hex(Color c) {
    auto byte = [](double v) { return static_cast<std::uint32_t>(std::lround(255.0 * v)); };
    return byte(c.r) << 16 | byte(c.g) << 8 | byte(c.b);
}

/// y = f(x) at n + 1 points from x0 to x1.
PlotSeries sampled(double x0, double x1, int n, double (*f)(double), Color color) {
    PlotSeries s;
    for (int i = 0; i <= n; ++i) {
        const double x = x0 + (x1 - x0) * i / n;
        s.x.push_back(x);
        s.y.push_back(f(x));
    }
    s.color = color;
    return s;
}

LinePlot two_panels() {
    LinePlot plot;
    plot.title = "circle: area and length";
    plot.x_name = "t";
    plot.panels.push_back(
        {"area",
         {sampled(
             0.0, 2.0, 40, [](double t) { return 5 * M_PI - 2 * M_PI * t; }, palette_color(0))}});
    plot.panels.push_back(
        {"length",
         {sampled(
             0.0, 2.0, 40, [](double t) { return 2 * M_PI * std::sqrt(5 - 2 * t); },
             palette_color(1))}});
    return plot;
}

TEST(Plot, WritesSvgAndPngOfStackedPanels) {
    const TempDir dir;
    const LinePlot plot = two_panels();
    save_plot(plot, dir.path() / "history.svg");
    save_plot(plot, dir.path() / "sub" / "history.PNG");
    const std::string svg = slurp(dir.path() / "history.svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    const std::string png = slurp(dir.path() / "sub" / "history.PNG");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

    // Two panels and a title, as the layout says.
    const SurfacePtr image = read_png(dir.path() / "sub" / "history.PNG");
    EXPECT_EQ(cairo_image_surface_get_height(image.get()),
              png_scale * (top + title_room + 2 * panel_height + panel_gap + 60));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 2);
}

TEST(Plot, ScalesEachAxisToItsData) {
    // y = x / 10 on [0, 10]: in a square-aspect picture a nearly flat line, here the panel's
    // diagonal. The y axis spans [−0.05, 1.05] (5% margins), the x axis [0, 10] exactly, so the
    // line passes through the panel's centre.
    const TempDir dir;
    LinePlot plot;
    plot.panels.push_back(
        {"y",
         {sampled(
             0.0, 10.0, 100, [](double x) { return x / 10; }, palette_color(2))}});
    save_plot(plot, dir.path() / "line.png");
    const SurfacePtr image = read_png(dir.path() / "line.png");
    const int cx = png_scale * (plot_left + plot_width / 2);
    const int cy = png_scale * (top + panel_height / 2);
    EXPECT_EQ(pixel(image.get(), cx, cy), hex(palette_color(2)));
    // A quarter of the way along, the line is a quarter of the way up (from the data's bottom,
    // 0.05 / 1.1 of the panel above its lower edge).
    const double up = (0.05 + 0.25) / 1.1;
    const int qx = png_scale * (plot_left + plot_width / 4);
    const int qy = static_cast<int>(std::lround(png_scale * (top + (1.0 - up) * panel_height)));
    EXPECT_EQ(pixel(image.get(), qx, qy), hex(palette_color(2)));
    // Far from the line the panel is white.
    EXPECT_EQ(pixel(image.get(), qx, cy + png_scale * panel_height / 4 + 20), 0xffffffu);
}

TEST(Plot, DrawsALongSeriesAsItsEnvelopeInFewBytes) {
    // 10^5 points alternating between 0 and 1: drawn as at most four points per pixel column,
    // the line still fills the band from 0 to 1 in every column.
    const TempDir dir;
    constexpr int n = 100000;
    PlotSeries zigzag;
    for (int i = 0; i < n; ++i) {
        zigzag.x.push_back(static_cast<double>(i) / (n - 1));
        zigzag.y.push_back(i % 2);
    }
    zigzag.color = palette_color(3);
    LinePlot plot;
    plot.panels.push_back({"y", {zigzag}});
    save_plot(plot, dir.path() / "zigzag.svg");
    save_plot(plot, dir.path() / "zigzag.png");
    // About 20 bytes a point: 4 points in each of 1120 columns, not 10^5 points.
    EXPECT_LT(fs::file_size(dir.path() / "zigzag.svg"), 200000u);
    const SurfacePtr image = read_png(dir.path() / "zigzag.png");
    for (const double along : {0.1, 0.37, 0.5, 0.81}) {
        const int x = static_cast<int>(png_scale * (plot_left + along * plot_width));
        for (const double y : {0.0, 0.5, 1.0}) {
            const double up = (0.05 + y) / 1.1;  // the y axis spans [−0.05, 1.05]
            const int row =
                static_cast<int>(std::lround(png_scale * (top + (1.0 - up) * panel_height)));
            EXPECT_EQ(pixel(image.get(), x, row), hex(palette_color(3))) << along << " " << y;
        }
    }
}

TEST(Plot, DrawsConstantZeroAndOnePointSeries) {
    const TempDir dir;
    LinePlot plot;
    // A quantity constant to rounding (the area of a rotating curve), one that is 0 throughout,
    // a single point, and a panel with nothing in it.
    plot.panels.push_back({"area", {{{0.0, 1.0, 2.0}, {M_PI, M_PI * (1 + 1e-15), M_PI}}}});
    plot.panels.push_back({"zero", {{{0.0, 2.0}, {0.0, 0.0}}}});
    plot.panels.push_back({"one point", {{{1.0}, {3.0}}}});
    plot.panels.push_back({"empty", {}});
    EXPECT_NO_THROW(save_plot(plot, dir.path() / "flat.png"));
    EXPECT_NO_THROW(save_plot(plot, dir.path() / "flat.svg"));
    LinePlot single;
    single.panels.push_back({"y", {{{0.5}, {0.5}}}});
    EXPECT_NO_THROW(save_plot(single, dir.path() / "single.png"));
}

TEST(Plot, RejectsBadExtensionAndBadData) {
    const TempDir dir;
    const LinePlot plot = two_panels();
    EXPECT_THROW(save_plot(plot, dir.path() / "history.jpg"), InvalidInput);
    EXPECT_THROW(save_plot(plot, dir.path() / "history"), InvalidInput);
    EXPECT_THROW(save_plot(LinePlot{}, dir.path() / "none.png"), InvalidInput);

    LinePlot uneven = two_panels();
    uneven.panels[1].series[0].y.pop_back();
    EXPECT_THROW(save_plot(uneven, dir.path() / "uneven.png"), InvalidInput);
    LinePlot nan = two_panels();
    nan.panels[0].series[0].y[3] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(save_plot(nan, dir.path() / "nan.png"), InvalidInput);
    LinePlot thin = two_panels();
    thin.panels[0].series[0].line_width = 0.0;
    EXPECT_THROW(save_plot(thin, dir.path() / "thin.png"), InvalidInput);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace slc
