// VTK XML PolyData (.vtp) and ParaView collections (.pvd), written as ASCII text by hand: the
// format is a handful of XML elements (VTK File Formats, "XML File Formats", PolyData and
// Collection), so a writer of its own spares the project the VTK library.
#include "slc/io/vtk.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <iterator>
#include <string_view>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {
namespace {

void check_time(double time) {
    if (!std::isfinite(time))
        throw InvalidInput(fmt::format("VTK frame time must be finite, got {}", time));
}

/// A DataArray element holding values, `components` to a tuple and a line. fmt's "{}" of a double
/// is the shortest text that reads back to the same double. VTK's reader needs NumberOfTuples in
/// field data, where no point or cell count implies it.
template <class T>
void append_array(std::string& out, const char* type, const char* name, int components,
                  const std::vector<T>& values) {
    const auto per_line = static_cast<std::size_t>(components == 1 ? 8 : components);
    fmt::format_to(std::back_inserter(out),
                   "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                   "NumberOfTuples=\"{}\" format=\"ascii\">",
                   type, name, components, values.size() / components);
    for (std::size_t i = 0; i < values.size(); ++i) {
        out += i % per_line == 0 ? "\n          " : " ";
        fmt::format_to(std::back_inserter(out), "{}", values[i]);
    }
    out += "\n        </DataArray>\n";
}

/// Points at z = 0, in the interface's order.
void append_points(std::string& out, const Interface& curves) {
    std::vector<double> xyz;
    xyz.reserve(3 * curves.size());
    for (const Vec2 p : curves.points()) xyz.insert(xyz.end(), {p.x, p.y, 0.0});
    out += "      <Points>\n";
    append_array(out, "Float64", "Points", 3, xyz);
    out += "      </Points>\n";
}

/// One closed polyline per curve: its vertices in order, then its first vertex again.
void append_lines(std::string& out, const Interface& curves) {
    std::vector<std::int64_t> connectivity;
    std::vector<std::int64_t> offsets;
    connectivity.reserve(curves.size() + curves.curve_count());
    for (std::size_t k = 0; k < curves.curve_count(); ++k) {
        const std::size_t first = curves.offsets()[k];
        for (std::size_t i = first; i < curves.offsets()[k + 1]; ++i)
            connectivity.push_back(static_cast<std::int64_t>(i));
        connectivity.push_back(static_cast<std::int64_t>(first));
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    out += "      <Lines>\n";
    append_array(out, "Int64", "connectivity", 1, connectivity);
    append_array(out, "Int64", "offsets", 1, offsets);
    out += "      </Lines>\n";
}

/// Point data "curve"; cell data "curve", "signed_area" and "length".
void append_data(std::string& out, const Interface& curves) {
    const std::size_t c = curves.curve_count();
    std::vector<std::int32_t> point_curve(curves.size());
    for (std::size_t i = 0; i < curves.size(); ++i)
        point_curve[i] = static_cast<std::int32_t>(curves.curve_of(i));
    std::vector<std::int32_t> cell_curve(c);
    std::vector<double> areas(c);
    std::vector<double> lengths(c, 0.0);
    for (std::size_t k = 0; k < c; ++k) {
        cell_curve[k] = static_cast<std::int32_t>(k);
        areas[k] = signed_area(curves.curve(k));
        for (std::size_t i = curves.offsets()[k]; i < curves.offsets()[k + 1]; ++i)
            lengths[k] += distance(curves.point(i), curves.point(curves.next(i)));
    }
    out += "      <PointData Scalars=\"curve\">\n";
    append_array(out, "Int32", "curve", 1, point_curve);
    out += "      </PointData>\n      <CellData Scalars=\"curve\">\n";
    append_array(out, "Int32", "curve", 1, cell_curve);
    append_array(out, "Float64", "signed_area", 1, areas);
    append_array(out, "Float64", "length", 1, lengths);
    out += "      </CellData>\n";
}

constexpr std::string_view pvd_tail = "  </Collection>\n</VTKFile>\n";

/// The opening of a PolyData file down to its one <Piece>: the time as field data, and the
/// numbers of points, lines and polygons of the piece.
void append_piece_head(std::string& out, double time, std::size_t points, std::size_t lines,
                       std::size_t polys) {
    out += "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    out += "  <PolyData>\n    <FieldData>\n";
    append_array(out, "Float64", "TimeValue", 1, std::vector<double>{time});
    out += "    </FieldData>\n";
    fmt::format_to(std::back_inserter(out),
                   "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"{}\">\n",
                   points, lines, polys);
}

/// The collection's line for one frame.
std::string dataset_line(const VtkFrame& f) {
    check_time(f.time);
    if (f.file.find_first_of("<>&\"") != std::string::npos)
        throw InvalidInput(
            fmt::format("VTK frame file name must not hold <, >, & or \", got {}", f.file));
    return fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", f.time,
                       f.file);
}

/// Replaces the closing lines of the collection at path, size bytes long, by text and those
/// lines, with one write at their place: a program stopped at any moment (short of the machine
/// failing) leaves the old collection or the new one. False, writing nothing, if the file is not
/// of that size or does not end in those lines (someone else changed it), or cannot be opened.
bool append_to_collection(const std::filesystem::path& path, std::size_t size,
                          const std::string& text) {
    if (size < pvd_tail.size()) return false;
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) return false;
    std::string ending(pvd_tail.size(), '\0');
    struct stat st {};
    const auto at = static_cast<off_t>(size - pvd_tail.size());
    bool ok =
        ::fstat(fd, &st) == 0 && static_cast<std::size_t>(st.st_size) == size &&
        ::pread(fd, ending.data(), ending.size(), at) == static_cast<ssize_t>(ending.size()) &&
        ending == pvd_tail;
    if (ok) {
        const std::string update = text + std::string(pvd_tail);
        ok = ::pwrite(fd, update.data(), update.size(), at) == static_cast<ssize_t>(update.size());
    }
    return ::close(fd) == 0 && ok;
}

}  // namespace

std::string vtp_text(const Interface& curves, double time) {
    check_time(time);
    std::string out;
    out.reserve(70 * curves.size() + 200 * curves.curve_count() + 1200);
    append_piece_head(out, time, curves.size(), curves.curve_count(), 0);
    append_points(out, curves);
    append_lines(out, curves);
    append_data(out, curves);
    out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
    return out;
}

std::string vtp_text(const Surface& surface, double time) {
    check_time(time);
    std::vector<double> xyz;
    xyz.reserve(3 * surface.vertices.size());
    for (const Vec3 p : surface.vertices) xyz.insert(xyz.end(), {p.x, p.y, p.z});
    std::vector<std::int64_t> connectivity, offsets;
    connectivity.reserve(3 * surface.size());
    for (const TriangleIndices& t : surface.triangles) {
        connectivity.insert(connectivity.end(), t.begin(), t.end());
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    std::vector<std::int32_t> component;
    for (const std::uint32_t c : component_labels(surface))
        component.push_back(static_cast<std::int32_t>(c));
    std::string out;
    out.reserve(90 * surface.vertices.size() + 1200);
    append_piece_head(out, time, surface.vertices.size(), 0, surface.size());
    out += "      <Points>\n";
    append_array(out, "Float64", "Points", 3, xyz);
    out += "      </Points>\n      <Polys>\n";
    append_array(out, "Int64", "connectivity", 1, connectivity);
    append_array(out, "Int64", "offsets", 1, offsets);
    out += "      </Polys>\n      <CellData Scalars=\"component\">\n";
    append_array(out, "Int32", "component", 1, component);
    out += "      </CellData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
    return out;
}

std::string pvd_text(std::span<const VtkFrame> frames) {
    std::string out;
    out += "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    out += "  <Collection>\n";
    for (const VtkFrame& f : frames) out += dataset_line(f);
    out += pvd_tail;
    return out;
}

VtkSeries::VtkSeries(std::filesystem::path pvd) : pvd_(std::move(pvd)) {
    if (!pvd_.has_filename() || !pvd_.has_stem())
        throw InvalidInput(
            fmt::format("VTK collection needs a file name, got '{}'", pvd_.string()));
}

void VtkSeries::write_frame(double time, const std::string& vtp) {
    const std::string name =
        fmt::format("{}/frame_{:04d}.vtp", pvd_.stem().string(), frames_.size());
    write_file_atomic(pvd_.parent_path() / name, vtp);
    frames_.push_back({time, name});
}

void VtkSeries::add_frame(double time, const std::string& vtp) {
    write_frame(time, vtp);
    const std::string line = dataset_line(frames_.back());
    if (pvd_size_ > 0 && append_to_collection(pvd_, pvd_size_, line)) {
        pvd_size_ += line.size();
        return;
    }
    write_collection();
}

void VtkSeries::add(double time, const Interface& curves) {
    add_frame(time, vtp_text(curves, time));
}

void VtkSeries::add(double time, const Surface& surface) {
    add_frame(time, vtp_text(surface, time));
}

void VtkSeries::add(std::span<const std::pair<double, Interface>> frames) {
    for (const auto& [time, curves] : frames) write_frame(time, vtp_text(curves, time));
    if (!frames.empty()) write_collection();
}

void VtkSeries::keep(std::span<const double> times) {
    for (const double time : times) {
        const std::string name =
            fmt::format("{}/frame_{:04d}.vtp", pvd_.stem().string(), frames_.size());
        if (!std::filesystem::exists(pvd_.parent_path() / name)) {
            throw InvalidInput(fmt::format("{}: missing, a frame of the run",
                                           (pvd_.parent_path() / name).string()));
        }
        frames_.push_back({time, name});
    }
    write_collection();
}

void VtkSeries::write_collection() {
    const std::string text = pvd_text(frames_);
    write_file_atomic(pvd_, text);
    pvd_size_ = text.size();
}

}  // namespace slc
