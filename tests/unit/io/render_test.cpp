// Tests of pictures: both formats are written, atomically; the PNG has the layout's size and shows
// a field the right way up with the right colours; bad arguments are InvalidInput.
#include "slc/io/render.hpp"

#include <cairo.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "slc/core/error.hpp"
#include "temp_dir.hpp"

// Cairo's toy text API keeps fontconfig's configuration and font patterns in process-wide caches
// that are never freed; LeakSanitizer (the SLC_SANITIZE build) would report them at exit. This
// hook, read by LeakSanitizer only, names them as expected.
extern "C" const char* __lsan_default_suppressions() { return "leak:libfontconfig.so\n"; }

namespace slc {
namespace {

namespace fs = std::filesystem;

// The page layout of render.cpp for a figure with no title, legend or field: an 80 px left
// margin, a 560 px plot, 30 px on the right, 20 px above, 60 px below; PNG at twice that.
constexpr int plain_width = 670;
constexpr int plain_height = 640;
constexpr int title_room = 34;
constexpr int plot_left = 80;
constexpr int plot_top = 20;
constexpr int plot_size = 560;
constexpr int png_scale = 2;

using test_support::TempDir;

using test_support::slurp;

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

SurfacePtr read_png(const fs::path& path) {
    SurfacePtr image(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS) << path;
    return image;
}

/// The colour of PNG pixel (x, y), y down, as 0–255 components.
struct Rgb {
    int r, g, b;
};
Rgb pixel(cairo_surface_t* image, int x, int y) {
    cairo_surface_flush(image);
    const unsigned char* row =
        cairo_image_surface_get_data(image) + y * cairo_image_surface_get_stride(image);
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[x];
    return {static_cast<int>((argb >> 16) & 0xff), static_cast<int>((argb >> 8) & 0xff),
            static_cast<int>(argb & 0xff)};
}

/// On the centre column of a plain plot of [−1, 1]², the pixel a quarter of the way down (y = 0.5)
/// is red and the one a quarter of the way up (y = −0.5) blue, as the diverging map draws
/// positive and negative values.
void expect_red_above_and_blue_below(cairo_surface_t* image) {
    const int x = png_scale * (plot_left + plot_size / 2);
    const Rgb upper = pixel(image, x, png_scale * (plot_top + plot_size / 4));
    const Rgb lower = pixel(image, x, png_scale * (plot_top + 3 * plot_size / 4));
    EXPECT_GT(upper.r, upper.b + 40) << upper.r << " " << upper.g << " " << upper.b;
    EXPECT_GT(lower.b, lower.r + 40) << lower.r << " " << lower.g << " " << lower.b;
}

/// A field equal to y on the box: negative below the x axis, positive above.
ScalarGrid y_field(const Box& box, int n) {
    ScalarGrid grid{box, n, n, std::vector<double>(static_cast<std::size_t>(n) * n)};
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            grid.values[static_cast<std::size_t>(j) * n + i] =
                box.lo.y + (j + 0.5) * box.height() / n;
        }
    }
    return grid;
}

Interface circle(Vec2 c, double r, int n) {
    std::vector<Vec2> points;
    for (int k = 0; k < n; ++k) {
        const double t = 2.0 * M_PI * k / n;
        points.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
    }
    return Interface({points});
}

TEST(Render, WritesSvgAndPngOfEveryKindOfLayer) {
    const TempDir dir;
    Figure figure(Box::centered_square(1.5), "every layer");
    figure.add_field(y_field(Box::centered_square(1.0), 16), "y", true);
    const std::vector<Box> boxes = {{{-1.0, -1.0}, {0.0, 0.0}}, {{0.0, 0.0}, {0.5, 0.5}}};
    figure.add_boxes(boxes, {0.3, 0.3, 0.3, 1.0});
    const std::vector<Vec2> vertices = {{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}};
    const std::vector<std::array<std::uint32_t, 3>> triangles = {{0, 1, 2}};
    figure.add_triangles(vertices, triangles, {0.0, 0.5, 0.0, 1.0});
    figure.add_curves(circle({0.0, 0.0}, 0.7, 64), "circle", palette_color(0));
    figure.add_points(vertices, palette_color(1));
    const std::vector<Vec2> vec = {{0.1, 0.0}, {0.0, 0.1}, {0.0, 0.0}};
    figure.add_arrows(vertices, vec, 2.0, palette_color(2));

    figure.save(dir.path() / "a.svg");
    figure.save(dir.path() / "sub" / "a.PNG");
    const std::string svg = slurp(dir.path() / "a.svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    const std::string png = slurp(dir.path() / "sub" / "a.PNG");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(Render, PngHasTheLayoutSizeAtTwiceTheScale) {
    const TempDir dir;
    Figure(Box::centered_square(2.0)).save(dir.path() / "plain.png");
    const SurfacePtr plain = read_png(dir.path() / "plain.png");
    EXPECT_EQ(cairo_image_surface_get_width(plain.get()), png_scale * plain_width);
    EXPECT_EQ(cairo_image_surface_get_height(plain.get()), png_scale * plain_height);

    // A title adds room above; a legend adds a column on the right.
    Figure titled(Box::centered_square(2.0), "title");
    titled.add_curves(circle({0.0, 0.0}, 1.0, 32), "label", palette_color(0));
    titled.save(dir.path() / "titled.png");
    const SurfacePtr image = read_png(dir.path() / "titled.png");
    EXPECT_EQ(cairo_image_surface_get_height(image.get()), png_scale * (plain_height + title_room));
    EXPECT_GT(cairo_image_surface_get_width(image.get()), png_scale * plain_width);
}

TEST(Render, LegendListsFortyLayersAndCountsTheRest) {
    const TempDir dir;
    const Interface ring = circle({0.0, 0.0}, 1.0, 16);
    auto height_with = [&](int labelled) {
        Figure f(Box::centered_square(2.0));
        for (int i = 0; i < labelled; ++i)
            f.add_curves(ring, fmt::format("layer {}", i), palette_color(i));
        const fs::path png = dir.path() / fmt::format("legend_{}.png", labelled);
        f.save(png);
        f.save(dir.path() / fmt::format("legend_{}.svg", labelled));
        return cairo_image_surface_get_height(read_png(png).get()) / png_scale;
    };
    const int forty = height_with(40);
    EXPECT_GT(forty, plain_height);          // forty rows are taller than the plot
    EXPECT_EQ(height_with(41), forty + 20);  // one more row: "… and 1 more"
    // Two thousand rows would be 40000 pixels tall, beyond what cairo draws.
    EXPECT_EQ(height_with(2000), forty + 20);
    EXPECT_GT(fs::file_size(dir.path() / "legend_2000.svg"), 0u);
}

TEST(Render, DivergingFieldIsBlueBelowZeroAndRedAboveWithYUp) {
    const TempDir dir;
    Figure figure(Box::centered_square(1.0));
    figure.add_field(y_field(Box::centered_square(1.0), 50), "phi", true);
    figure.save(dir.path() / "field.png");
    const SurfacePtr image = read_png(dir.path() / "field.png");

    expect_red_above_and_blue_below(image.get());
    // Outside the plot the page is white.
    const Rgb corner = pixel(image.get(), 2, 2);
    EXPECT_EQ(corner.r + corner.g + corner.b, 3 * 255);
}

TEST(Render, ValuesOnACurveColourItsSegmentsOnTheFieldsMap) {
    // A circle of radius 0.5 coloured by y at its vertices, on the diverging map: red at its top,
    // blue at its bottom, and a colour bar as for a field.
    const TempDir dir;
    const Interface c = circle({0.0, 0.0}, 0.5, 64);
    std::vector<double> y;
    for (const Vec2 p : c.points()) y.push_back(p.y);
    Figure figure(Box::centered_square(1.0));
    figure.add_curve_values(c, y, "V_y", true, 8.0);
    figure.save(dir.path() / "values.png");
    const SurfacePtr image = read_png(dir.path() / "values.png");
    expect_red_above_and_blue_below(image.get());
    // Inside the circle nothing is drawn.
    const Rgb centre = pixel(image.get(), png_scale * (plot_left + plot_size / 2),
                             png_scale * (plot_top + plot_size / 2));
    EXPECT_EQ(centre.r + centre.g + centre.b, 3 * 255);
    // One value a vertex.
    EXPECT_THROW(figure.add_curve_values(c, std::span(y).first(10), "V_y"), InvalidInput);
}

TEST(Render, SavingReplacesTheFileAndLeavesNoTemporaryFile) {
    const TempDir dir;
    const fs::path path = dir.path() / "fig.svg";
    std::ofstream(path) << "old";
    Figure(Box::centered_square(1.0)).save(path);
    EXPECT_NE(slurp(path).find("<svg"), std::string::npos);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);
}

TEST(Render, RejectsBadExtensionAndBadArguments) {
    const TempDir dir;
    Figure figure(Box::centered_square(1.0));
    EXPECT_THROW(figure.save(dir.path() / "fig.jpg"), InvalidInput);
    EXPECT_THROW(figure.save(dir.path() / "fig"), InvalidInput);
    EXPECT_TRUE(fs::is_empty(dir.path()));

    EXPECT_THROW(Figure(Box{{1.0, 1.0}, {1.0, 1.0}}), InvalidInput);
    EXPECT_THROW(Figure(Box{{1.0, 1.0}, {0.0, 2.0}}), InvalidInput);
    EXPECT_THROW(Figure(Box{{0.0, 0.0}, {NAN, 1.0}}), InvalidInput);
    EXPECT_THROW(figure.add_field(ScalarGrid{Box::centered_square(1.0), 2, 2, {1.0}}, "f", false),
                 InvalidInput);
    const std::vector<Vec2> two = {{0.0, 0.0}, {1.0, 1.0}};
    const std::vector<std::array<std::uint32_t, 3>> bad = {{0, 1, 2}};
    EXPECT_THROW(figure.add_triangles(two, bad, {}), InvalidInput);
    EXPECT_THROW(figure.add_arrows(two, std::span<const Vec2>(two).first(1), 1.0, {}),
                 InvalidInput);
    EXPECT_THROW(figure.add_points(two, {}, -1.0), InvalidInput);
}

TEST(Render, PaletteCyclesThroughDistinctColours) {
    for (std::size_t i = 0; i < 8; ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            const Color a = palette_color(i);
            const Color b = palette_color(j);
            EXPECT_FALSE(a.r == b.r && a.g == b.g && a.b == b.b) << i << " " << j;
        }
        EXPECT_EQ(palette_color(i).r, palette_color(i + 8).r);
        EXPECT_EQ(palette_color(i).a, 1.0);
    }
}

}  // namespace
}  // namespace slc
