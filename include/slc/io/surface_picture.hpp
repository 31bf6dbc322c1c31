/// @file
/// Shaded pictures of closed triangle surfaces (the 3D counterpart of render.hpp's figures): an
/// orthographic view, back faces culled, triangles painted far to near with flat Lambert
/// shading, drawn with cairo as PNG or SVG (chosen by the file extension).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "slc/core/box3.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// The axis drawn upward in a picture.
enum class UpAxis { x, y, z };

/// How a surface is looked at: from the direction at `azimuth` about the up axis and `elevation`
/// above the plane normal to it, the up axis up in the picture (seen from straight above, the
/// picture's up is the horizontal direction away from the azimuth). With up z (the default) the
/// azimuth is from the +x axis in the xy plane; with up y, from +z in the zx plane; with up x,
/// from +y in the yz plane (the axes in cyclic order, so the view is never mirrored).
struct SurfaceView {
    double azimuth = 35.0;    ///< degrees about the up axis (see above)
    double elevation = 25.0;  ///< degrees above the plane normal to the up axis
    int width = 800;          ///< pixels (PNG); points (SVG)
    int height = 800;         ///< pixels (PNG); points (SVG)
    std::string title;        ///< drawn at the top when not empty
    bool edges = true;        ///< thin darker triangle edges on surfaces of at most 20000 triangles
    UpAxis up = UpAxis::z;    ///< the axis drawn upward
    /// An axis triad (x, y, z) at the bottom left and a scale bar (a length of 1, 2 or 5 × 10^n
    /// fitting a fifth of the width, labelled) at the bottom right, in a band below the surface.
    /// The view is orthographic, so the bar holds for lengths in the picture's plane.
    bool guides = true;
};

/// A quantity to colour a surface by: one value a vertex, each triangle painted in the colour of
/// the mean of its corners' values, shaded as usual; the diverging map (render.hpp's, blue for
/// negative, red for positive) over ±max|value|, with a colour bar labelled `label` in the band
/// below the surface.
struct SurfaceColoring {
    std::vector<double> values;  ///< one a vertex of the surface
    std::string label;           ///< what the values are, above the colour bar
};

/// The axis to draw upward for a surface with bounding box `box`, when the user names no view.
/// Only y and z are candidates: z is up in CAD and STL files and in slc's own shapes, y in the
/// OBJ files of scanners and Blender. When y's and z's extents are within 10%, z. Otherwise the
/// model is taken as standing when the longer of them is also over 10% longer than x and x is
/// not 10% shorter than the shorter of them (a figure, with its width x between its height and
/// its depth; a long ellipsoid), and the longer is up; else as lying (a torus, a plate; an animal,
/// x its narrowest width and the longer of y and z its length), and the shorter is up.
UpAxis up_axis(const Box3& box);

/// Draws closed, outward-oriented surfaces in one orthographic view fitted, within a margin, to
/// their joint bounding box: surface i in palette_color(i) (render.hpp), lit from near the viewer
/// (a little above and left of it) on a white background. Triangles are sorted by the depth of
/// their centroids (painter's algorithm), so where two surfaces cross or large triangles overlap
/// in depth the picture may be wrong by a triangle or so.
///
/// The extension of path (.png or .svg, any case) picks the format; the file is written
/// atomically (write_file_atomic semantics). The same input gives the same bytes.
/// Cost: O(N log N) for N triangles in all; a million triangles take a few seconds.
/// Throws InvalidInput for another extension, when every surface is empty, for a vertex index
/// out of range or a vertex that is not finite, for a size outside [1, 32767] or an angle that is
/// not finite, or when the file cannot be written.
void save_surface_picture(std::span<const Surface> surfaces, const std::filesystem::path& path,
                          const SurfaceView& view = {});

/// One surface, in palette colour 0; as above.
void save_surface_picture(const Surface& surface, const std::filesystem::path& path,
                          const SurfaceView& view = {});

/// Four views of the surfaces on one page of 2 × 2 pictures, each view.width × view.height: view
/// itself at the top left, then along the axes of its up frame, so that what one view hides
/// another shows: from the first and the second horizontal axis at elevation 0 (with up z, from
/// +x and from +y) and from straight above (+z). Each is fitted to the surfaces as
/// save_surface_picture fits one, with its own axis triad and scale bar, titled with the
/// direction it looks from (the first keeps view.title). As above otherwise; the page's sides
/// must stay within [1, 32767].
void save_surface_views(std::span<const Surface> surfaces, const std::filesystem::path& path,
                        const SurfaceView& view = {});

/// One surface coloured by a quantity (SurfaceColoring), with its colour bar; as above. Throws
/// InvalidInput, besides, when there is not one value a vertex or a value is not finite.
void save_surface_picture(const Surface& surface, const SurfaceColoring& coloring,
                          const std::filesystem::path& path, const SurfaceView& view = {});

}  // namespace slc
