// libFuzzer target: the interface file reader (parse_interface_json) and validation
// (prepare_interface) on arbitrary bytes. Bad input must end in InvalidInput, nothing else: any
// other exception, a crash or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "slc/core/error.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/io/interface_json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const slc::InterfaceFile file = slc::parse_interface_json(text, "fuzz.json");
        const slc::PreparedInterface prepared = slc::prepare_interface(file.curves);
        // What was accepted writes and reads back to the same points.
        const std::string written = slc::interface_json(prepared.curves, file.time);
        const slc::InterfaceFile again = slc::parse_interface_json(written, "written.json");
        if (again.curves != prepared.curves.curves() || again.time != file.time) __builtin_trap();
    } catch (const slc::InvalidInput&) {
    }
    return 0;
}
