// PairGrid: every overlapping pair among a set of boxes at once, through a uniform grid built
// afresh for each call. The world's candidate pairs come from here each step; the
// b2DynamicTree (broadphase.h) stays for queries of one region (sweeps, World queries),
// where it wins. Benchmarked against the tree, brute force and sort-and-sweep in
// tests/bench/world_bench.cpp (BM_Broadphase).
// Cost: linear in the boxes and the pairs for boxes of similar sizes (a game's bodies; long
// walls are tested against everything, one by one). Boxes of very different sizes crowded
// together cost more: the small ones share cells (tested pairwise) or the large ones span
// many (tested against all); the answer is exact either way.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "jostle/collision.h"

namespace jostle::detail {

struct GridItem {
    Aabb box;              // finite, min <= max
    std::uint32_t id = 0;  // ascending through the items
    bool active = false;   // pairs of two inactive items are not reported
};

struct GridPair {
    std::uint32_t a = 0;  // ids, a < b
    std::uint32_t b = 0;
};

class PairGrid {
public:
    // Writes to `out` every pair of items whose boxes overlap (closed: touching counts, as
    // b2TestOverlap), at least one of them active, sorted by (a, b), each pair once. Items
    // must come in ascending id order. Exact whatever the grid: the grid only decides which
    // pairs are tested.
    void find(std::span<const GridItem> items, std::vector<GridPair>& out);
    // The same, with big items (those spanning more than 64 cells: long walls) looked up
    // through big_query(box, found), which must call found(id) for every item whose box
    // overlaps `box` (more is fine: each is tested; unknown ids are ignored), instead of
    // being tested against every item. The world passes its b2DynamicTree's query.
    using BigQuery = std::function<void(const Aabb& box, const std::function<void(std::uint32_t id)>& found)>;
    void find(std::span<const GridItem> items, std::vector<GridPair>& out, const BigQuery& big_query);

private:
    struct Cells {
        std::int32_t x0, y0, x1, y1;
    };
    // A box as the pair test compares it: (min.x, min.y, -max.x, -max.y), so that one
    // four-lane compare tests all four sides (negation is exact).
    struct alignas(16) TestBox {
        float v[4];
    };
    std::vector<Cells> cells_;            // per item
    std::vector<TestBox> boxes_;          // per item
    std::vector<std::uint32_t> big_;      // items spanning too many cells: tested against all
    std::vector<std::uint32_t> starts_;   // per cell or hash bucket, into entries_ (counting sort)
    // One item in one cell: the item's ordinal, then kFirstColumn, kFirstRow, kActive. Kept
    // to 4 bytes because the counting sort scatters them.
    std::vector<std::uint32_t> entries_;
    std::vector<std::uint64_t> entry_cells_;      // hashed grids only: each entry's cell
    std::vector<std::uint32_t> fill_;     // counting sorts' positions
    std::vector<std::uint32_t> bucket_of_entry_;  // hashed grids only, in the order entries are made
    std::vector<std::uint64_t> keys_;     // pairs found, as (lower item, higher item)
    std::vector<std::uint64_t> sorted_;   // the sort's other buffer
    template <bool kDense>
    std::size_t gather(std::span<const GridItem> items, std::size_t entry_count, const Cells& region, int bits);
    void sort_keys(std::uint32_t n, int bits, std::size_t count);
};

}  // namespace jostle::detail
