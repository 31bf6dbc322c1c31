// The history of `slc run`: DIR/history.csv, one line per time level (the initial interface and
// the interface after every step) with its area, length, components, segments and the CPU seconds
// of the step that made it, and DIR/history.png, area and length against t, and the number of
// curves when it changed.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "slc/geometry/interface.hpp"

namespace slc::cli {

/// The time levels of a run, held in memory and written whole, atomically, when asked: at the
/// start, at each checkpoint and at the end: about 100 bytes per step in memory.
class History {
public:
    /// The header line of history.csv, without its newline.
    static constexpr const char* header = "t,area,length,components,segments,cpu_s";

    /// The history of the run writing to dir. Reads and writes nothing yet.
    explicit History(std::filesystem::path dir);

    /// DIR/history.csv.
    std::filesystem::path csv_path() const { return dir_ / "history.csv"; }

    /// Starts with the initial interface at time t (cpu_s 0). Call this or resume() first, once.
    void start(double t, const Interface& curves);
    /// Continues the history of a run resumed after steps_done steps at time t: reads
    /// `csv` (the history.csv of the folder resumed) back and keeps its first steps_done + 1 time
    /// levels, dropping any a run stopped after its last checkpoint wrote. Throws InvalidInput
    /// naming the file when it is missing, malformed, shorter than that, or not at time t after
    /// steps_done steps.
    void resume(int steps_done, double t, const std::filesystem::path& csv);
    /// Records the interface after a step that ended at time t and took cpu_s CPU seconds.
    void add(double t, const Interface& curves, double cpu_s);

    /// Writes DIR/history.csv, every time level so far, atomically. Cost O(levels).
    void save_csv() const;
    /// Draws area and length against t, and the number of curves when it changed, titled "NAME:
    /// area and length" (or "area, length and curves"), to DIR/history.png.
    void save_plot(const std::string& name) const;

private:
    void record(double t, double area, double length, double components, std::string_view line);

    std::filesystem::path dir_;
    std::string csv_;  ///< history.csv: the header and a line per time level
    std::vector<double> t_;
    std::vector<double> area_;
    std::vector<double> length_;
    std::vector<double> components_;
};

}  // namespace slc::cli
