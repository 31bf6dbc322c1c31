// Test helpers for files: a fresh temporary folder per test, removed afterwards, and a file's
// bytes as a string.
#pragma once

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace slc::test_support {

/// A new empty folder under the system's temporary folder, named after `prefix`, the process and
/// a counter; removed with everything in it (even what a test made read-only) when destroyed.
class TempDir {
public:
    explicit TempDir(const std::string& prefix = "slc_test") {
        static int counter = 0;
        path_ = std::filesystem::temp_directory_path() /
                fmt::format("{}_{}_{}", prefix, ::getpid(), counter++);
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                     std::filesystem::perm_options::add, ec);
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    /// The folder.
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

/// The whole file at path, bytes as they are (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace slc::test_support
