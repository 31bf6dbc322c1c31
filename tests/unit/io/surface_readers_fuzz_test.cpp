// Mutation fuzzing of the surface readers (OBJ, STL, PLY), deterministic and fast enough to run
// with every test and under the sanitizers: valid files in every form, mutated by byte flips,
// insertions, deletions, repeats, cuts, splices and numbers replaced by extreme ones, must each
// be read or refused with InvalidInput (surface_reader_fuzz.hpp). tests/fuzz/ holds the same
// check as a libFuzzer target for longer, coverage-guided runs (scripts/fuzz).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "slc/geometry/surface_shapes.hpp"
#include "surface_bytes.hpp"
#include "surface_reader_fuzz.hpp"

namespace slc {
namespace {

using test::bytes_of;

/// Valid files of a tetrahedron (and an icosphere's OBJ) in every form the readers take.
std::vector<std::string> seeds() {
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    std::vector<std::string> out;
    out.push_back(obj_text(sphere({0.1, 0, 0}, 1.0, 1)));
    out.push_back(
        "# pyramid\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nv 0.5 0.5 1\n"
        "f 4/1 3/1 2/1 1/1\nf 1//1 2//1 -1//1\nf 2/1/1 3/1/1 5/1/1\r\nf -3 -2 -1\nf 4 1 5\n");
    std::string stl = "solid t\n";
    for (const auto& t : f) {
        stl += "facet normal 0 0 0\nouter loop\n";
        for (int k : t) stl += fmt::format("vertex {} {} {}\n", v[k][0], v[k][1], v[k][2]);
        stl += "endloop\nendfacet\n";
    }
    out.push_back(stl + "endsolid t\n");
    Surface tetra;
    for (const auto& p : v) tetra.vertices.push_back({p[0], p[1], p[2]});
    for (const auto& t : f)
        tetra.triangles.push_back({static_cast<std::uint32_t>(t[0]),
                                   static_cast<std::uint32_t>(t[1]),
                                   static_cast<std::uint32_t>(t[2])});
    const std::string binary = test::binary_stl(tetra, "");
    out.push_back(binary);
    const std::string tail =
        " 1.0\ncomment by hand\nelement vertex 4\nproperty double x\nproperty float y\n"
        "property float z\nproperty uchar red\nelement face 4\n"
        "property list uchar int vertex_indices\nproperty float quality\nend_header\n";
    std::string ascii = "ply\nformat ascii" + tail;
    for (const auto& p : v) ascii += fmt::format("{} {} {} 255\n", p[0], p[1], p[2]);
    for (const auto& t : f) ascii += fmt::format("3 {} {} {} 0.5\n", t[0], t[1], t[2]);
    out.push_back(ascii);
    for (const bool little : {true, false}) {
        std::string bin = std::string("ply\nformat ") +
                          (little ? "binary_little_endian" : "binary_big_endian") + tail;
        for (const auto& p : v) {
            bin += bytes_of(p[0], little) + bytes_of(static_cast<float>(p[1]), little) +
                   bytes_of(static_cast<float>(p[2]), little) + bytes_of(std::uint8_t{255}, little);
        }
        for (const auto& t : f) {
            bin += bytes_of(std::uint8_t{3}, little);
            for (int i : t) bin += bytes_of(static_cast<std::int32_t>(i), little);
            bin += bytes_of(0.5f, little);
        }
        out.push_back(bin);
    }
    return out;
}

/// One random edit of text, or now and then two to four.
std::string mutate(std::string text, const std::vector<std::string>& others, std::mt19937_64& rng) {
    static const char* const numbers[] = {
        "1e400",      "-1e400", "nan",        "inf",        "-0",          "99999999999999999999",
        "4294967295", "-1",     "2147483648", "0x10",       "1e-400",      "18446744073709551616",
        "3.5",        "",       "1e308",      "4294967296", "-2147483649", "0"};
    static const char specials[] = {'\0', '\n', '\r', ' ', '/', '-', '#', '.', 'e', '1', '\xff'};
    auto below = [&](std::size_t n) {
        return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n);
    };
    const int edits = rng() % 4 == 0 ? 2 + static_cast<int>(rng() % 3) : 1;
    for (int e = 0; e < edits; ++e) {
        const std::size_t at = below(text.size() + 1);
        switch (rng() % 9) {
            case 0:  // flip a bit
                if (!text.empty()) text[below(text.size())] ^= static_cast<char>(1u << (rng() % 8));
                break;
            case 1:  // a byte of the kind parsers look for
                if (!text.empty()) text[below(text.size())] = specials[below(sizeof specials)];
                break;
            case 2:  // insert random bytes
                for (std::size_t n = 1 + below(8); n-- > 0;)
                    text.insert(text.begin() + static_cast<std::ptrdiff_t>(at),
                                static_cast<char>(rng()));
                break;
            case 3:  // delete a range
                text.erase(at, 1 + below(32));
                break;
            case 4:  // repeat a range
                if (at < text.size()) text.insert(at, text.substr(at, 1 + below(64)));
                break;
            case 5:  // cut the end
                text.resize(at);
                break;
            case 6: {  // a number replaced by an extreme one
                std::size_t start = at;
                while (start < text.size() &&
                       !(std::isdigit(static_cast<unsigned char>(text[start]))))
                    ++start;
                std::size_t end = start;
                while (end < text.size() &&
                       (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.'))
                    ++end;
                text.replace(start, end - start, numbers[below(std::size(numbers))]);
                break;
            }
            case 7: {  // splice with another seed
                const std::string& other = others[below(others.size())];
                text = text.substr(0, at) + other.substr(below(other.size() + 1));
                break;
            }
            default: {  // a binary count or index overwritten by an extreme 32-bit value
                const std::uint32_t values[] = {0u,          1u,       0xffffffffu, 0x7fffffffu,
                                                0x80000000u, 0x10000u, 1000000000u};
                const std::string b = bytes_of(values[below(std::size(values))], rng() % 2 == 0);
                if (at + 4 <= text.size()) text.replace(at, 4, b);
                break;
            }
        }
    }
    return text;
}

TEST(SurfaceReadersFuzz, SeedsAreValidSurfaces) {
    // The mutations start from files their readers accept and validate: two OBJ, two STL
    // (ASCII, binary), three PLY (ASCII, both binary byte orders).
    const std::vector<std::string> corpus = seeds();
    ASSERT_EQ(corpus.size(), 7u);
    for (std::size_t s = 0; s < corpus.size(); ++s) {
        const auto parse = s < 2 ? &parse_obj : s < 4 ? &parse_stl : &parse_ply;
        EXPECT_NO_THROW(prepare_surface(parse(corpus[s], "seed"))) << "seed " << s;
        EXPECT_NO_THROW(fuzz::read_surface_bytes(corpus[s])) << "seed " << s;
    }
}

TEST(SurfaceReadersFuzz, MutatedFilesAreReadOrRefusedInOneLine) {
    const std::vector<std::string> corpus = seeds();
    std::mt19937_64 rng(20261128);
    // SLC_FUZZ_MUTANTS sets a longer run.
    const char* asked = std::getenv("SLC_FUZZ_MUTANTS");
    const int mutants_per_seed = asked != nullptr ? std::atoi(asked) : 2000;
    for (std::size_t s = 0; s < corpus.size(); ++s) {
        std::string current = corpus[s];
        for (int i = 0; i < mutants_per_seed; ++i) {
            // Mostly from the seed; now and then from the last mutant, to go deeper.
            const std::string input = mutate(rng() % 4 == 0 ? current : corpus[s], corpus, rng);
            try {
                fuzz::read_surface_bytes(input);
            } catch (const std::exception& e) {
                FAIL() << "seed " << s << ", mutant " << i << ": " << e.what() << "\ninput ("
                       << input.size() << " bytes):\n"
                       << input.substr(0, 400);
            }
            current = input;
        }
    }
}

}  // namespace
}  // namespace slc
