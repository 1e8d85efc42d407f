// PairGrid (engine/world/src/pair_grid.h, private): every overlapping pair at once must be
// exactly brute force's list (closed overlap, at least one active item, sorted, each once),
// whatever the boxes: mixed sizes, long walls, touching edges, points, far and negative
// coordinates, ids with gaps. And over the broadphase's fat bounds it must give the pairs one
// tree query per moving body gives, which is what World::step relied on before the grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "broadphase.h"  // engine/world/src (private)
#include "jostle/core/rng.h"
#include "pair_grid.h"

namespace jostle::detail {
namespace {

bool closed_overlap(const Aabb& a, const Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> brute_force(const std::vector<GridItem>& items) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        for (std::size_t j = i + 1; j < items.size(); ++j) {
            if ((items[i].active || items[j].active) && closed_overlap(items[i].box, items[j].box)) {
                out.emplace_back(items[i].id, items[j].id);
            }
        }
    }
    return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> grid_pairs(PairGrid& grid, const std::vector<GridItem>& items) {
    std::vector<GridPair> found;
    grid.find(items, found);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const GridPair& p : found) out.emplace_back(p.a, p.b);
    return out;
}

Aabb box_at(Vec2 centre, Vec2 half) { return {centre - half, centre + half}; }

TEST(PairGrid, NoItemsOrOneItemGiveNoPairs) {
    PairGrid grid;
    std::vector<GridPair> found{{1, 2}};
    grid.find({}, found);
    EXPECT_TRUE(found.empty());
    const std::vector<GridItem> one{{box_at({0, 0}, {1, 1}), 7, true}};
    grid.find(one, found);
    EXPECT_TRUE(found.empty());
}

TEST(PairGrid, TouchingEdgesAndCornersArePairs) {
    PairGrid grid;
    const std::vector<GridItem> items{
        {{{0, 0}, {10, 10}}, 0, true},
        {{{10, 0}, {20, 10}}, 1, true},    // shares an edge with 0
        {{{20, 10}, {30, 20}}, 2, true},   // shares a corner with 1
        {{{30.001f, 0}, {40, 5}}, 3, true},  // misses 2 by a hair
    };
    const auto pairs = grid_pairs(grid, items);
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected{{0, 1}, {1, 2}};
    EXPECT_EQ(pairs, expected);
}

TEST(PairGrid, InactivePairsAreLeftOutButActiveOnesMeetThem) {
    PairGrid grid;
    const std::vector<GridItem> items{
        {box_at({0, 0}, {5, 5}), 2, false},
        {box_at({1, 1}, {5, 5}), 4, false},  // overlaps 2: both inactive, no pair
        {box_at({2, 2}, {1, 1}), 9, true},   // inside both
    };
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected{{2, 9}, {4, 9}};
    EXPECT_EQ(grid_pairs(grid, items), expected);
}

TEST(PairGrid, PointsAndIdenticalBoxes) {
    PairGrid grid;
    const std::vector<GridItem> items{
        {{{3, 3}, {3, 3}}, 0, true},  // a point
        {{{3, 3}, {3, 3}}, 1, true},  // the same point
        {box_at({3, 3}, {2, 2}), 2, true},
        {box_at({3, 3}, {2, 2}), 3, true},
    };
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    EXPECT_EQ(grid_pairs(grid, items), expected);
}

TEST(PairGrid, LongWallsMeetEverythingAlongThem) {
    PairGrid grid;
    std::vector<GridItem> items;
    items.push_back({{{-10, -2}, {1010, 0}}, 0, false});  // a floor, many cells long
    for (std::uint32_t k = 0; k < 100; ++k) {
        items.push_back({box_at({5.0f + 10.0f * static_cast<float>(k), 1.0f}, {2, 1}), k + 1, true});
    }
    const auto pairs = grid_pairs(grid, items);
    EXPECT_EQ(pairs.size(), 100u);  // each box's bottom touches the floor's top (y = 0)
    EXPECT_EQ(pairs, brute_force(items));
}

TEST(PairGrid, FarAndNegativeCoordinates) {
    PairGrid grid;
    const std::vector<GridItem> items{
        {box_at({-1e11f, -1e11f}, {4, 4}), 0, true}, {box_at({-1e11f, -1e11f}, {1, 1}), 1, true},
        {box_at({1e11f, 1e11f}, {4, 4}), 2, true},   {box_at({1e11f, 1e11f}, {1, 1}), 3, true},
        {box_at({0, 0}, {4, 4}), 4, true},           {{{-1e12f, -1}, {1e12f, 1}}, 5, false},  // very long
    };
    EXPECT_EQ(grid_pairs(grid, items), brute_force(items));
}

// Seeded random scenes of every flavour: sizes from points to walls, clusters and sparse
// spreads, some inactive items, ids with gaps.
TEST(PairGrid, PropertyEqualsBruteForce) {
    Rng rng(20261126);
    PairGrid grid;  // reused across scenes, as the world reuses it across steps
    for (int scene = 0; scene < 300; ++scene) {
        const auto n = static_cast<std::uint32_t>(rng.below(400));
        const float spread = rng.uniform(10.0f, 5000.0f);
        const float size = rng.uniform(0.0f, 40.0f);
        std::vector<GridItem> items;
        std::uint32_t id = rng.below(5);
        for (std::uint32_t k = 0; k < n; ++k) {
            id += 1 + rng.below(3);
            Vec2 half{rng.uniform(0.0f, size), rng.uniform(0.0f, size)};
            if (rng.below(50) == 0) half.x *= 100.0f;  // now and then a wall
            // Coordinates on a coarse lattice now and then, so that edges coincide exactly.
            Vec2 centre{rng.uniform(-spread, spread), rng.uniform(-spread, spread)};
            if (rng.below(4) == 0) centre = {std::floor(centre.x / 8.0f) * 8.0f, std::floor(centre.y / 8.0f) * 8.0f};
            if (rng.below(4) == 0) half = {std::floor(half.x), std::floor(half.y)};
            items.push_back({box_at(centre, half), id, rng.below(5) != 0});
        }
        ASSERT_EQ(grid_pairs(grid, items), brute_force(items)) << "scene " << scene << ", " << n << " items";
    }
}

// Thousands of items (the radix sort takes three passes), crowded cells (many boxes much
// smaller than the typical one, in one spot) and big items looked up through a query that
// reports more than it must, twice.
TEST(PairGrid, ManyItemsCrowdedCellsAndBigItemsThroughAQuery) {
    Rng rng(11);
    std::vector<GridItem> items;
    std::uint32_t id = 0;
    for (int k = 0; k < 6000; ++k) {
        const bool crowd = k % 10 == 0;  // tiny boxes piled in one small square
        const Vec2 c = crowd ? Vec2{rng.uniform(0.0f, 3.0f), rng.uniform(0.0f, 3.0f)}
                             : Vec2{rng.uniform(-900.0f, 900.0f), rng.uniform(-900.0f, 900.0f)};
        const Vec2 h = crowd ? Vec2{0.05f, 0.05f} : Vec2{rng.uniform(1.0f, 9.0f), rng.uniform(1.0f, 9.0f)};
        items.push_back({box_at(c, h), id, rng.below(4) != 0});
        id += 1 + rng.below(2);
        if (k % 700 == 0) {  // a long wall now and then
            items.push_back({box_at({rng.uniform(-500.0f, 500.0f), rng.uniform(-900.0f, 900.0f)}, {600, 2}), id, false});
            id += 1;
        }
    }
    const auto expected = brute_force(items);
    PairGrid grid;
    EXPECT_EQ(grid_pairs(grid, items), expected);
    std::vector<GridPair> found;
    grid.find(items, found, [&](const Aabb& box, const std::function<void(std::uint32_t)>& report) {
        for (const GridItem& item : items) {
            // Everything near the box, some twice, and ids that are not items.
            if (item.box.min.x <= box.max.x + 5 && box.min.x - 5 <= item.box.max.x) report(item.id);
            if (item.id % 3 == 0) report(item.id);
        }
        report(0xfffffff0u);
    });
    std::vector<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const GridPair& p : found) got.emplace_back(p.a, p.b);
    EXPECT_EQ(got, expected);
}

// The grid is dense over a crowd (a cell for every spot of the boxes' region) and hashed when
// the boxes are spread thinly (here: the same crowd and one box far away); boxes of up to
// 2 x 2 cells take a branch-free path, larger ones the general one. Every way gives brute
// force's pairs.
TEST(PairGrid, DenseAndHashedGridsAndBoxesOfEveryCellSpan) {
    Rng rng(29);
    std::vector<GridItem> crowd;
    for (std::uint32_t k = 0; k < 3000; ++k) {
        const float size = rng.below(8) == 0 ? 30.0f : 10.0f;  // some span 3 or more cells
        const Vec2 half{rng.uniform(0.0f, size), rng.uniform(0.0f, size)};
        Vec2 centre{rng.uniform(-400.0f, 400.0f), rng.uniform(-400.0f, 400.0f)};
        if (rng.below(4) == 0) centre = {std::floor(centre.x / 8.0f) * 8.0f, std::floor(centre.y / 8.0f) * 8.0f};
        crowd.push_back({box_at(centre, half), 2 * k + 1, rng.below(6) != 0});
    }
    std::vector<GridItem> spread = crowd;
    spread.push_back({box_at({3e7f, -2e7f}, {5, 5}), 1u << 20, true});
    spread.push_back({box_at({3e7f, -2e7f}, {1, 1}), (1u << 20) + 1, false});
    PairGrid grid;
    for (const std::vector<GridItem>* items : {&crowd, &spread, &crowd}) {
        const auto expected = brute_force(*items);
        ASSERT_GT(expected.size(), 1000u);
        EXPECT_EQ(grid_pairs(grid, *items), expected);
    }
}

// Over the broadphase's fat bounds the grid finds what a tree query from each moving body
// finds (the set World::step used to build that way).
TEST(PairGrid, SamePairsAsTreeQueriesOverFatBounds) {
    Rng rng(7);
    for (int scene = 0; scene < 20; ++scene) {
        Broadphase tree;
        std::vector<int> proxy;
        std::vector<bool> moving;
        const std::uint32_t n = 50 + rng.below(300);
        for (std::uint32_t i = 0; i < n; ++i) {
            const float far = scene % 2 ? 1e6f : 400.0f;  // odd scenes spread far, some negative
            const Vec2 c{rng.uniform(-far, far), rng.uniform(-far, 300.0f)};
            const Vec2 h{rng.uniform(0.5f, 12.0f), rng.uniform(0.5f, 12.0f)};
            proxy.push_back(tree.create(box_at(c, h), i));
            moving.push_back(rng.below(3) != 0);
        }
        // Move some of them, so that fat bounds are stretched along their motion.
        for (std::uint32_t i = 0; i < n; ++i) {
            if (!moving[i]) continue;
            const Vec2 d{rng.uniform(-6.0f, 6.0f), rng.uniform(-6.0f, 6.0f)};
            const Aabb fat = tree.fat_bounds(proxy[i]);
            const Vec2 c = 0.5f * (fat.min + fat.max) + d;
            tree.move(proxy[i], box_at(c, {3, 3}), d);
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>> from_tree;
        for (std::uint32_t i = 0; i < n; ++i) {
            if (!moving[i]) continue;
            tree.query(tree.fat_bounds(proxy[i]), [&](std::uint32_t j) {
                if (j == i || (moving[j] && j < i)) return;
                from_tree.emplace_back(std::min(i, j), std::max(i, j));
            });
        }
        std::sort(from_tree.begin(), from_tree.end());
        from_tree.erase(std::unique(from_tree.begin(), from_tree.end()), from_tree.end());

        std::vector<GridItem> items;
        for (std::uint32_t i = 0; i < n; ++i) items.push_back({tree.fat_bounds(proxy[i]), i, moving[i]});
        PairGrid grid;
        ASSERT_EQ(grid_pairs(grid, items), from_tree) << "scene " << scene;
    }
}

}  // namespace
}  // namespace jostle::detail
