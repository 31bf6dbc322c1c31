// An animated overview of a run: its frames shown one after another, in a loop, as one SVG file
// animated with SMIL (<animate>), which web browsers play without any plug-in or script.
#pragma once

#include <span>
#include <string>

#include "slc/core/box.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// One frame of an animation: the interface at a time.
struct AnimationFrame {
    double time = 0.0;  ///< shown as "t = ..." while the frame is on screen
    Interface curves;   ///< may be empty (everything vanished)
};

/// How animated_svg() draws and times the frames.
struct AnimationOptions {
    /// Seconds each frame stays on screen, > 0; the loop lasts frames × this.
    double seconds_per_frame = 0.25;
    /// Text above the picture; none when empty.
    std::string title;
    /// Draw every frame thinly beneath the current one, coloured from early (dark violet) to late
    /// (yellow) as sequence_color() does, so that the whole run stays in view.
    bool trail = true;
};

/// The text of an animated SVG showing frames in order, in a loop. The region view of the plane
/// (widened to a square about its centre) fills a 560 × 560 pixel plot with a frame around it;
/// each frame is one group (its curves as one path, filled by the even-odd rule so that holes show,
/// and its time) made visible in turn by a discrete SMIL animation of its visibility. Without
/// SMIL (an image converter, say) only the trail and the plot's frame show. Cost O(N) in the
/// total number N of vertices, about 15 bytes per vertex (30 with the trail).
/// Throws InvalidInput for no frames, an empty or non-finite view, a non-finite time, or
/// seconds_per_frame not positive and finite.
std::string animated_svg(std::span<const AnimationFrame> frames, const Box& view,
                         const AnimationOptions& options = {});

}  // namespace slc
