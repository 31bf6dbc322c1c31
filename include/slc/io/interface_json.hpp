/// @file
/// Interface files (DESIGN §6): {"time": 0.0, "curves": [{"points": [[x, y], ...]}, ...]}.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/geometry/interface.hpp"

namespace slc {

/// The content of an interface file before validation (see prepare_interface).
struct InterfaceFile {
    double time = 0.0;                      ///< "time", 0 when absent
    std::vector<std::vector<Vec2>> curves;  ///< "curves"[c]."points", as read
};

/// Most points an interface file may hold, all curves together: reading one takes about 1 GB of
/// memory per million points, so larger files are refused before they are read into memory.
inline constexpr std::size_t max_interface_points = 2'000'000;

/// Most JSON values (numbers, arrays, objects, strings, ...) an interface file may hold: three
/// per point and room for the rest, so that a file padded with other values is refused while it
/// is counted, before its document is built.
inline constexpr std::size_t max_interface_values = 4 * max_interface_points;

/// Largest input file the tool reads (interfaces, points, surfaces, velocity lattices): 128 MiB.
/// An interface of max_interface_points points as slc writes it takes about 110 MB.
inline constexpr std::uintmax_t max_input_bytes = std::uintmax_t{128} << 20;

/// Parses interface JSON text. `source` names the input in messages (a file name).
/// Throws InvalidInput, one line naming the source and what is wrong: not JSON, no "curves"
/// array, a curve without "points", a point that is not two numbers, a non-finite "time", more
/// than max_interface_points points or max_interface_values values.
InterfaceFile parse_interface_json(const std::string& text, const std::string& source);

/// Reads and parses an interface file; a missing or unreadable file is InvalidInput too.
InterfaceFile read_interface_json(const std::filesystem::path& path);

/// The interface as JSON text, coordinates with 17 significant digits (round-trips exactly).
std::string interface_json(const Interface& curves, double time);

/// The whole content of a file; InvalidInput ("cannot read PATH: reason") when it cannot be read,
/// is not a regular file (a device such as /dev/zero, a pipe, a folder), or holds more than
/// max_input_bytes (checked before it is read, and again while reading).
std::string read_text_file(const std::filesystem::path& path);

/// Writes text to path atomically: to a temporary file in the same folder, then renamed over
/// path, so that a reader never sees a partial file. Creates missing parent folders. Throws
/// InvalidInput when the folder cannot be written.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);

/// The same for a file that write(temp) writes at the temporary path it is given (another
/// library's writer): an exception from it (its what() the reason) removes the temporary and
/// becomes InvalidInput ("cannot write PATH: reason"), leaving any earlier file at path whole.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path&)>& write);

}  // namespace slc
