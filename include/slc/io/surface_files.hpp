/// @file
/// Surface files (DESIGN §8): Wavefront OBJ, STL (ASCII and binary) and PLY (ASCII and binary,
/// either byte order) read; OBJ written (the interchange format), VTK PolyData in vtk.hpp.
/// Readers check the file's own structure (syntax, counts, indices in range) and name the line or
/// record at fault; whether the triangles make a valid surface is prepare_surface's question.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "slc/geometry/surface.hpp"

namespace slc {

/// True when path names a surface file by its extension (.obj, .stl, .ply, .vdb, any case): the
/// tool then works in 3D.
bool is_surface_file(const std::filesystem::path& path);

/// Parses OBJ text: `v x y z` (a fourth number, or colours, ignored), `f a b c ...` with 1-based
/// or negative (relative) indices in the forms `i`, `i/t`, `i//n`, `i/t/n`; polygons are fanned
/// from their first corner; comments (`#`) and other statements (vt, vn, o, g, s, usemtl, ...)
/// ignored. Throws InvalidInput naming source and line: a bad number, an index 0 or out of range,
/// a face of fewer than 3 corners; or no faces at all.
Surface parse_obj(std::string_view text, const std::string& source);

/// Parses STL, binary (80-byte header, count, 50 bytes per triangle, little-endian floats: told
/// by its size, even if the header begins with "solid") or ASCII (`solid`, `facet normal`, `outer
/// loop`, `vertex x y z` ×3, `endloop`, `endfacet`, `endsolid`). STL repeats each corner in every
/// triangle: vertices with exactly equal coordinates become one (−0 and +0 alike). Throws
/// InvalidInput naming source and line (or byte size for binary) at fault.
Surface parse_stl(std::string_view bytes, const std::string& source);

/// Parses PLY (ascii, binary_little_endian or binary_big_endian 1.0): element `vertex` with
/// scalar properties x, y, z (any numeric type; others skipped) and element `face` with a list
/// property vertex_indices (or vertex_index), polygons fanned; other elements and properties
/// skipped. Throws InvalidInput naming source and the header line or element at fault.
Surface parse_ply(std::string_view bytes, const std::string& source);

/// Reads a surface file, chosen by extension (is_surface_file); a .vdb file is an OpenVDB level
/// set, contoured by read_vdb_level_set (vdb.hpp). A missing file, an unknown extension or bad
/// content is InvalidInput naming the file.
Surface read_surface(const std::filesystem::path& path);

/// OBJ text of a surface: `v` lines (shortest round-trip decimals), then `f` lines (1-based).
std::string obj_text(const Surface& surface);

}  // namespace slc
