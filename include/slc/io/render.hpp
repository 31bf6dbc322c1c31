/// @file
/// Pictures of interfaces, trees and fields in the style of the paper's figures, drawn with cairo
/// as SVG or PNG (chosen by the file extension).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "slc/core/box.hpp"
#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// An RGBA colour, components in [0, 1].
struct Color {
    double r = 0.0;  ///< red
    double g = 0.0;  ///< green
    double b = 0.0;  ///< blue
    double a = 1.0;  ///< opacity (alpha), 1 opaque
};

/// A qualitative palette for successive interfaces in one picture (legend order).
Color palette_color(std::size_t i);

/// A colour for the member at t ∈ [0, 1] of an ordered sequence (frames in time): dark violet at
/// 0 through blue and green to a dark yellow at 1.
Color sequence_color(double t);

/// Scalar samples on a uniform nx × ny grid of cell centres covering box, row-major from the
/// bottom-left (values[j * nx + i] at x = lo.x + (i + ½) w / nx, y = lo.y + (j + ½) h / ny).
struct ScalarGrid {
    Box box;                     ///< the region covered
    int nx = 0;                  ///< samples per row
    int ny = 0;                  ///< rows
    std::vector<double> values;  ///< nx · ny samples, row-major from the bottom-left
};

/// A picture: axes with ticks around the view box, layers drawn in the order added, a legend of
/// the labelled layers (the first 40, then a row "… and n more"), an optional colour bar for a
/// field or values on curves (the last added), and a title.
class Figure {
public:
    /// view: the region of the plane shown (kept square-aspect). Throws InvalidInput if empty.
    explicit Figure(Box view, std::string title = {});

    /// A scalar field as a colour image, with a colour bar labelled `label`. diverging: a
    /// blue–white–red map symmetric about 0 (for signed distance); else a sequential map.
    void add_field(const ScalarGrid& field, const std::string& label, bool diverging);
    /// Outlines of boxes (quadtree cells), thin lines.
    void add_boxes(std::span<const Box> boxes, Color color, double line_width = 0.4);
    /// Edges of triangles given by vertex indices.
    void add_triangles(std::span<const Vec2> vertices,
                       std::span<const std::array<std::uint32_t, 3>> triangles, Color color,
                       double line_width = 0.3);
    /// Every curve of an interface, closed, with a legend entry `label` (none if empty).
    void add_curves(const Interface& curves, const std::string& label, Color color,
                    double line_width = 1.5);
    /// An open polyline through points (a graph), with a legend entry `label` (none if empty).
    void add_polyline(std::span<const Vec2> points, const std::string& label, Color color,
                      double line_width = 1.5);
    /// Every curve of an interface, closed, each segment coloured by the mean of its ends'
    /// values (one per vertex, in the interface's order) on the map of add_field, with a colour
    /// bar labelled `label`.
    void add_curve_values(const Interface& curves, std::span<const double> values,
                          const std::string& label, bool diverging = false,
                          double line_width = 3.0);
    /// Dots at points (for instance the vertices of a curve).
    void add_points(std::span<const Vec2> points, Color color, double radius = 1.5);
    /// Arrows from at[i] along vec[i] * scale (plane units).
    void add_arrows(std::span<const Vec2> at, std::span<const Vec2> vec, double scale, Color color);

    /// Names the axes (default "x" and "y"); a y name longer than one character is turned to
    /// read along the axis.
    void set_axis_names(std::string x, std::string y) {
        x_name_ = std::move(x);
        y_name_ = std::move(y);
    }

    /// Writes the picture; the extension (.svg or .png) picks the format, else InvalidInput.
    /// Written atomically (write_file_atomic semantics).
    void save(const std::filesystem::path& path) const;

    /// Writes the figures as one picture of panels, `columns` to a row (the last row may be
    /// short), each with its own title, axes and legend, in cells of the largest one's size.
    /// The extension (.svg or .png) picks the format, else InvalidInput; a PNG is drawn at
    /// most 2400 pixels wide. Throws InvalidInput if there are no figures or columns < 1.
    static void save_grid(std::span<const Figure> figures, int columns,
                          const std::filesystem::path& path);

private:
    struct Layer;
    Box view_;
    std::string title_;
    std::string x_name_ = "x";
    std::string y_name_ = "y";
    std::vector<std::shared_ptr<Layer>> layers_;
};

}  // namespace slc
