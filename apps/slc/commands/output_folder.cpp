// Output folders as transactions: the lock beside DIR, the working folder, and the atomic swap
// (renameat2 with RENAME_EXCHANGE) that puts it in DIR's place.
#include "commands/output_folder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <system_error>

#include "slc/core/error.hpp"

namespace slc::cli {
namespace {

namespace fs = std::filesystem;

/// Files whose presence marks a folder as results of slc (run, contour, study), which a new
/// command may replace; a folder without any of them is not replaced.
constexpr std::array<const char*, 6> result_files = {
    "summary.json", "checkpoint.json", "history.csv", "final.json", "table.json", "table.md"};

InvalidInput cannot(const std::string& what, const fs::path& path, int err) {
    return InvalidInput(
        fmt::format("cannot {} {}: {}", what, path.string(), std::generic_category().message(err)));
}

/// Copies the tree at from to to (which must not exist) with a hard link per file, or a copy
/// where the file system has no hard links.
void link_tree(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::create_directory(to, ec);
    if (ec) throw cannot("create", to, ec.value());
    for (auto it = fs::recursive_directory_iterator(from, ec); !ec && it != fs::end(it);
         it.increment(ec)) {
        const fs::path target = to / fs::relative(it->path(), from);
        if (it->is_directory()) {
            fs::create_directory(target, ec);
        } else {
            fs::create_hard_link(it->path(), target, ec);
            if (ec) fs::copy_file(it->path(), target, ec);
        }
        if (ec) break;
    }
    if (ec) throw cannot("copy the results into", to, ec.value());
}

/// Puts the folder `from` at `to` in one step: exchanged with the folder at `to` when there is
/// one (which then lies at `from`), else renamed.
void swap_into_place(const fs::path& from, const fs::path& to) {
    if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_EXCHANGE) == 0) return;
    const int err = errno;
    if (err == ENOENT && !fs::exists(to)) {
        if (std::rename(from.c_str(), to.c_str()) == 0) return;
        throw cannot("write", to, errno);
    }
    if (err != EINVAL && err != ENOSYS) throw cannot("replace", to, err);
    // A file system without RENAME_EXCHANGE: two renames, DIR briefly missing (never mixed).
    fs::path old = from;
    old += ".old";
    if (std::rename(to.c_str(), old.c_str()) != 0) throw cannot("replace", to, errno);
    if (std::rename(from.c_str(), to.c_str()) != 0) {
        const int e = errno;
        std::rename(old.c_str(), to.c_str());
        throw cannot("replace", to, e);
    }
    std::rename(old.c_str(), from.c_str());
}

/// DIR checked: missing, or a folder that is empty or holds results of slc.
void check_target(const fs::path& dir, const fs::path& given) {
    std::error_code ec;
    const fs::file_status s = fs::symlink_status(dir, ec);
    if (!fs::exists(s)) return;
    if (!fs::is_directory(s)) {
        throw InvalidInput(fmt::format("--out {}: {} exists and is not a folder", given.string(),
                                       fs::is_regular_file(s) ? "a file" : "it"));
    }
    bool empty = true;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        (void)entry;
        empty = false;
        break;
    }
    if (ec) throw cannot("read", given, ec.value());
    if (empty) return;
    for (const char* name : result_files)
        if (fs::exists(dir / name, ec)) return;
    throw InvalidInput(
        fmt::format("--out {}: the folder holds files that are not results of slc, which would "
                    "be replaced; give a new or empty folder",
                    given.string()));
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& dir, bool keep_results) : dir_(dir) {
    std::error_code ec;
    final_ = fs::absolute(dir, ec).lexically_normal();
    if (final_.has_parent_path() && final_.filename().empty()) final_ = final_.parent_path();
    if (ec || final_ == final_.root_path()) {
        throw InvalidInput(fmt::format("--out {}: not a folder slc can replace", dir.string()));
    }
    const fs::path parent = final_.parent_path();
    fs::create_directories(parent, ec);
    if (ec) throw cannot("create", parent, ec.value());

    // DIR.lock: flock refuses a second writer at once. A lock file removed by the writer before
    // it let go is retried, so that two writers never lock two different files of one name.
    lock_ = final_;
    lock_ += ".lock";
    while (true) {
        lock_fd_ = ::open(lock_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (lock_fd_ < 0) {
            // The lock is slc's own: a user needs the folder named, and why it cannot be
            // written there.
            const int err = errno;
            throw InvalidInput(fmt::format("--out {}: cannot write in {}: {}", dir.string(),
                                           parent.string(), std::generic_category().message(err)));
        }
        if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            ::close(lock_fd_);
            lock_fd_ = -1;
            if (err == EWOULDBLOCK) {
                throw InvalidInput(fmt::format(
                    "--out {}: another slc is writing this folder ({} is locked); wait for it "
                    "or choose another folder",
                    dir.string(), lock_.string()));
            }
            throw cannot("lock", lock_, err);
        }
        struct stat held {};
        struct stat named {};
        if (::fstat(lock_fd_, &held) == 0 && ::stat(lock_.c_str(), &named) == 0 &&
            held.st_ino == named.st_ino && held.st_dev == named.st_dev) {
            break;
        }
        ::close(lock_fd_);
        lock_fd_ = -1;
    }
    try {
        check_target(final_, dir);
        // Working folders of a command that was killed: nobody else writes them while we hold
        // the lock.
        const std::string stale = final_.filename().string() + ".slc-";
        for (const auto& entry : fs::directory_iterator(parent, ec)) {
            if (entry.path().filename().string().starts_with(stale)) fs::remove_all(entry, ec);
        }
        work_ = final_;
        work_ += fmt::format(".slc-work-{}", static_cast<long>(::getpid()));
        if (keep_results && fs::is_directory(final_)) {
            link_tree(final_, work_);
        } else {
            fs::create_directory(work_, ec);
            if (ec) throw cannot("create", work_, ec.value());
        }
    } catch (...) {
        ::unlink(lock_.c_str());
        ::close(lock_fd_);
        throw;
    }
}

OutputFolder::~OutputFolder() {
    std::error_code ec;
    if (!committed_ && !work_.empty()) fs::remove_all(work_, ec);
    ::unlink(lock_.c_str());
    ::close(lock_fd_);
}

void OutputFolder::publish() {
    fs::path snapshot = final_;
    snapshot += fmt::format(".slc-new-{}", static_cast<long>(::getpid()));
    std::error_code ec;
    fs::remove_all(snapshot, ec);
    link_tree(work_, snapshot);
    swap_into_place(snapshot, final_);
    fs::remove_all(snapshot, ec);  // the earlier DIR, when there was one
}

void OutputFolder::commit() {
    swap_into_place(work_, final_);
    committed_ = true;
    std::error_code ec;
    fs::remove_all(work_, ec);  // the earlier DIR, when there was one
}

}  // namespace slc::cli
