// VTK output for ParaView and other VTK readers: an interface as VTK XML PolyData (.vtp, ASCII)
// and a time series of them as a ParaView collection (.pvd), which ParaView opens as an animation.
// The project's own small writer: no VTK library is needed to write these files.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "slc/geometry/interface.hpp"
#include "slc/geometry/surface.hpp"

namespace slc {

/// The text of a VTK XML PolyData file (.vtp, format version 0.1, ASCII) holding curves at time.
///
/// Points: one per vertex, in the interface's order, z = 0, each coordinate in the shortest
/// decimal form that reads back to the same double. Lines: one closed polyline cell per curve,
/// its vertex indices in order followed by its first vertex again. Point data "curve" (Int32, the
/// index of the vertex's curve); cell data "curve", "signed_area" (positive counterclockwise,
/// negative for a hole) and "length" of each curve; field data "TimeValue" = time, which ParaView
/// shows as the time of a single file. An empty interface gives a valid file with no points.
/// Cost O(N) for N vertices, about 65 bytes per vertex. Throws InvalidInput for a non-finite time.
std::string vtp_text(const Interface& curves, double time);

/// The text of a VTK XML PolyData file (.vtp, ASCII) holding a triangle surface at time (DESIGN
/// §8): its vertices as points (shortest round-trip decimals), its triangles as polygon cells
/// (vertex indices in their orientation), cell data "component" (Int32) and field data
/// "TimeValue". Cost O(N), about 90 bytes per vertex. Throws InvalidInput for a non-finite time.
std::string vtp_text(const Surface& surface, double time);

/// One dataset of a ParaView collection: its time and its file, relative to the .pvd file.
struct VtkFrame {
    double time = 0.0;  ///< the dataset's time (the "timestep" attribute)
    std::string file;   ///< path relative to the folder of the .pvd file, '/'-separated
};

/// The text of a ParaView collection file (.pvd) listing frames in the order given. Throws
/// InvalidInput for a non-finite time or a file name holding a character XML must escape
/// ('<', '>', '&', '"').
std::string pvd_text(std::span<const VtkFrame> frames);

/// A time series written frame by frame: DIR/NAME.pvd and its frames DIR/NAME/frame_0000.vtp,
/// frame_0001.vtp, ... (NAME the stem of the .pvd path). Each add() writes its frame atomically
/// (write_file_atomic) and then lists it in the collection: the first time by writing the
/// collection atomically, after that by one write that replaces the collection's closing lines
/// with the frame's line and those lines. So the collection on disk always lists complete frames
/// only, even when the writing program is stopped midway, and a series of F frames costs O(F),
/// not O(F²). If the collection on disk is not the one this series last wrote, it is written
/// whole again.
class VtkSeries {
public:
    /// A series whose collection file is pvd (its extension should be .pvd). Writes nothing yet.
    /// Throws InvalidInput if pvd has no file name.
    explicit VtkSeries(std::filesystem::path pvd);

    /// Writes curves at time as the next frame and lists it in the collection. Cost O(N) for N
    /// vertices (O(F) for F frames so far only when the collection must be written whole).
    /// Throws InvalidInput for a non-finite time or when a file cannot be written (the message
    /// names it).
    void add(double time, const Interface& curves);
    /// Writes a surface at time as the next frame and lists it in the collection; as above.
    void add(double time, const Surface& surface);
    /// Lists the frames an earlier run wrote (DIR/NAME/frame_0000.vtp, ... at the given times,
    /// kept in the folder) as this series' first ones and writes the collection whole, so that
    /// a resumed run goes on after them. Throws InvalidInput naming a frame file that is
    /// missing, or as add() does.
    void keep(std::span<const double> times);
    /// Writes each (time, curves) as the next frame, then the collection once: O(total N + F).
    /// Throws as add() does.
    void add(std::span<const std::pair<double, Interface>> frames);

    /// The frames written so far, in order, their files relative to the collection's folder.
    std::span<const VtkFrame> frames() const { return frames_; }
    /// The collection file.
    const std::filesystem::path& pvd() const { return pvd_; }

private:
    /// Writes the next frame's .vtp text and records it; the collection is not rewritten.
    void write_frame(double time, const std::string& vtp);
    /// write_frame, then lists the frame in the collection.
    void add_frame(double time, const std::string& vtp);
    /// Writes the whole collection atomically.
    void write_collection();

    std::filesystem::path pvd_;
    std::vector<VtkFrame> frames_;
    std::size_t pvd_size_ = 0;  ///< bytes of the collection as this series last wrote it
};

}  // namespace slc
