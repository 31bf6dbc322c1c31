/// @file
/// Line plots of quantities against one variable (a run's area and length against time), drawn
/// with cairo as SVG or PNG (chosen by the file extension) in the style of render.hpp's Figure,
/// but with each axis scaled to its own data instead of the plane's square aspect.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slc/io/render.hpp"

namespace slc {

/// One graph: the polyline through (x[i], y[i]) in order (a dot when there is one point).
struct PlotSeries {
    std::vector<double> x;           ///< abscissae, as many as y, finite
    std::vector<double> y;           ///< ordinates, finite
    Color color = palette_color(0);  ///< of the line
    double line_width = 1.5;         ///< in layout pixels, > 0
};

/// A panel: one y axis, named y_name (turned to read along the axis), and its graphs.
struct PlotPanel {
    std::string y_name;              ///< the y axis's name
    std::vector<PlotSeries> series;  ///< its graphs
};

/// Panels stacked from top to bottom, sharing one x axis named x_name below the last, under a
/// title. The x axis spans the data exactly; each y axis the data of its panel with a margin of
/// 5%, widened to at least 0.1% of its largest magnitude so that a nearly constant quantity is
/// drawn flat with readable ticks.
struct LinePlot {
    std::string title;              ///< above the panels
    std::string x_name = "x";       ///< the x axis's name
    std::vector<PlotPanel> panels;  ///< top to bottom
};

/// Writes plot to path, atomically (write_file_atomic semantics); the extension (.svg or .png)
/// picks the format. Cost O(points). Throws InvalidInput for another extension, no panels, a
/// series whose x and y differ in size or hold a non-finite value, a line width not positive,
/// or a file that cannot be written (the message names it).
void save_plot(const LinePlot& plot, const std::filesystem::path& path);

}  // namespace slc
