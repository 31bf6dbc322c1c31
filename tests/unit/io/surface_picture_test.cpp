// Tests of surface pictures: a sphere fills the middle of the PNG and leaves its margin white, and
// is brighter on the lit side; a torus seen from above shows the background in its hole; +z is up
// (or the up axis asked for) and the nearer of two surfaces hides the farther; the guides (axis
// triad, scale bar) and a colour bar sit in the band below; the up axis chosen from extents; a
// quantity colours the surface; SVG is written too; the same input gives the same bytes; faces
// leave no crack between them; bad input is InvalidInput and writes nothing.
#include "slc/io/surface_picture.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;
using test_support::slurp;
using test_support::TempDir;

using ImagePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

// The default picture: 800 × 800 pixels with a margin of 5 % of its side (40 pixels), and a band
// of guides 11 % of its side tall (88 pixels) at the bottom. The tests of where things go turn
// the guides off (the layout of a margin all round).
constexpr int side = 800;
constexpr int margin = 40;

SurfaceView without_guides() {
    SurfaceView view;
    view.guides = false;
    return view;
}

SurfaceView from_azimuth(double azimuth) {
    SurfaceView view;
    view.azimuth = azimuth;
    return view;
}

ImagePtr read_png(const fs::path& path) {
    ImagePtr image(cairo_image_surface_create_from_png(path.c_str()), &cairo_surface_destroy);
    EXPECT_EQ(cairo_surface_status(image.get()), CAIRO_STATUS_SUCCESS) << path;
    cairo_surface_flush(image.get());
    return image;
}

/// The colour of pixel (x, y), y down, as 0–255 components.
struct Rgb {
    int r, g, b;
    bool is_background() const { return r == 255 && g == 255 && b == 255; }
    int brightness() const { return (r + g + b) / 3; }
};

Rgb pixel(cairo_surface_t* image, int x, int y) {
    const unsigned char* row =
        cairo_image_surface_get_data(image) + y * cairo_image_surface_get_stride(image);
    const std::uint32_t argb = reinterpret_cast<const std::uint32_t*>(row)[x];
    return {static_cast<int>((argb >> 16) & 0xff), static_cast<int>((argb >> 8) & 0xff),
            static_cast<int>(argb & 0xff)};
}

/// Mean brightness of the (2h + 1)² pixels around (x, y).
double mean_brightness(cairo_surface_t* image, int x, int y, int h) {
    double sum = 0.0;
    for (int j = y - h; j <= y + h; ++j)
        for (int i = x - h; i <= x + h; ++i) sum += pixel(image, i, j).brightness();
    return sum / ((2 * h + 1) * (2 * h + 1));
}

/// True when every pixel of the picture's outer band `width` pixels wide is background.
bool border_is_background(cairo_surface_t* image, int width) {
    const int w = cairo_image_surface_get_width(image);
    const int h = cairo_image_surface_get_height(image);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const bool inner = x >= width && x < w - width && y >= width && y < h - width;
            if (!inner && !pixel(image, x, y).is_background()) return false;
        }
    }
    return true;
}

TEST(SurfacePicture, SphereFillsTheMiddleAndLeavesTheMarginWhite) {
    const TempDir dir;
    save_surface_picture(sphere({1.0, 2.0, 3.0}, 0.5, 4), dir.path() / "sphere.png",
                         without_guides());
    const ImagePtr image = read_png(dir.path() / "sphere.png");
    ASSERT_EQ(cairo_image_surface_get_width(image.get()), side);
    ASSERT_EQ(cairo_image_surface_get_height(image.get()), side);
    EXPECT_FALSE(pixel(image.get(), side / 2, side / 2).is_background());
    for (const int x : {0, side - 1})
        for (const int y : {0, side - 1}) EXPECT_TRUE(pixel(image.get(), x, y).is_background());
    // The sphere lies inside its bounding box's projection, which fills the page to the margin;
    // a pixel less for the antialiased rim and the seam strokes.
    EXPECT_TRUE(border_is_background(image.get(), margin - 1));
}

TEST(SurfacePicture, LitSideOfASphereIsBrighterThanTheSideAwayFromTheLight) {
    const TempDir dir;
    save_surface_picture(sphere({0.0, 0.0, 0.0}, 1.0, 5), dir.path() / "sphere.png",
                         without_guides());
    const ImagePtr image = read_png(dir.path() / "sphere.png");
    // The light comes from above left of the viewer. The sphere's disc has a radius of about 240
    // pixels; patches 100 pixels up-left and down-right of its centre lie well inside it, where
    // Lambert's law gives brightness 0.99 and 0.49 of the colour's. Half that difference of the
    // palette blue's mean (122) is asserted.
    constexpr int offset = 100;
    constexpr int patch = 5;
    constexpr double least_difference = 30.0;
    const double lit = mean_brightness(image.get(), side / 2 - offset, side / 2 - offset, patch);
    const double dark = mean_brightness(image.get(), side / 2 + offset, side / 2 + offset, patch);
    EXPECT_GT(lit, dark + least_difference) << lit << " " << dark;
    EXPECT_LT(lit, 255.0);
}

TEST(SurfacePicture, TorusSeenFromAboveShowsTheBackgroundInItsHole) {
    const TempDir dir;
    SurfaceView view;
    view.elevation = 90.0;
    view.guides = false;
    const double major = 1.0;
    save_surface_picture(torus({0.0, 0.0, 0.0}, major, 0.35, 64, 24), dir.path() / "torus.png",
                         view);
    const ImagePtr image = read_png(dir.path() / "torus.png");
    EXPECT_TRUE(pixel(image.get(), side / 2, side / 2).is_background());
    // The box [−1.35, 1.35]² turned by the azimuth (35°) spans 2.7 (cos 35° + sin 35°) = 3.76
    // units across the 720 pixels inside the margin: the tube's centre circle is 191 pixels from
    // the middle, in every direction.
    const int ring = static_cast<int>(major * (side - 2 * margin) / (2.7 * 1.3927));
    for (const auto& [dx, dy] : {std::pair{ring, 0}, {-ring, 0}, {0, ring}, {0, -ring}})
        EXPECT_FALSE(pixel(image.get(), side / 2 + dx, side / 2 + dy).is_background());
}

/// True when the pixel has the hue of palette colour 0 (a blue) rather than 1 (an orange).
bool is_blue(Rgb c) { return c.b > c.r + 20; }
bool is_orange(Rgb c) { return c.r > c.b + 20; }

TEST(SurfacePicture, ZIsUpAndEachSurfaceHasItsPaletteColour) {
    const TempDir dir;
    const std::vector<Surface> stacked = {sphere({0.0, 0.0, 1.5}, 1.0, 3),
                                          sphere({0.0, 0.0, -1.5}, 1.0, 3)};
    SurfaceView view;
    view.azimuth = 0.0;
    view.elevation = 0.0;
    view.edges = false;
    view.guides = false;
    save_surface_picture(stacked, dir.path() / "stacked.png", view);
    const ImagePtr image = read_png(dir.path() / "stacked.png");
    // The box spans 5 units of height over 720 pixels: the centres are 216 pixels from the
    // middle, the upper sphere (blue) above.
    const Rgb upper = pixel(image.get(), side / 2, side / 2 - 216);
    const Rgb lower = pixel(image.get(), side / 2, side / 2 + 216);
    EXPECT_TRUE(is_blue(upper)) << upper.r << " " << upper.g << " " << upper.b;
    EXPECT_TRUE(is_orange(lower)) << lower.r << " " << lower.g << " " << lower.b;
}

TEST(SurfacePicture, UpYTurnsTheViewAboutY) {
    // Seen from azimuth 0 about y (from +z), elevation 0: y is up, x to the right.
    const TempDir dir;
    const std::vector<Surface> stacked = {sphere({0.0, 1.5, 0.0}, 1.0, 3),
                                          sphere({0.0, -1.5, 0.0}, 1.0, 3)};
    SurfaceView view;
    view.azimuth = 0.0;
    view.elevation = 0.0;
    view.edges = false;
    view.guides = false;
    view.up = UpAxis::y;
    save_surface_picture(stacked, dir.path() / "stacked.png", view);
    const ImagePtr image = read_png(dir.path() / "stacked.png");
    const Rgb upper = pixel(image.get(), side / 2, side / 2 - 216);
    const Rgb lower = pixel(image.get(), side / 2, side / 2 + 216);
    EXPECT_TRUE(is_blue(upper)) << upper.r << " " << upper.g << " " << upper.b;
    EXPECT_TRUE(is_orange(lower)) << lower.r << " " << lower.g << " " << lower.b;
}

TEST(SurfacePicture, UpAxisIsZUnlessTheExtentsSayY) {
    auto up = [](double x, double y, double z) { return up_axis({{0.0, 0.0, 0.0}, {x, y, z}}); };
    EXPECT_EQ(up(1.0, 1.0, 1.0), UpAxis::z);  // a sphere
    EXPECT_EQ(up(2.4, 2.4, 0.7), UpAxis::z);  // a torus about z, lying flat
    EXPECT_EQ(up(2.4, 0.7, 2.4), UpAxis::y);  // a torus about y
    EXPECT_EQ(up(0.7, 2.4, 2.4), UpAxis::z);  // a torus about x: y and z alike
    EXPECT_EQ(up(0.6, 1.4, 0.6), UpAxis::y);  // an ellipsoid long along y
    EXPECT_EQ(up(0.6, 0.6, 1.4), UpAxis::z);  // ... along z
    EXPECT_EQ(up(0.6, 1.8, 0.3), UpAxis::y);  // a figure, y up
    EXPECT_EQ(up(0.6, 0.3, 1.8), UpAxis::z);  // a figure, z up
    EXPECT_EQ(up(0.5, 1.6, 2.0), UpAxis::y);  // an animal, y up, its length along z
    EXPECT_EQ(up(0.5, 2.0, 1.6), UpAxis::z);  // an animal, z up, its length along y
    EXPECT_EQ(up(0.0, 0.0, 0.0), UpAxis::z);  // a point
}

/// True when some pixel of the rectangle [x0, x1) × [y0, y1) satisfies the condition.
template <class Condition>
bool any_pixel(cairo_surface_t* image, int x0, int x1, int y0, int y1, Condition condition) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            if (condition(pixel(image, x, y))) return true;
    return false;
}

TEST(SurfacePicture, GuidesAreDrawnInTheBandBelowTheSurface) {
    // The triad's red, green and blue arms at the bottom left, the scale bar's black at the
    // bottom right; nothing there without guides.
    const TempDir dir;
    const Surface ball = sphere({0.0, 0.0, 0.0}, 1.0, 3);
    save_surface_picture(ball, dir.path() / "guides.png");
    save_surface_picture(ball, dir.path() / "none.png", without_guides());
    const ImagePtr with = read_png(dir.path() / "guides.png");
    const ImagePtr without = read_png(dir.path() / "none.png");
    constexpr int band_top = side - 88;
    auto red = [](Rgb c) { return c.r > c.g + 60 && c.r > c.b + 60; };
    auto green = [](Rgb c) { return c.g > c.r + 40 && c.g > c.b + 40; };
    auto blue = [](Rgb c) { return c.b > c.r + 60 && c.b > c.g + 20; };
    auto black = [](Rgb c) { return c.brightness() < 40; };
    for (const auto& condition : {std::function<bool(Rgb)>(red), {green}, {blue}}) {
        EXPECT_TRUE(any_pixel(with.get(), 0, side / 4, band_top, side, condition));
        EXPECT_FALSE(any_pixel(without.get(), 0, side / 4, band_top, side, condition));
    }
    EXPECT_TRUE(any_pixel(with.get(), 3 * side / 4, side, band_top, side, black));
    EXPECT_FALSE(any_pixel(without.get(), 3 * side / 4, side, band_top, side, black));
}

TEST(SurfacePicture, FourViewsShowWhatOneHides) {
    // Two spheres on the x axis: seen from +x the nearer (blue) hides the smaller farther one
    // (orange); from +y and from above both show. The page holds the four views 2 × 2.
    const TempDir dir;
    const std::vector<Surface> in_line = {sphere({1.5, 0.0, 0.0}, 1.0, 3),
                                          sphere({-1.5, 0.0, 0.0}, 0.8, 3)};
    SurfaceView view;
    view.width = view.height = 400;
    view.edges = false;
    view.guides = false;
    save_surface_views(in_line, dir.path() / "views.png", view);
    const ImagePtr image = read_png(dir.path() / "views.png");
    EXPECT_EQ(cairo_image_surface_get_width(image.get()), 800);
    EXPECT_EQ(cairo_image_surface_get_height(image.get()), 800);
    const auto shows = [&](int quadrant, auto condition) {
        const int x0 = (quadrant % 2) * 400, y0 = (quadrant / 2) * 400;
        return any_pixel(image.get(), x0, x0 + 400, y0, y0 + 400, condition);
    };
    EXPECT_TRUE(shows(0, is_blue) && shows(0, is_orange));  // the view given: both
    EXPECT_TRUE(shows(1, is_blue));                         // from +x: the nearer only
    EXPECT_FALSE(shows(1, is_orange));
    for (const int quadrant : {2, 3})  // from +y, from above
        EXPECT_TRUE(shows(quadrant, is_blue) && shows(quadrant, is_orange)) << quadrant;
    view.width = 20000;
    EXPECT_THROW(save_surface_views(in_line, dir.path() / "wide.png", view), InvalidInput);
    EXPECT_FALSE(fs::exists(dir.path() / "wide.png"));
}

TEST(SurfacePicture, ColoringPaintsByTheValuesWithAColourBar) {
    // Coloured by x: seen from +x the sphere's middle is red, from −x blue; the colour bar's two
    // ends in the band below.
    const TempDir dir;
    const Surface ball = sphere({0.0, 0.0, 0.0}, 1.0, 4);
    SurfaceColoring by_x{{}, "x"};
    for (const Vec3& v : ball.vertices) by_x.values.push_back(v.x);
    save_surface_picture(ball, by_x, dir.path() / "front.png", from_azimuth(0.0));
    save_surface_picture(ball, by_x, dir.path() / "back.png", from_azimuth(180.0));
    const ImagePtr front = read_png(dir.path() / "front.png");
    const ImagePtr back = read_png(dir.path() / "back.png");
    const Rgb f = pixel(front.get(), side / 2, side / 2);
    const Rgb b = pixel(back.get(), side / 2, side / 2);
    EXPECT_GT(f.r, f.b + 40) << f.r << " " << f.g << " " << f.b;
    EXPECT_GT(b.b, b.r + 40) << b.r << " " << b.g << " " << b.b;
    const int bar_y = side - 44;  // the middle of the band
    const Rgb left = pixel(front.get(), static_cast<int>(0.31 * side), bar_y);
    const Rgb right = pixel(front.get(), static_cast<int>(0.65 * side), bar_y);
    EXPECT_GT(left.b, left.r + 60) << left.r << " " << left.g << " " << left.b;
    EXPECT_GT(right.r, right.b + 60) << right.r << " " << right.g << " " << right.b;

    EXPECT_THROW(
        save_surface_picture(ball, SurfaceColoring{{1.0, 2.0}, "two"}, dir.path() / "short.png"),
        InvalidInput);
    SurfaceColoring not_finite = by_x;
    not_finite.values[7] = NAN;
    EXPECT_THROW(save_surface_picture(ball, not_finite, dir.path() / "nan.png"), InvalidInput);
    EXPECT_FALSE(fs::exists(dir.path() / "short.png") || fs::exists(dir.path() / "nan.png"));
}

TEST(SurfacePicture, NearerSurfaceHidesTheFartherWhateverTheirOrder) {
    const TempDir dir;
    SurfaceView view;
    view.azimuth = 0.0;  // looking along −x: the sphere at x = 2 is the nearer
    view.elevation = 0.0;
    view.guides = false;
    const Surface near = sphere({2.0, 0.0, 0.0}, 1.0, 3);
    const Surface far = sphere({-2.0, 0.0, 0.0}, 1.0, 3);
    const std::vector<Surface> near_first = {near, far};
    const std::vector<Surface> far_first = {far, near};
    save_surface_picture(near_first, dir.path() / "near_first.png", view);
    save_surface_picture(far_first, dir.path() / "far_first.png", view);
    const Rgb a = pixel(read_png(dir.path() / "near_first.png").get(), side / 2, side / 2);
    const Rgb b = pixel(read_png(dir.path() / "far_first.png").get(), side / 2, side / 2);
    EXPECT_TRUE(is_blue(a)) << a.r << " " << a.g << " " << a.b;
    EXPECT_TRUE(is_orange(b)) << b.r << " " << b.g << " " << b.b;
}

TEST(SurfacePicture, PngHasTheViewsSizeAndATitleAtTheTop) {
    const TempDir dir;
    SurfaceView view;
    view.width = 640;
    view.height = 400;
    save_surface_picture(box_surface({0.0, 0.0, 0.0}, {1.0, 2.0, 0.5}, 3), dir.path() / "a.png",
                         view);
    view.title = "a box";
    save_surface_picture(box_surface({0.0, 0.0, 0.0}, {1.0, 2.0, 0.5}, 3), dir.path() / "b.png",
                         view);
    const ImagePtr plain = read_png(dir.path() / "a.png");
    const ImagePtr titled = read_png(dir.path() / "b.png");
    for (cairo_surface_t* image : {plain.get(), titled.get()}) {
        EXPECT_EQ(cairo_image_surface_get_width(image), 640);
        EXPECT_EQ(cairo_image_surface_get_height(image), 400);
        EXPECT_FALSE(pixel(image, 320, 220).is_background());
    }
    // The title's black letters in the band above the margin (20 pixels: 5 % of 400).
    auto has_dark_pixel_on_top = [](cairo_surface_t* image) {
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 640; ++x)
                if (pixel(image, x, y).brightness() < 64) return true;
        return false;
    };
    EXPECT_FALSE(has_dark_pixel_on_top(plain.get()));
    EXPECT_TRUE(has_dark_pixel_on_top(titled.get()));
}

TEST(SurfacePicture, LongTitleIsSetSmallerToFitBetweenTheMargins) {
    // A title of 90 characters would be some 1000 pixels wide at the default size: it is set
    // smaller, and the side margins above the surface stay white.
    const TempDir dir;
    SurfaceView view;
    view.title =
        "contour K = 5, eps = 5e-04, 15 passes: 32594 triangles, error 1.67e-02 at a "
        "sharp edge";
    save_surface_picture(sphere({0.0, 0.0, 0.0}, 1.0, 3), dir.path() / "a.png", view);
    const ImagePtr image = read_png(dir.path() / "a.png");
    bool dark = false, dark_in_margin = false;
    for (int y = 0; y < margin; ++y) {  // within the title's band, 48 pixels tall
        for (int x = 0; x < side; ++x) {
            const bool is_dark = pixel(image.get(), x, y).brightness() < 64;
            dark |= is_dark;
            dark_in_margin |= is_dark && (x < margin || x >= side - margin);
        }
    }
    EXPECT_TRUE(dark);
    EXPECT_FALSE(dark_in_margin);
}

TEST(SurfacePicture, WritesSvg) {
    const TempDir dir;
    SurfaceView view;
    view.title = "sphere";
    save_surface_picture(sphere({0.0, 0.0, 0.0}, 1.0, 2), dir.path() / "sphere.SVG", view);
    const std::string svg = slurp(dir.path() / "sphere.SVG");
    EXPECT_TRUE(svg.starts_with("<?xml") || svg.starts_with("<svg")) << svg.substr(0, 40);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(SurfacePicture, SameInputGivesTheSameBytes) {
    const TempDir dir;
    const std::vector<Surface> surfaces = {torus({0.0, 0.0, 0.0}, 1.0, 0.4, 48, 16), Surface{},
                                           sphere({0.0, 0.0, 0.5}, 0.5, 3)};
    save_surface_picture(surfaces, dir.path() / "a.png");
    save_surface_picture(surfaces, dir.path() / "b.png");
    const std::string a = slurp(dir.path() / "a.png");
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, slurp(dir.path() / "b.png"));
}

TEST(SurfacePicture, EdgesAreDrawnOnlyOnSurfacesOfAtMostTwentyThousandTriangles) {
    const TempDir dir;
    SurfaceView plain;
    plain.edges = false;
    auto differ = [&](const Surface& s) {
        save_surface_picture(s, dir.path() / "edges.png");
        save_surface_picture(s, dir.path() / "plain.png", plain);
        return slurp(dir.path() / "edges.png") != slurp(dir.path() / "plain.png");
    };
    EXPECT_TRUE(differ(sphere({0.0, 0.0, 0.0}, 1.0, 2)));   // 320 triangles
    EXPECT_FALSE(differ(sphere({0.0, 0.0, 0.0}, 1.0, 6)));  // 81920 triangles
}

TEST(SurfacePicture, NeighbouringFacesLeaveNoCrackBetweenThem) {
    // Antialiased triangles composited one over the other let the background show through at
    // every shared edge unless each face is drawn a little wider than itself. A crack is a pixel
    // paler than any face can be: faces are their colour, 0x4e79a7, times a brightness ≤ 1.
    const TempDir dir;
    SurfaceView plain = without_guides();
    plain.edges = false;
    save_surface_picture(sphere({0.0, 0.0, 0.0}, 0.5, 3), dir.path() / "sphere.png", plain);
    const ImagePtr image = read_png(dir.path() / "sphere.png");
    int radius = 0;  // of the sphere's disc, along the middle row
    while (!pixel(image.get(), side / 2 + radius, side / 2).is_background()) ++radius;
    ASSERT_GT(radius, side / 4);
    int cracks = 0, inside = 0;
    const int r = 9 * radius / 10;
    for (int y = side / 2 - r; y <= side / 2 + r; ++y) {
        for (int x = side / 2 - r; x <= side / 2 + r; ++x) {
            if ((x - side / 2) * (x - side / 2) + (y - side / 2) * (y - side / 2) > r * r) continue;
            const Rgb c = pixel(image.get(), x, y);
            ++inside;
            if (c.r > 0x4e + 1 || c.g > 0x79 + 1 || c.b > 0xa7 + 1) ++cracks;
        }
    }
    EXPECT_GT(inside, 50000);
    EXPECT_EQ(cracks, 0);
}

TEST(SurfacePicture, RejectsBadInputAndWritesNothing) {
    const TempDir dir;
    const Surface ball = sphere({0.0, 0.0, 0.0}, 1.0, 1);
    EXPECT_THROW(save_surface_picture(ball, dir.path() / "ball.jpg"), InvalidInput);
    EXPECT_THROW(save_surface_picture(ball, dir.path() / "ball"), InvalidInput);
    EXPECT_THROW(save_surface_picture(Surface{}, dir.path() / "empty.png"), InvalidInput);
    const std::vector<Surface> empties(2);
    EXPECT_THROW(save_surface_picture(empties, dir.path() / "empties.png"), InvalidInput);
    EXPECT_THROW(save_surface_picture(std::span<const Surface>{}, dir.path() / "none.png"),
                 InvalidInput);

    for (const auto& [w, h] : {std::pair{0, 800}, {800, -1}, {40000, 800}}) {
        SurfaceView view;
        view.width = w;
        view.height = h;
        EXPECT_THROW(save_surface_picture(ball, dir.path() / "size.png", view), InvalidInput);
    }
    SurfaceView tilted;
    tilted.elevation = NAN;
    EXPECT_THROW(save_surface_picture(ball, dir.path() / "nan.png", tilted), InvalidInput);

    Surface bad_index = ball;
    bad_index.triangles[3][1] = static_cast<std::uint32_t>(ball.vertices.size());
    EXPECT_THROW(save_surface_picture(bad_index, dir.path() / "index.png"), InvalidInput);
    Surface bad_vertex = ball;
    bad_vertex.vertices[0].z = INFINITY;
    EXPECT_THROW(save_surface_picture(bad_vertex, dir.path() / "vertex.png"), InvalidInput);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
}  // namespace slc
