// Bytes of surface files in binary forms, for the readers' tests: numbers in either byte order
// and a binary STL of a surface.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <type_traits>

#include "slc/geometry/surface.hpp"

namespace slc::test {

/// Bytes of x in the given byte order.
template <class T>
std::string bytes_of(T x, bool little) {
    auto u = std::bit_cast<
        std::conditional_t<sizeof(T) == 8, std::uint64_t,
                           std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint8_t>>>(x);
    std::string out(sizeof(T), '\0');
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const auto byte = static_cast<char>((u >> (8 * i)) & 0xff);
        out[little ? i : sizeof(T) - 1 - i] = byte;
    }
    return out;
}

/// A binary STL of a surface's triangles (coordinates must be exact in float).
inline std::string binary_stl(const Surface& s, const std::string& header) {
    std::string out = header;
    out.resize(80, ' ');
    auto put32 = [&](std::uint32_t u) {
        for (int i = 0; i < 4; ++i) out += static_cast<char>((u >> (8 * i)) & 0xff);
    };
    put32(static_cast<std::uint32_t>(s.size()));
    for (std::size_t t = 0; t < s.size(); ++t) {
        for (int i = 0; i < 3; ++i) put32(0);  // the normal, ignored
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = s.triangle(t)[k];
            for (double c : {p.x, p.y, p.z})
                put32(std::bit_cast<std::uint32_t>(static_cast<float>(c)));
        }
        out += std::string(2, '\0');
    }
    return out;
}

}  // namespace slc::test
