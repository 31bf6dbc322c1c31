// libFuzzer target: the surface file readers (parse_obj, parse_stl, parse_ply) on arbitrary
// bytes, the first byte choosing the format, and validation of whatever they accept. Bad input
// must end in InvalidInput; every vertex index accepted must be in range.
#include <cstddef>
#include <cstdint>
#include <string>

#include "slc/core/error.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/surface_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        slc::Surface s;
        switch (data[0] % 3) {
            case 0:
                s = slc::parse_obj(bytes, "fuzz.obj");
                break;
            case 1:
                s = slc::parse_stl(bytes, "fuzz.stl");
                break;
            default:
                s = slc::parse_ply(bytes, "fuzz.ply");
                break;
        }
        for (const slc::TriangleIndices& t : s.triangles)
            for (const std::uint32_t v : t)
                if (v >= s.vertices.size()) __builtin_trap();
        if (s.size() <= 2000) slc::prepare_surface(s);
    } catch (const slc::InvalidInput&) {
    }
    return 0;
}
