/// @file
/// Point files for `slc distance`: one "x,y" per line, an optional header line "x,y"; in 3D
/// (DESIGN §8) one "x,y,z" per line, an optional header "x,y,z".
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slc/core/vec2.hpp"
#include "slc/core/vec3.hpp"

namespace slc {

/// Parses CSV text of points. Blank lines are skipped; a first line "x,y" is a header.
/// Throws InvalidInput naming the source and line: wrong number of columns, a non-number,
/// a non-finite value, a value beyond ±tolerance::max_coordinate.
std::vector<Vec2> parse_points_csv(const std::string& text, const std::string& source);

/// Reads and parses a points file; a missing file is InvalidInput.
std::vector<Vec2> read_points_csv(const std::filesystem::path& path);

/// parse_points_csv with three columns x,y,z (header "x,y,z").
std::vector<Vec3> parse_points3_csv(const std::string& text, const std::string& source);

/// Reads and parses a file of x,y,z points; a missing file is InvalidInput.
std::vector<Vec3> read_points3_csv(const std::filesystem::path& path);

}  // namespace slc
