/// @file
/// KeyMap: a hash map from 64-bit keys to small values, open addressing with linear probing in
/// one array. The contouring tree and the triangulation look up every grid point they touch in
/// one; std::unordered_map's node per entry cost them a cache miss per lookup.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <new>
#include <utility>
#include <vector>

#include "slc/core/error.hpp"
#include "slc/core/memory.hpp"

namespace slc {

namespace detail {

/// The allocator of KeyMap's slots. A table of millions of entries is read at random, each
/// lookup on a page of its own: at 4 KiB a page, nearly every lookup also misses the TLB.
/// Arrays of huge_page_size or more are on huge pages (allocate_huge), which a few TLB entries
/// cover.
template <class T>
struct HugePageAllocator {
    using value_type = T;

    HugePageAllocator() = default;
    template <class U>
    explicit HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        return static_cast<T*>(bytes < huge_page_size ? ::operator new(bytes)
                                                      : allocate_huge(bytes));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < huge_page_size)
            ::operator delete(p);
        else
            free_huge(p);
    }
    friend bool operator==(const HugePageAllocator&, const HugePageAllocator&) { return true; }
};

}  // namespace detail

/// Entries are only added or changed, never erased. Any key but KeyMap::no_key. The order of the
/// entries is never observed, so results cannot depend on it.
template <class Value>
class KeyMap {
public:
    /// The one key that cannot be stored: it marks an empty slot.
    static constexpr std::uint64_t no_key = std::numeric_limits<std::uint64_t>::max();

    /// Room for about `expected` entries before the first growth.
    explicit KeyMap(std::size_t expected = 16) { rehash(capacity_for(expected)); }

    /// The number of entries.
    std::size_t size() const { return size_; }
    /// Room for about `expected` entries in all before the next growth.
    void reserve(std::size_t expected) {
        if (capacity_for(expected) > slots_.size()) rehash(capacity_for(expected));
    }
    /// Whether key has an entry.
    bool contains(std::uint64_t key) const { return find(key) != nullptr; }

    /// The value of key, or nullptr.
    const Value* find(std::uint64_t key) const {
        for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
            if (slots_[i].key == key) return &slots_[i].value;
            if (slots_[i].key == no_key) return nullptr;
        }
    }
    /// The value of key, or nullptr, to change.
    Value* find(std::uint64_t key) { return const_cast<Value*>(std::as_const(*this).find(key)); }
    /// The value of a key that must be present.
    const Value& at(std::uint64_t key) const {
        const Value* v = find(key);
        SLC_ASSERT(v != nullptr, "KeyMap::at: the key is present");
        return *v;
    }
    /// The value of a key that must be present, to change.
    Value& at(std::uint64_t key) { return const_cast<Value&>(std::as_const(*this).at(key)); }

    /// Inserts (key, value) unless key is present; returns its value and whether it was inserted.
    std::pair<Value*, bool> try_emplace(std::uint64_t key, const Value& value) {
        SLC_ASSERT(key != no_key, "KeyMap: no_key is not a key");
        if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
        std::size_t i = slot(key);
        for (; slots_[i].key != no_key; i = (i + 1) & mask_)
            if (slots_[i].key == key) return {&slots_[i].value, false};
        slots_[i] = {key, value};
        ++size_;
        return {&slots_[i].value, true};
    }
    /// Sets key's value, inserting it if absent.
    void assign(std::uint64_t key, const Value& value) {
        auto [v, inserted] = try_emplace(key, value);
        if (!inserted) *v = value;
    }

private:
    static std::size_t capacity_for(std::size_t expected) {
        return std::bit_ceil(std::max<std::size_t>(16, 2 * expected));
    }
    /// Fibonacci hashing: the top bits of key times 2^64/φ.
    std::size_t slot(std::uint64_t key) const {
        return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    }
    void rehash(std::size_t capacity) {
        std::vector<Slot, detail::HugePageAllocator<Slot>> old(capacity);
        old.swap(slots_);
        mask_ = capacity - 1;
        shift_ = 64 - std::countr_zero(capacity);
        size_ = 0;
        for (const Slot& s : old)
            if (s.key != no_key) try_emplace(s.key, s.value);
    }

    /// A key with its value, side by side: one cache line holds both.
    struct Slot {
        std::uint64_t key = no_key;
        Value value{};
    };
    std::vector<Slot, detail::HugePageAllocator<Slot>> slots_;
    std::size_t mask_ = 0;
    int shift_ = 64;
    std::size_t size_ = 0;
};

}  // namespace slc
