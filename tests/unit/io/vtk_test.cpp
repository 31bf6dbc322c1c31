// Tests of the VTK writer: a .vtp read back by a small independent parser gives the interface's
// points bit for bit and one closed polyline per curve; the point and cell data match the curves;
// a .pvd lists every frame with its time and file; bad times and names are InvalidInput.
#include "slc/io/vtk.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "random_interfaces.hpp"
#include "slc/core/error.hpp"
#include "temp_dir.hpp"

namespace slc {
namespace {

namespace fs = std::filesystem;

using test_support::TempDir;

using test_support::slurp;

/// The text of the first element `<tag ...>` at or after `from`, up to its '>'; empty if none.
std::string element(const std::string& xml, const std::string& tag, std::size_t from = 0) {
    const std::size_t begin = xml.find("<" + tag + " ", from);
    if (begin == std::string::npos) return {};
    return xml.substr(begin, xml.find('>', begin) + 1 - begin);
}

/// The value of attribute `name` in the first element `tag` of xml; fails the test when absent.
std::string attribute(const std::string& xml, const std::string& tag, const std::string& name,
                      std::size_t from = 0) {
    const std::string e = element(xml, tag, from);
    const std::size_t at = e.find(" " + name + "=\"");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << tag << " with " << name;
        return {};
    }
    const std::size_t begin = at + name.size() + 3;
    return e.substr(begin, e.find('"', begin) - begin);
}

/// The values of the DataArray named `name` inside the element `section` (Points, Lines,
/// PointData, CellData, FieldData), parsed as doubles by the C library, as a VTK reader does.
std::vector<double> data_array(const std::string& xml, const std::string& section,
                               const std::string& name) {
    const std::size_t open = xml.find("<" + section);
    const std::size_t close = xml.find("</" + section + ">");
    const std::size_t at = xml.find("<DataArray type=", open);
    std::size_t array = at;
    while (array < close && attribute(xml, "DataArray", "Name", array) != name)
        array = xml.find("<DataArray type=", array + 1);
    if (open == std::string::npos || array >= close) {
        ADD_FAILURE() << "no DataArray " << name << " in " << section;
        return {};
    }
    const std::size_t begin = xml.find('>', array) + 1;
    std::vector<double> values;
    std::istringstream in(xml.substr(begin, xml.find("</DataArray>", begin) - begin));
    std::string word;
    while (in >> word) values.push_back(std::strtod(word.c_str(), nullptr));
    return values;
}

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// Checks that the .vtp text describes curves exactly: points, closed polylines, data arrays.
void expect_describes(const std::string& xml, const Interface& curves, double time) {
    const std::size_t n = curves.size();
    const std::size_t c = curves.curve_count();
    EXPECT_EQ(attribute(xml, "VTKFile", "type"), "PolyData");
    EXPECT_EQ(attribute(xml, "Piece", "NumberOfPoints"), std::to_string(n));
    EXPECT_EQ(attribute(xml, "Piece", "NumberOfLines"), std::to_string(c));

    const std::vector<double> xyz = data_array(xml, "Points", "Points");
    ASSERT_EQ(xyz.size(), 3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        EXPECT_TRUE(same_bits(xyz[3 * i], curves.point(i).x)) << "x of vertex " << i;
        EXPECT_TRUE(same_bits(xyz[3 * i + 1], curves.point(i).y)) << "y of vertex " << i;
        EXPECT_EQ(xyz[3 * i + 2], 0.0);
    }

    // Cell k: the vertices of curve k in order, then its first vertex again (a closed polyline).
    const std::vector<double> connectivity = data_array(xml, "Lines", "connectivity");
    const std::vector<double> offsets = data_array(xml, "Lines", "offsets");
    ASSERT_EQ(offsets.size(), c);
    ASSERT_EQ(connectivity.size(), n + c);
    std::size_t begin = 0;
    for (std::size_t k = 0; k < c; ++k) {
        const auto end = static_cast<std::size_t>(offsets[k]);
        const std::span<const Vec2> curve = curves.curve(k);
        ASSERT_EQ(end - begin, curve.size() + 1) << "cell " << k;
        for (std::size_t j = 0; j <= curve.size(); ++j) {
            const auto index = static_cast<std::size_t>(connectivity[begin + j]);
            ASSERT_LT(index, n);
            EXPECT_EQ(curves.point(index), curve[j % curve.size()])
                << "cell " << k << " item " << j;
        }
        begin = end;
    }

    const std::vector<double> point_curve = data_array(xml, "PointData", "curve");
    ASSERT_EQ(point_curve.size(), n);
    for (std::size_t i = 0; i < n; ++i)
        EXPECT_EQ(point_curve[i], static_cast<double>(curves.curve_of(i)));
    const std::vector<double> areas = data_array(xml, "CellData", "signed_area");
    const std::vector<double> lengths = data_array(xml, "CellData", "length");
    ASSERT_EQ(areas.size(), c);
    ASSERT_EQ(lengths.size(), c);
    double total_area = 0.0, total_length = 0.0;
    for (std::size_t k = 0; k < c; ++k) {
        EXPECT_TRUE(same_bits(areas[k], signed_area(curves.curve(k))));
        total_area += areas[k];
        total_length += lengths[k];
    }
    // Sums in another order than area() and length(): equal to a few rounding errors.
    constexpr double sum_tolerance = 1e-13;
    EXPECT_NEAR(total_area, area(curves), sum_tolerance);
    EXPECT_NEAR(total_length, length(curves), sum_tolerance);

    const std::vector<double> t = data_array(xml, "FieldData", "TimeValue");
    ASSERT_EQ(t.size(), 1u);
    EXPECT_TRUE(same_bits(t[0], time));
}

TEST(Vtp, RandomInterfacesReadBackExactly) {
    const unsigned seed = 20240817;
    std::mt19937 rng(seed);
    SCOPED_TRACE(fmt::format("seed {}", seed));
    for (int trial = 0; trial < 50; ++trial) {
        const Interface curves = testing::random_interface(rng);
        const double time = std::uniform_real_distribution<double>(0.0, 10.0)(rng);
        SCOPED_TRACE(fmt::format("trial {}", trial));
        expect_describes(vtp_text(curves, time), curves, time);
    }
}

TEST(Vtp, ExtremeCoordinatesReadBackExactly) {
    const double tiny = std::numeric_limits<double>::denorm_min();
    const Interface curves({{{-1e300, 0.1}, {1.0 / 3.0, tiny}, {2.0, 1e-300}}});
    expect_describes(vtp_text(curves, 0.1), curves, 0.1);
}

TEST(Vtp, EmptyInterfaceHasNoPoints) {
    const std::string xml = vtp_text(Interface{}, 2.0);
    expect_describes(xml, Interface{}, 2.0);
}

TEST(Vtp, NonFiniteTimeIsInvalid) {
    const Interface square({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}});
    EXPECT_THROW(vtp_text(square, std::nan("")), InvalidInput);
    EXPECT_THROW(vtp_text(square, std::numeric_limits<double>::infinity()), InvalidInput);
}

TEST(VtkSeries, WritesFramesAndACollectionOfThem) {
    TempDir dir;
    VtkSeries series(dir.path() / "run.pvd");
    std::vector<Interface> shapes;
    const std::vector<double> times = {0.0, 0.25, 0.5};
    for (std::size_t f = 0; f < times.size(); ++f) {
        const double s = 1.0 + static_cast<double>(f);
        shapes.push_back(Interface({{{0, 0}, {s, 0}, {0, s}}, {{3, 3}, {3 + s, 3}, {3, 3 + s}}}));
        series.add(times[f], shapes.back());
    }
    ASSERT_EQ(series.frames().size(), times.size());

    const std::string pvd = slurp(dir.path() / "run.pvd");
    EXPECT_EQ(attribute(pvd, "VTKFile", "type"), "Collection");
    std::size_t f = 0;
    for (std::size_t at = pvd.find("<DataSet "); at != std::string::npos;
         at = pvd.find("<DataSet ", at + 1), ++f) {
        ASSERT_LT(f, times.size());
        const std::string time = attribute(pvd, "DataSet", "timestep", at);
        const std::string file = attribute(pvd, "DataSet", "file", at);
        EXPECT_TRUE(same_bits(std::strtod(time.c_str(), nullptr), times[f]));
        EXPECT_EQ(file, fmt::format("run/frame_{:04d}.vtp", f));
        const fs::path frame = dir.path() / file;
        ASSERT_TRUE(fs::exists(frame)) << frame;
        expect_describes(slurp(frame), shapes[f], times[f]);
    }
    EXPECT_EQ(f, times.size());
    // Atomic writes leave no temporary files behind.
    for (const auto& entry : fs::recursive_directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(VtkSeries, FramesAddedTogetherWriteWhatOneByOneWould) {
    TempDir one_dir, all_dir;
    VtkSeries one(one_dir.path() / "run.pvd"), all(all_dir.path() / "run.pvd");
    std::vector<std::pair<double, Interface>> frames;
    for (int f = 0; f < 3; ++f) {
        const double s = 1.0 + f;
        frames.emplace_back(0.5 * f, Interface({{{0, 0}, {s, 0}, {0, s}}}));
        one.add(frames.back().first, frames.back().second);
    }
    all.add(std::span<const std::pair<double, Interface>>(frames).first(2));
    all.add(frames[2].first, frames[2].second);
    ASSERT_EQ(all.frames().size(), 3u);
    EXPECT_EQ(slurp(all_dir.path() / "run.pvd"), slurp(one_dir.path() / "run.pvd"));
    for (const VtkFrame& f : one.frames())
        EXPECT_EQ(slurp(all_dir.path() / f.file), slurp(one_dir.path() / f.file)) << f.file;
    all.add({});  // nothing to add: nothing changes
    EXPECT_EQ(all.frames().size(), 3u);
}

TEST(VtkSeries, LaterFramesAreAppendedInPlaceAndTheCollectionStaysWhole) {
    TempDir dir;
    const fs::path pvd = dir.path() / "run.pvd";
    VtkSeries series(pvd);
    auto inode = [&] {
        struct stat st {};
        EXPECT_EQ(::stat(pvd.c_str(), &st), 0);
        return st.st_ino;
    };
    series.add(0.0, Interface({{{0, 0}, {1, 0}, {0, 1}}}));
    const auto first = inode();
    for (int f = 1; f < 40; ++f) {
        series.add(0.125 * f, Interface({{{0, 0}, {1.0 + f, 0}, {0, 1}}}));
        // The same file, extended in place: not replaced by a rewrite of every line.
        EXPECT_EQ(inode(), first) << "frame " << f;
        ASSERT_EQ(slurp(pvd), pvd_text(series.frames())) << "frame " << f;
    }
}

TEST(VtkSeries, ACollectionChangedOnDiskIsWrittenWholeAgain) {
    TempDir dir;
    const fs::path pvd = dir.path() / "run.pvd";
    VtkSeries series(pvd);
    const Interface triangle({{{0, 0}, {1, 0}, {0, 1}}});
    series.add(0.0, triangle);
    series.add(0.5, triangle);
    // Truncated (its closing lines lost), then replaced by other text of the same length.
    fs::resize_file(pvd, fs::file_size(pvd) - 5);
    series.add(1.0, triangle);
    EXPECT_EQ(slurp(pvd), pvd_text(series.frames()));
    const std::size_t size = fs::file_size(pvd);
    std::ofstream(pvd, std::ios::binary | std::ios::trunc) << std::string(size, 'x');
    series.add(1.5, triangle);
    EXPECT_EQ(slurp(pvd), pvd_text(series.frames()));
    ASSERT_EQ(series.frames().size(), 4u);
}

TEST(VtkSeries, BadTimesNamesAndFoldersAreInvalid) {
    TempDir dir;
    const Interface square({{{0, 0}, {1, 0}, {1, 1}, {0, 1}}});
    VtkSeries series(dir.path() / "run.pvd");
    EXPECT_THROW(series.add(std::nan(""), square), InvalidInput);
    EXPECT_TRUE(series.frames().empty());
    EXPECT_THROW(VtkSeries(dir.path() / ""), InvalidInput);
    const std::vector<VtkFrame> bad = {{0.0, "a<b.vtp"}};
    EXPECT_THROW(pvd_text(bad), InvalidInput);

    // A collection where a file blocks the frames' folder cannot be written.
    std::ofstream(dir.path() / "blocked") << "x";
    VtkSeries blocked(dir.path() / "blocked.pvd");
    EXPECT_THROW(blocked.add(0.0, square), InvalidInput);
}

}  // namespace
}  // namespace slc
