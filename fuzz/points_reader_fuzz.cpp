// libFuzzer target: the points file reader of `slc distance` (parse_points_csv) on arbitrary bytes.
// Bad input must end in InvalidInput; every point accepted must be finite.
#include <cstddef>
#include <cstdint>
#include <string>

#include "slc/core/error.hpp"
#include "slc/io/points_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        for (const slc::Vec2 p : slc::parse_points_csv(text, "fuzz.csv"))
            if (!slc::is_finite(p)) __builtin_trap();
    } catch (const slc::InvalidInput&) {
    }
    return 0;
}
