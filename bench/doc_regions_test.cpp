// Tests of the regions a benchmark program writes into a page written by hand (doc_regions.hpp):
// only the text between a region's markers changes, a run writes the same page twice the same,
// and a page whose markers are missing, repeated or out of order is refused whole.
#include "doc_regions.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace slc::bench {
namespace {

const std::string sample =
    "# Title\n\nWritten by hand.\n\n<!-- begin summary -->\n\nold summary\n\n<!-- end summary "
    "-->\n\nMore by hand.\n\n<!-- begin table -->\n\n| a |\n|---|\n| 1 |\n\n<!-- end table "
    "-->\n\nThe end.\n";

/// The message with_regions throws for page and regions, or "" when it throws nothing.
std::string refusal(const std::string& page, const std::vector<Region>& regions) {
    try {
        (void)with_regions(page, regions);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

TEST(DocRegions, ReplacesOnlyTheTextBetweenTheMarkers) {
    const std::string page = with_regions(sample, {{"table", "| a |\n|---|\n| 2 |\n"}});
    EXPECT_EQ(page,
              "# Title\n\nWritten by hand.\n\n<!-- begin summary -->\n\nold summary\n\n"
              "<!-- end summary -->\n\nMore by hand.\n\n<!-- begin table -->\n\n| a |\n"
              "|---|\n| 2 |\n\n<!-- end table -->\n\nThe end.\n");
    EXPECT_EQ(region_text(page, "table"), "| a |\n|---|\n| 2 |");
    EXPECT_EQ(region_text(page, "summary"), "old summary");
}

TEST(DocRegions, WritingARegionTwiceGivesThePageOnce) {
    const std::vector<Region> regions = {{"summary", "\n\nnew summary\n"}, {"table", ""}};
    const std::string once = with_regions(sample, regions);
    EXPECT_EQ(with_regions(once, regions), once);
    EXPECT_EQ(region_text(once, "summary"), "new summary");
    EXPECT_EQ(region_text(once, "table"), "");
    // A region written back with its own text leaves the page as it was.
    EXPECT_EQ(with_regions(sample, {{"summary", region_text(sample, "summary")},
                                    {"table", region_text(sample, "table")}}),
              sample);
}

TEST(DocRegions, RefusesAPageWithoutTheMarkersAndNamesThem) {
    const std::string message = refusal("# Title\n\nNo regions.\n", {{"summary", "x"}});
    EXPECT_NE(message.find("lacks the line <!-- begin summary -->"), std::string::npos) << message;
    // A marker inside a line of prose is not a marker.
    EXPECT_NE(
        refusal("see `<!-- begin summary -->` and `<!-- end summary -->`\n", {{"summary", ""}}),
        "");
}

TEST(DocRegions, RefusesTheWholePageWhenOneRegionIsBroken) {
    const std::string message =
        refusal(sample, {{"summary", "new"}, {"missing", "x"}, {"also-missing", "y"}});
    EXPECT_NE(message.find("<!-- begin missing -->"), std::string::npos) << message;
    EXPECT_NE(message.find("<!-- begin also-missing -->"), std::string::npos) << message;
}

TEST(DocRegions, RefusesRepeatedOrReversedMarkers) {
    const std::string twice = sample + "<!-- end table -->\n";
    EXPECT_NE(refusal(twice, {{"table", ""}}).find("more than once"), std::string::npos);
    const std::string reversed = "<!-- end r -->\n\n<!-- begin r -->\n";
    EXPECT_NE(refusal(reversed, {{"r", ""}}).find("before"), std::string::npos);
}

TEST(DocRegions, WritesAPageOnlyWhenItHoldsEveryRegion) {
    const auto dir = std::filesystem::temp_directory_path() / "slc_doc_regions_test";
    std::filesystem::create_directories(dir);
    const auto path = dir / "page.md";
    write_file_atomic(path, sample);
    EXPECT_NO_THROW(check_regions(path, {"summary", "table"}));
    EXPECT_THROW(write_regions(path, {{"summary", "new"}, {"missing", "x"}}), std::runtime_error);
    EXPECT_EQ(read_text_file(path), sample);  // nothing written
    write_regions(path, {{"summary", "new"}});
    EXPECT_EQ(region_text(read_text_file(path), "summary"), "new");
    EXPECT_THROW(require_regions(dir / "none.md", {"summary"}), std::runtime_error);
    // A region whose text has no blank line around it would change when written back.
    write_file_atomic(path, "<!-- begin r -->\ntight\n<!-- end r -->\n");
    EXPECT_THROW(check_regions(path, {"r"}), std::runtime_error);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace slc::bench
