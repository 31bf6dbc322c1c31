// One input of the surface readers' fuzzing, shared by the mutation test under the sanitizers
// (tests/unit/io/surface_readers_fuzz_test.cpp) and the libFuzzer target (tests/fuzz/).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

#include "slc/core/error.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/surface_files.hpp"

namespace slc::fuzz {

/// Surfaces larger than this are read but not validated, so that one input stays fast.
inline constexpr std::size_t largest_validated = 4096;

/// Feeds bytes to every surface reader, and what one accepts to prepare_surface. The contract:
/// a reader returns a surface whose indices are in range, or throws InvalidInput (one line);
/// prepare_surface returns a closed surface of finite coordinates, or throws InvalidInput.
/// Anything else (another exception, a crash, a sanitizer report, an index out of range) is a
/// defect: throws std::logic_error naming it, or dies.
inline void read_surface_bytes(std::string_view bytes) {
    using Parser = Surface (*)(std::string_view, const std::string&);
    const Parser parsers[] = {&parse_obj, &parse_stl, &parse_ply};
    const char* names[] = {"obj", "stl", "ply"};
    for (int p = 0; p < 3; ++p) {
        Surface s;
        try {
            s = parsers[p](bytes, "fuzz");
        } catch (const InvalidInput& e) {
            if (std::string_view(e.what()).find('\n') != std::string_view::npos)
                throw std::logic_error(std::string(names[p]) + ": a message of several lines");
            continue;
        }
        for (const TriangleIndices& t : s.triangles)
            for (const auto i : t)
                if (i >= s.vertices.size())
                    throw std::logic_error(std::string(names[p]) + ": an index out of range");
        if (s.size() > largest_validated) continue;
        try {
            const PreparedSurface prepared = prepare_surface(s);
            for (const Vec3& v : prepared.surface.vertices)
                if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
                    throw std::logic_error(std::string(names[p]) + ": a non-finite vertex kept");
        } catch (const InvalidInput&) {
        }
    }
}

}  // namespace slc::fuzz
