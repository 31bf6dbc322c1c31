// libFuzzer target: the surface file readers (parse_obj, parse_stl, parse_ply) on arbitrary
// bytes, and validation of whatever they accept; the check is slc::fuzz::read_surface_bytes
// (tests/support/surface_reader_fuzz.hpp), which the mutation test of the unit tests also runs.
#include "surface_reader_fuzz.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Any exception but InvalidInput escapes, and libFuzzer reports it with its input.
    slc::fuzz::read_surface_bytes({reinterpret_cast<const char*>(data), size});
    return 0;
}
