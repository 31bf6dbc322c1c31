// Output folders written as transactions: a command writes into a working folder beside --out DIR
// and swaps it into place when done (and, for runs with checkpoints, at each checkpoint), so that a
// reader of DIR sees the earlier results or the new ones, whole, never a mixture of both; a lock
// beside DIR refuses a second writer at once.
#pragma once

#include <filesystem>
#include <string>

namespace slc::cli {

/// The folder --out DIR of one command, from its start to its end.
///
/// DIR.lock (beside DIR) is held with flock for the lifetime of the object and removed at its
/// end; the working folder DIR.slc-work-PID (beside DIR, so that renames stay on one file system)
/// receives every file. publish() swaps a copy of it (hard links: every file of the tool is
/// written to a temporary file and renamed, never changed in place) into DIR with one
/// renameat2(RENAME_EXCHANGE); commit() swaps the working folder itself. A command that fails
/// before commit() leaves DIR as it was, and the destructor removes the working folder.
///
/// DIR may be missing, an empty folder, or a folder of results of slc (summary.json,
/// checkpoint.json, history.csv, final.json or table.json in it): the results are replaced
/// whole. Anything else (a file, a device, a folder of other files) is InvalidInput, as is a
/// DIR whose lock another process holds.
class OutputFolder {
public:
    /// Locks DIR and creates the working folder, empty, or with keep_results a copy of DIR's
    /// files (to continue a run). Also removes working folders a killed command left beside DIR.
    OutputFolder(const std::filesystem::path& dir, bool keep_results);
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    /// The working folder: write every file here.
    const std::filesystem::path& path() const { return work_; }
    /// DIR, as given.
    const std::filesystem::path& target() const { return dir_; }

    /// Makes the files written so far DIR's content, atomically; writing goes on in path().
    /// Cost: a hard link per file. Throws InvalidInput when DIR cannot be replaced.
    void publish();
    /// Makes the working folder DIR, atomically, and removes the earlier DIR. Call it once, last.
    void commit();

private:
    std::filesystem::path dir_;    ///< DIR as given (messages)
    std::filesystem::path final_;  ///< DIR, absolute
    std::filesystem::path work_;   ///< the working folder
    std::filesystem::path lock_;   ///< DIR.lock
    int lock_fd_ = -1;
    bool committed_ = false;
};

}  // namespace slc::cli
