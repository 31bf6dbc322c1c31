/// @file
/// 2:1 balance of a 2^d tree (Orthtree<d>: Quadtree, Octree), written for any tree with the
/// interface below. A tree here offers size(), is_leaf(c), cell(c).level, depth(),
/// max_depth() and split(c); `coarser(c, d)` names the leaf bordering cell c across its face d
/// (0 .. 2d − 1) when that leaf is coarser than c, else Tree::no_cell.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "slc/core/parallel.hpp"

namespace slc::tree_balance {

/// True when every two leaves sharing part of a face differ by at most one level. That holds
/// iff every cell with children has all its same-level face neighbours (or the root box's face
/// there): where one is missing, a leaf at least two levels coarser borders a leaf descendant of
/// the cell, and where none is, the neighbours of a leaf are siblings or its parent's neighbours
/// or their children. So only the cells with children are asked, each on one worker thread.
template <int Faces, class Tree, class Coarser>
bool is_balanced(const Tree& tree, Coarser&& coarser) {
    std::vector<std::uint8_t> coarse(tree.size(), 0);
    parallel_for(tree.size(), [&](std::size_t c) {
        if (tree.is_leaf(c)) return;
        for (int d = 0; d < Faces; ++d)
            if (coarser(c, d) != Tree::no_cell) coarse[c] = 1;
    });
    return std::find(coarse.begin(), coarse.end(), std::uint8_t{1}) == coarse.end();
}

/// Splits leaves until the tree is balanced (is_balanced), calling on_split(c) after each split
/// of cell c, in order. From the finest level to the coarsest, a missing neighbour of a cell at
/// level l is a leaf above level l, split until the neighbour exists; the splits make cells
/// with children above level l, handled when their own level comes up. Cost O(cells) on average.
template <int Faces, class Tree, class Coarser, class OnSplit>
void balance(Tree& tree, Coarser&& coarser, OnSplit&& on_split) {
    if (is_balanced<Faces>(tree, coarser)) return;  // the common case, on all worker threads
    std::vector<std::vector<std::uint32_t>> by_level(static_cast<std::size_t>(tree.max_depth()) +
                                                     1);
    for (std::uint32_t c = 0; c < tree.size(); ++c)
        if (!tree.is_leaf(c)) by_level[static_cast<std::size_t>(tree.cell(c).level)].push_back(c);
    for (int level = tree.depth() - 1; level >= 1; --level) {
        const auto& list = by_level[static_cast<std::size_t>(level)];
        for (std::size_t k = 0; k < list.size(); ++k) {
            for (int d = 0; d < Faces; ++d) {
                for (std::uint32_t n = coarser(list[k], d); n != Tree::no_cell;
                     n = coarser(list[k], d)) {
                    tree.split(n);
                    on_split(n);
                    by_level[static_cast<std::size_t>(tree.cell(n).level)].push_back(n);
                }
            }
        }
    }
}

/// All leaves, in increasing cell number.
template <class Tree>
std::vector<std::uint32_t> leaves(const Tree& tree) {
    std::vector<std::uint32_t> out;
    for (std::size_t c = 0; c < tree.size(); ++c)
        if (tree.is_leaf(c)) out.push_back(static_cast<std::uint32_t>(c));
    return out;
}

}  // namespace slc::tree_balance
