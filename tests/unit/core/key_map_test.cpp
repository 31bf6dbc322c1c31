#include "slc/core/key_map.hpp"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

namespace slc {
namespace {

TEST(KeyMap, AgreesWithStdUnorderedMapThroughGrowth) {
    // Grid keys as the contouring tree makes them ((x << 32) | y), clustered as points near a
    // curve are, and random ones; a few thousand inserts grow the table from its smallest size.
    std::mt19937_64 rng(5);
    KeyMap<int> map;
    std::unordered_map<std::uint64_t, int> expected;
    for (int i = 0; i < 20000; ++i) {
        const std::uint64_t key =
            i % 2 == 0 ? (std::uint64_t{rng() % 64} << 32) | (rng() % 4096) : rng() >> 1;
        const int value = static_cast<int>(rng() % 1000);
        if (i % 3 == 0) {
            map.assign(key, value);
            expected[key] = value;
        } else {
            const auto [stored, inserted] = map.try_emplace(key, value);
            const auto [it, fresh] = expected.try_emplace(key, value);
            EXPECT_EQ(inserted, fresh);
            EXPECT_EQ(*stored, it->second);
        }
    }
    EXPECT_EQ(map.size(), expected.size());
    for (const auto& [key, value] : expected) {
        ASSERT_TRUE(map.contains(key));
        EXPECT_EQ(map.at(key), value);
    }
    for (int i = 0; i < 1000; ++i) {
        const std::uint64_t key = rng() >> 1;
        EXPECT_EQ(map.find(key) == nullptr, !expected.contains(key));
    }
}

TEST(KeyMap, TablesOfManyMegabytesKeepEveryEntry) {
    // Past 2 MiB of slots the table takes huge pages: grown from its smallest size to 16 MiB
    // of slots, and built at that size from the start, it holds the same entries.
    std::mt19937_64 rng(9);
    std::vector<std::uint64_t> keys(500'000);
    for (auto& k : keys) k = rng() >> 1;
    KeyMap<std::uint32_t> grown, reserved(keys.size());
    for (std::uint32_t i = 0; i < keys.size(); ++i) {
        grown.try_emplace(keys[i], i);
        reserved.try_emplace(keys[i], i);
    }
    ASSERT_EQ(grown.size(), keys.size());  // 2^63 keys: no two alike among these
    for (std::uint32_t i = 0; i < keys.size(); ++i) {
        ASSERT_EQ(grown.at(keys[i]), i);
        ASSERT_EQ(reserved.at(keys[i]), i);
    }
    for (int i = 0; i < 1000; ++i) EXPECT_EQ(grown.find(rng() >> 1), nullptr);
}

TEST(KeyMap, ValuesCanBeChangedInPlace) {
    KeyMap<double> map(1);
    map.try_emplace(7, 1.0);
    *map.find(7) = 2.5;
    map.at(7) += 1.0;
    EXPECT_EQ(map.at(7), 3.5);
    EXPECT_FALSE(map.try_emplace(7, 0.0).second);
    EXPECT_EQ(map.at(7), 3.5);
    EXPECT_EQ(map.find(8), nullptr);
    EXPECT_EQ(map.size(), 1u);
}

TEST(KeyMap, ReserveKeepsTheEntries) {
    KeyMap<std::uint32_t> map;
    for (std::uint32_t k = 0; k < 100; ++k) map.try_emplace(3 * std::uint64_t{k} + 1, k);
    map.reserve(100'000);
    map.reserve(10);  // never shrinks
    EXPECT_EQ(map.size(), 100u);
    for (std::uint32_t k = 0; k < 100; ++k) {
        ASSERT_NE(map.find(3 * std::uint64_t{k} + 1), nullptr);
        EXPECT_EQ(map.at(3 * std::uint64_t{k} + 1), k);
        EXPECT_EQ(map.find(3 * std::uint64_t{k} + 2), nullptr);
    }
}

}  // namespace
}  // namespace slc
