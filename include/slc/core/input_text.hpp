/// @file
/// Input files as text, for the modules that read them (interfaces, points and surfaces in io,
/// velocity lattices in velocity): a file's bytes, and its fields as a one-line message shows
/// them.
#pragma once

#include <fmt/format.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include "slc/core/error.hpp"

namespace slc {

/// InvalidInput "cannot read PATH: reason" for the error number err (an errno value).
inline InvalidInput cannot_read(const std::filesystem::path& path, int err) {
    return InvalidInput(
        fmt::format("cannot read {}: {}", path.string(), std::generic_category().message(err)));
}

/// The size in bytes of the regular file at path. Devices (/dev/zero never ends), pipes and
/// folders are refused before they are opened ("cannot read PATH: not a regular file"), and a
/// file whose state cannot be read throws cannot_read().
inline std::uintmax_t regular_file_size(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec) throw cannot_read(path, ec.value());
    if (!std::filesystem::is_regular_file(status)) {
        throw InvalidInput(fmt::format("cannot read {}: not a regular file", path.string()));
    }
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) throw cannot_read(path, ec.value());
    return size;
}

/// The bytes of the file at path, read to its end or until more than max_bytes have been read:
/// a result longer than max_bytes means a larger file, which the caller refuses. Throws
/// cannot_read() when the file cannot be opened or read. O(bytes read).
inline std::string file_bytes(
    const std::filesystem::path& path,
    std::uintmax_t max_bytes = std::numeric_limits<std::uintmax_t>::max()) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         &std::fclose);
    if (!file) throw cannot_read(path, errno);
    std::string text;
    char buffer[1 << 16];
    std::size_t n = 0;
    while (text.size() <= max_bytes && (n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0)
        text.append(buffer, n);
    if (text.size() > max_bytes) return text;
    if (std::ferror(file.get())) throw cannot_read(path, errno);
    return text;
}

/// s without the blanks (space, tab, CR, form feed, vertical tab) at either end.
inline std::string_view trim(std::string_view s) {
    constexpr std::string_view blanks = " \t\r\f\v";
    const std::size_t first = s.find_first_not_of(blanks);
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(blanks) - first + 1);
}

/// A field of an input file as a one-line message shows it, without quotes: control and
/// non-ASCII bytes as '?', at most 24 characters, then "..." when the field is longer.
inline std::string printable(std::string_view field) {
    constexpr std::size_t longest = 24;
    std::string out;
    for (const char c : field.substr(0, longest)) {
        const auto byte = static_cast<unsigned char>(c);
        out += byte >= 0x20 && byte < 0x7f ? c : '?';
    }
    if (field.size() > longest) out += "...";
    return out;
}

}  // namespace slc
