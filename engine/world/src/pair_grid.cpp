// PairGrid (see pair_grid.h): a uniform grid hashed into buckets, built by counting sort, then
// pairs gathered item by item so that they come out sorted without sorting them all.
#include "pair_grid.h"

#include <algorithm>
#include <cmath>

namespace jostle::detail {

namespace {

// A box in more cells than this is tested against every item instead (a level's long walls).
constexpr std::int64_t kMaxCellsPerItem = 64;
// Cell coordinates are clamped here, far inside int32: clamping keeps the mapping monotonic,
// so overlapping boxes still share a cell (far-away boxes just share more).
constexpr double kMaxCell = 1 << 30;

std::int32_t cell_of(float v, double inverse_size) {
    const double c = std::floor(static_cast<double>(v) * inverse_size);
    return static_cast<std::int32_t>(std::clamp(c, -kMaxCell, kMaxCell));
}

// Neighbouring cells land in unrelated buckets (a multiplicative hash, then its high bits
// mixed down).
std::uint32_t bucket_of(std::int32_t x, std::int32_t y, std::uint32_t mask) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 0x9E3779B1u + static_cast<std::uint32_t>(y) * 0x85EBCA77u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    return h & mask;
}

// Closed overlap, as b2TestOverlap for finite boxes. Not short-circuited: each comparison
// alone is unpredictable, their conjunction nearly always false.
bool touch(const Aabb& a, const Aabb& b) {
    return (a.min.x <= b.max.x) & (b.min.x <= a.max.x) & (a.min.y <= b.max.y) & (b.min.y <= a.max.y);
}

}  // namespace

void PairGrid::find(std::span<const GridItem> items, std::vector<GridPair>& out) {
    out.clear();
    const auto n = static_cast<std::uint32_t>(items.size());
    if (n < 2) return;

    // Cell size: the median of the boxes' larger extents. With cells as large as a typical
    // box, each box spans about four cells and each cell holds about as many boxes as touch
    // one; the median ignores a few long walls.
    std::vector<float>& extents = scratch_;
    extents.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const Aabb& b = items[i].box;
        extents[i] = std::fmax(b.max.x - b.min.x, b.max.y - b.min.y);
    }
    std::nth_element(extents.begin(), extents.begin() + n / 2, extents.end());
    const float size = std::fmax(extents[n / 2], 1e-3f);
    const double inverse_size = 1.0 / static_cast<double>(size);

    cells_.resize(n);
    big_.clear();
    std::size_t entry_count = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Aabb& b = items[i].box;
        Cells& c = cells_[i];
        c = {cell_of(b.min.x, inverse_size), cell_of(b.min.y, inverse_size), cell_of(b.max.x, inverse_size),
             cell_of(b.max.y, inverse_size)};
        const std::int64_t count = (std::int64_t{c.x1} - c.x0 + 1) * (std::int64_t{c.y1} - c.y0 + 1);
        if (count > kMaxCellsPerItem) {
            big_.push_back(i);
            c.x1 = c.x0 - 1;  // in no cell
        } else {
            entry_count += static_cast<std::size_t>(count);
        }
    }

    // Buckets: a power of two, at least twice the entries, filled by counting sort so that
    // each bucket lists its items in ascending order.
    std::uint32_t buckets = 16;
    while (buckets < 2 * entry_count) buckets *= 2;
    const std::uint32_t mask = buckets - 1;
    starts_.assign(buckets + 1, 0);
    const auto for_each_cell = [&](std::uint32_t i, auto&& f) {
        const Cells& c = cells_[i];
        for (std::int32_t y = c.y0; y <= c.y1 && c.x0 <= c.x1; ++y) {
            for (std::int32_t x = c.x0; x <= c.x1; ++x) f(x, y);
        }
    };
    for (std::uint32_t i = 0; i < n; ++i) {
        for_each_cell(i, [&](std::int32_t x, std::int32_t y) { ++starts_[bucket_of(x, y, mask) + 1]; });
    }
    for (std::uint32_t k = 0; k < buckets; ++k) starts_[k + 1] += starts_[k];
    entries_.resize(entry_count);
    found_.assign(starts_.begin(), starts_.end() - 1);  // fill positions, reused below
    for (std::uint32_t i = 0; i < n; ++i) {
        for_each_cell(i, [&](std::int32_t x, std::int32_t y) { entries_[found_[bucket_of(x, y, mask)]++] = {x, y, i}; });
    }

    // Pairs, item by item: a pair shows up in every cell both boxes share; it is kept in one,
    // the cell of the corner (max of the mins) where their overlap starts.
    for (std::uint32_t i = 0; i < n; ++i) {
        const GridItem& a = items[i];
        const Cells& ca = cells_[i];
        found_.clear();
        const auto consider = [&](std::uint32_t j) {
            if ((a.active || items[j].active) && touch(a.box, items[j].box)) found_.push_back(j);
        };
        if (ca.x0 > ca.x1) {  // a big item: against every later one
            for (std::uint32_t j = i + 1; j < n; ++j) consider(j);
        } else {
            for_each_cell(i, [&](std::int32_t x, std::int32_t y) {
                const std::uint32_t bucket = bucket_of(x, y, mask);
                for (std::uint32_t e = starts_[bucket]; e < starts_[bucket + 1]; ++e) {
                    const Entry& entry = entries_[e];
                    const std::uint32_t j = entry.item;
                    if (j <= i || entry.x != x || entry.y != y) continue;
                    const Cells& cb = cells_[j];
                    if (std::max(ca.x0, cb.x0) != x || std::max(ca.y0, cb.y0) != y) continue;
                    consider(j);
                }
            });
            for (const std::uint32_t j : big_) {
                if (j > i) consider(j);
            }
        }
        std::sort(found_.begin(), found_.end());
        for (const std::uint32_t j : found_) out.push_back({a.id, items[j].id});
    }
}

}  // namespace jostle::detail
