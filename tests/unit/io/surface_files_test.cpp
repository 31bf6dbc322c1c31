// Tests of the surface file readers and writers: exact contents of small files in every form,
// round trips, and one-line errors naming the place.
#include "slc/io/surface_files.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "slc/core/error.hpp"
#include "slc/geometry/surface_shapes.hpp"
#include "slc/geometry/validate_surface.hpp"
#include "slc/io/points_csv.hpp"
#include "slc/io/vtk.hpp"
#include "surface_bytes.hpp"

namespace slc {
namespace {

using test::binary_stl;
using test::bytes_of;

/// The message a parser throws, or "" if it accepts the text.
template <class Parse>
std::string refusal(Parse&& parse, const std::string& text) {
    try {
        parse(text, "f");
    } catch (const InvalidInput& e) {
        return e.what();
    }
    return "";
}

TEST(Obj, ReadsEveryFaceFormNegativeIndicesAndFansPolygons) {
    const std::string text =
        "# a square pyramid\n"
        "o pyramid\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\n"
        "vt 0 0\nvn 0 0 1\n"
        "v 0.5 0.5 1  # apex\n"
        "f 4/1 3/1 2/1 1/1\n"      // the base, a quad: two triangles
        "f 1//1 2//1 -1//1\n"      // −1: the apex
        "f 2/1/1 3/1/1 5/1/1\r\n"  // CRLF
        "f -3 -2 -1\n"
        "f 4 1 5\n";
    const Surface s = parse_obj(text, "pyramid.obj");
    ASSERT_EQ(s.vertices.size(), 5u);
    EXPECT_EQ(s.vertices[4], (Vec3{0.5, 0.5, 1}));
    const std::vector<TriangleIndices> want = {{3, 2, 1}, {3, 1, 0}, {0, 1, 4},
                                               {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    EXPECT_EQ(s.triangles, want);
    EXPECT_TRUE(prepare_surface(s).notes.empty());
}

TEST(Obj, RefusesBadFilesNamingTheLine) {
    EXPECT_EQ(refusal(parse_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"),
              "f, line 4: vertex index 0 is out of range");
    EXPECT_EQ(refusal(parse_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
              "f, line 4: vertex index 4 is out of range (there are 3)");
    EXPECT_EQ(refusal(parse_obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"),
              "f, line 4: vertex index -4 is out of range");
    EXPECT_EQ(refusal(parse_obj, "v 0 zero 0\n"), "f, line 1: \"zero\" is not a finite number");
    EXPECT_EQ(refusal(parse_obj, "v 0 0\n"), "f, line 1: expected \"v x y z\", got 2 numbers");
    EXPECT_EQ(refusal(parse_obj, "v 0 0 0\nf 1 1\n"),
              "f, line 2: a face needs at least 3 corners, got 2");
    EXPECT_EQ(refusal(parse_obj, "v 0 0 0\n"), "f: no faces");
    EXPECT_EQ(refusal(parse_obj, "v 0 0 nan\n"), "f, line 1: \"nan\" is not a finite number");
}

TEST(Obj, RoundTripsExactly) {
    const Surface s = torus({0.1, -0.2, 0.3}, 1.0 / 3.0, 0.1, 12, 7);
    const Surface back = parse_obj(obj_text(s), "t.obj");
    EXPECT_EQ(back.vertices, s.vertices);
    EXPECT_EQ(back.triangles, s.triangles);
}

TEST(Stl, BinaryMergesCoincidentCornersExactly) {
    const Surface box = box_surface({-1, -0.5, 0}, {1, 0.5, 0.25}, 2);  // exact in float
    for (const std::string header : {"made by a test", "solid but binary"}) {
        const Surface s = parse_stl(binary_stl(box, header), "box.stl");
        ASSERT_EQ(s.size(), box.size());
        EXPECT_EQ(s.vertices.size(), 6u * 4 + 2);  // 6 n² + 2 boundary lattice points
        for (std::size_t t = 0; t < s.size(); ++t)
            for (int k = 0; k < 3; ++k) EXPECT_EQ(s.triangle(t)[k], box.triangle(t)[k]);
        EXPECT_EQ(euler_characteristic(s), 2);
        EXPECT_TRUE(prepare_surface(s).notes.empty());
    }
    std::string cut = binary_stl(box, "x");
    cut.pop_back();
    EXPECT_EQ(refusal(parse_stl, cut),
              "f: a binary STL file of 48 triangles has 2484 bytes, but the file has 2483");
}

TEST(Stl, AsciiMergesCornersAndNamesBadLines) {
    std::string text = "solid tetra\n";
    const Surface tet = [] {
        Surface s;
        s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
        return s;
    }();
    for (std::size_t t = 0; t < tet.size(); ++t) {
        text += "  facet normal 0 0 0\n    outer loop\n";
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = tet.triangle(t)[k];
            // −0 for one zero: the same vertex as +0.
            text += fmt::format("      vertex {} {} {}\n",
                                p.x == 0 && t == 1 ? "-0" : fmt::format("{}", p.x), p.y, p.z);
        }
        text += "    endloop\n  endfacet\n";
    }
    text += "endsolid tetra\n";
    const Surface s = parse_stl(text, "t.stl");
    EXPECT_EQ(s.vertices.size(), 4u);
    ASSERT_EQ(s.size(), tet.size());
    for (std::size_t t = 0; t < s.size(); ++t)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(s.triangle(t)[k], tet.triangle(t)[k]);
    EXPECT_EQ(refusal(parse_stl, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"),
              "f, line 4: expected \"vertex x y z\" in a facet");
    EXPECT_EQ(refusal(parse_stl, "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
              "f: the file ends inside a facet");
    EXPECT_EQ(refusal(parse_stl, "solid x\nfacet\nvertex 0 0 0\nvertex 1 0 0\nendfacet\n"),
              "f, line 5: a facet needs at least 3 vertices, got 2");
    EXPECT_EQ(refusal(parse_stl, "solid x\nfacade\n"), "f, line 2: unexpected \"facade\"");
    EXPECT_EQ(refusal(parse_stl, "solid x\nendsolid\n"), "f: no triangles");
    EXPECT_EQ(refusal(parse_stl, "hello\n"), "f, line 1: an ASCII STL file begins with \"solid\"");
}

TEST(Ply, ReadsAsciiAndBinaryOfBothByteOrders) {
    const std::string header_tail =
        " 1.0\ncomment made by hand\nelement vertex 4\nproperty double x\nproperty float y\n"
        "property float z\nproperty uchar red\nelement face 4\n"
        "property list uchar int vertex_indices\nproperty float quality\nend_header\n";
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    std::string ascii = "ply\nformat ascii" + header_tail;
    for (const auto& p : v) ascii += fmt::format("{} {} {} 255\n", p[0], p[1], p[2]);
    for (const auto& t : f) ascii += fmt::format("3 {} {} {} 0.5\n", t[0], t[1], t[2]);
    const Surface want = parse_ply(ascii, "a.ply");
    ASSERT_EQ(want.vertices.size(), 4u);
    EXPECT_EQ(want.vertices[3], (Vec3{0, 0, 1}));
    EXPECT_EQ(want.triangles,
              (std::vector<TriangleIndices>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    for (const bool little : {true, false}) {
        std::string bin = std::string("ply\nformat ") +
                          (little ? "binary_little_endian" : "binary_big_endian") + header_tail;
        for (const auto& p : v) {
            bin += bytes_of(p[0], little) + bytes_of(static_cast<float>(p[1]), little) +
                   bytes_of(static_cast<float>(p[2]), little) + bytes_of(std::uint8_t{255}, little);
        }
        for (const auto& t : f) {
            bin += bytes_of(std::uint8_t{3}, little);
            for (int i : t) bin += bytes_of(static_cast<std::int32_t>(i), little);
            bin += bytes_of(0.5f, little);
        }
        const Surface s = parse_ply(bin, "b.ply");
        EXPECT_EQ(s.vertices, want.vertices);
        EXPECT_EQ(s.triangles, want.triangles);
        bin.pop_back();
        EXPECT_EQ(refusal(parse_ply, bin), "f: the data ends early, in element face 3");
    }
    EXPECT_EQ(refusal(parse_ply, "ply\nformat ascii 1.0\nelement vertex 1\n"),
              "f: the PLY header has no end_header line");
    EXPECT_EQ(refusal(parse_ply, "plz\n"), "f, line 1: a PLY file begins with \"ply\"");
    EXPECT_EQ(refusal(parse_ply,
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                      "y\nproperty float z\nelement face 1\nproperty list uchar int "
                      "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
              "f: a face refers to vertex 5, but there are 3");
}

TEST(SurfaceFiles, ReadSurfaceChoosesByExtension) {
    EXPECT_TRUE(is_surface_file("a/b.OBJ"));
    EXPECT_TRUE(is_surface_file("b.stl"));
    EXPECT_TRUE(is_surface_file("b.ply"));
    EXPECT_FALSE(is_surface_file("b.json"));
    try {
        read_surface("nowhere/x.off");
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_EQ(std::string(e.what()),
                  "nowhere/x.off: unknown surface format (expected .obj, .stl, .ply or .vdb)");
    }
}

TEST(SurfaceFiles, VtpHoldsPointsAndTriangles) {
    const Surface s = box_surface({0, 0, 0}, {1, 1, 1}, 1);
    const std::string text = vtp_text(s, 0.5);
    EXPECT_NE(text.find("NumberOfPoints=\"8\""), std::string::npos);
    EXPECT_NE(text.find("NumberOfPolys=\"12\""), std::string::npos);
    EXPECT_NE(text.find("<Polys>"), std::string::npos);
    EXPECT_NE(text.find("Name=\"offsets\""), std::string::npos);
}

TEST(Points3Csv, ParsesThreeColumnsAndNamesBadLines) {
    const auto p = parse_points3_csv("x,y,z\n1,2,3\n\n-0.5, 0 ,1e-3\n", "p.csv");
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[1], (Vec3{-0.5, 0, 1e-3}));
    try {
        parse_points3_csv("1,2\n", "p.csv");
        FAIL();
    } catch (const InvalidInput& e) {
        EXPECT_EQ(std::string(e.what()), "p.csv, line 1: expected 3 columns x,y,z, got 2");
    }
}

}  // namespace
}  // namespace slc
