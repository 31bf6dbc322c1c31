// VTK XML PolyData (.vtp) and ParaView collections (.pvd), written as ASCII text by hand: the
// format is a handful of XML elements (VTK File Formats, "XML File Formats", PolyData and
// Collection), so a writer of its own spares the project the VTK library.
#include "slc/io/vtk.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "slc/core/error.hpp"
#include "slc/io/interface_json.hpp"

namespace slc {
namespace {

void check_time(double time) {
    if (!std::isfinite(time))
        throw InvalidInput(fmt::format("VTK frame time must be finite, got {}", time));
}

/// Opens a DataArray element; the values follow on the next lines. VTK's reader needs
/// NumberOfTuples in field data, where no point or cell count implies it.
void open_array(std::string& out, const char* type, const char* name, int components,
                std::size_t tuples) {
    fmt::format_to(std::back_inserter(out),
                   "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                   "NumberOfTuples=\"{}\" format=\"ascii\">\n",
                   type, name, components, tuples);
}

void close_array(std::string& out) { out += "\n        </DataArray>\n"; }

/// Values separated by spaces, `per_line` to a line. fmt's "{}" of a double is the shortest text
/// that reads back to the same double.
template <class Range>
void append_values(std::string& out, const Range& values, std::size_t per_line) {
    std::size_t n = 0;
    for (const auto& v : values) {
        if (n > 0) out += n % per_line == 0 ? "\n" : " ";
        if (n % per_line == 0) out += "          ";
        fmt::format_to(std::back_inserter(out), "{}", v);
        ++n;
    }
}

}  // namespace

std::string vtp_text(const Interface& curves, double time) {
    check_time(time);
    const std::size_t n = curves.size();
    const std::size_t c = curves.curve_count();
    std::string out;
    out.reserve(200 * c + 70 * n + 1200);
    out += "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    out += "  <PolyData>\n";
    out += "    <FieldData>\n";
    open_array(out, "Float64", "TimeValue", 1, 1);
    fmt::format_to(std::back_inserter(out), "          {}", time);
    close_array(out);
    out += "    </FieldData>\n";
    fmt::format_to(std::back_inserter(out),
                   "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                   "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                   n, c);

    out += "      <Points>\n";
    open_array(out, "Float64", "Points", 3, n);
    std::vector<double> xyz;
    xyz.reserve(3 * n);
    for (const Vec2 p : curves.points()) xyz.insert(xyz.end(), {p.x, p.y, 0.0});
    append_values(out, xyz, 3);
    close_array(out);
    out += "      </Points>\n";

    out += "      <Lines>\n";
    std::vector<std::size_t> connectivity;
    std::vector<std::size_t> offsets;
    connectivity.reserve(n + c);
    for (std::size_t k = 0; k < c; ++k) {
        const std::size_t first = curves.offsets()[k];
        for (std::size_t i = first; i < curves.offsets()[k + 1]; ++i) connectivity.push_back(i);
        connectivity.push_back(first);  // closes the polyline
        offsets.push_back(connectivity.size());
    }
    open_array(out, "Int64", "connectivity", 1, connectivity.size());
    append_values(out, connectivity, 12);
    close_array(out);
    open_array(out, "Int64", "offsets", 1, offsets.size());
    append_values(out, offsets, 12);
    close_array(out);
    out += "      </Lines>\n";

    out += "      <PointData Scalars=\"curve\">\n";
    std::vector<int> point_curve(n);
    for (std::size_t i = 0; i < n; ++i) point_curve[i] = static_cast<int>(curves.curve_of(i));
    open_array(out, "Int32", "curve", 1, n);
    append_values(out, point_curve, 12);
    close_array(out);
    out += "      </PointData>\n";

    out += "      <CellData Scalars=\"curve\">\n";
    std::vector<int> cell_curve(c);
    std::vector<double> areas(c);
    std::vector<double> lengths(c);
    for (std::size_t k = 0; k < c; ++k) {
        cell_curve[k] = static_cast<int>(k);
        areas[k] = signed_area(curves.curve(k));
        for (std::size_t i = curves.offsets()[k]; i < curves.offsets()[k + 1]; ++i)
            lengths[k] += distance(curves.point(i), curves.point(curves.next(i)));
    }
    open_array(out, "Int32", "curve", 1, c);
    append_values(out, cell_curve, 12);
    close_array(out);
    open_array(out, "Float64", "signed_area", 1, c);
    append_values(out, areas, 4);
    close_array(out);
    open_array(out, "Float64", "length", 1, c);
    append_values(out, lengths, 4);
    close_array(out);
    out += "      </CellData>\n";

    out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
    return out;
}

std::string pvd_text(std::span<const VtkFrame> frames) {
    std::string out;
    out += "<?xml version=\"1.0\"?>\n";
    out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    out += "  <Collection>\n";
    for (const VtkFrame& f : frames) {
        check_time(f.time);
        if (f.file.find_first_of("<>&\"") != std::string::npos)
            throw InvalidInput(
                fmt::format("VTK frame file name must not hold <, >, & or \", got {}", f.file));
        fmt::format_to(std::back_inserter(out),
                       "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", f.time,
                       f.file);
    }
    out += "  </Collection>\n</VTKFile>\n";
    return out;
}

VtkSeries::VtkSeries(std::filesystem::path pvd) : pvd_(std::move(pvd)) {
    if (!pvd_.has_filename() || !pvd_.has_stem())
        throw InvalidInput(
            fmt::format("VTK collection needs a file name, got '{}'", pvd_.string()));
}

void VtkSeries::add(double time, const Interface& curves) {
    const std::string name =
        fmt::format("{}/frame_{:04d}.vtp", pvd_.stem().string(), frames_.size());
    write_file_atomic(pvd_.parent_path() / name, vtp_text(curves, time));
    frames_.push_back({time, name});
    write_file_atomic(pvd_, pvd_text(frames_));
}

}  // namespace slc
