/// @file
/// Shaded pictures of closed triangle surfaces (the 3D counterpart of render.hpp's figures): an
/// orthographic view, back faces culled, triangles painted far to near with flat Lambert
/// shading, drawn with cairo as PNG or SVG (chosen by the file extension).
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "slc/geometry/surface.hpp"

namespace slc {

/// How a surface is looked at: from the direction at `azimuth` about the z axis and `elevation`
/// above the xy plane, +z up in the picture (seen from straight above, the picture's up is the
/// horizontal direction away from the azimuth).
struct SurfaceView {
    double azimuth = 35.0;    ///< degrees about the z axis, from the +x axis
    double elevation = 25.0;  ///< degrees above the xy plane
    int width = 800;          ///< pixels (PNG); points (SVG)
    int height = 800;         ///< pixels (PNG); points (SVG)
    std::string title;        ///< drawn at the top when not empty
    bool edges = true;        ///< thin darker triangle edges on surfaces of at most 20000 triangles
};

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

}  // namespace slc
