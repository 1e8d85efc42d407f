// PairGrid (see pair_grid.h): a uniform grid, dense over a crowd or hashed into buckets, built
// by counting sort; pairs gathered cell by cell, then sorted by their lower item.
#include "pair_grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "jostle/core/error.h"

namespace jostle::detail {

namespace {

// A box in more cells than this is tested against every item instead (a level's long walls).
constexpr std::int64_t kMaxCellsPerItem = 64;
// Cell coordinates are clamped here, far inside int32: clamping keeps the mapping monotonic,
// so overlapping boxes still share a cell (far-away boxes just share more).
constexpr float kMaxCell = 1 << 30;

// A box's cells: floor(coordinate * inverse_size), clamped, in float (any monotonic mapping
// keeps overlapping boxes in a shared cell; cells only decide which pairs are tested).
// Truncation, then one down where that rounded up: exact, as a float beyond 2^23 is whole.
#if defined(__SSE2__)
void cells_of(const Aabb& b, float inverse_size, std::int32_t* cells) {
    float v[4];
    std::memcpy(v, &b, sizeof v);
    const __m128 limit = _mm_set1_ps(kMaxCell);
    const __m128 scaled = _mm_mul_ps(_mm_loadu_ps(v), _mm_set1_ps(inverse_size));
    const __m128 t = _mm_min_ps(_mm_max_ps(scaled, _mm_sub_ps(_mm_setzero_ps(), limit)), limit);
    const __m128i c = _mm_cvttps_epi32(t);
    const __m128i down = _mm_castps_si128(_mm_cmplt_ps(t, _mm_cvtepi32_ps(c)));  // -1 where c > t
    _mm_storeu_si128(reinterpret_cast<__m128i*>(cells), _mm_add_epi32(c, down));
}
#else
void cells_of(const Aabb& b, float inverse_size, std::int32_t* cells) {
    const float v[4] = {b.min.x, b.min.y, b.max.x, b.max.y};
    for (int k = 0; k < 4; ++k) {
        // NaN goes to -kMaxCell, as MAXPS does above (and never reaches the conversion).
        const float s = v[k] * inverse_size;
        const float t = s >= -kMaxCell ? (s <= kMaxCell ? s : kMaxCell) : -kMaxCell;
        const auto c = static_cast<std::int32_t>(t);
        cells[k] = c - static_cast<std::int32_t>(t < static_cast<float>(c));
    }
}
#endif
static_assert(sizeof(Aabb) == 4 * sizeof(float));

// hi - lo for cell coordinates hi >= lo, in unsigned arithmetic: cells reach +-2^30, so the
// difference can exceed int32 (which would be undefined behaviour), never uint32.
std::uint32_t span(std::int32_t hi, std::int32_t lo) {
    return static_cast<std::uint32_t>(hi) - static_cast<std::uint32_t>(lo);
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

// An entry's bits: the item's ordinal below kFirstColumn; whether the cell is in the item's
// first column of cells, its first row; whether the item is active.
constexpr std::uint32_t kFirstColumn = 1u << 29;
constexpr std::uint32_t kFirstRow = 1u << 30;
constexpr std::uint32_t kActive = 1u << 31;
constexpr std::uint32_t kOrdinal = kFirstColumn - 1;

std::uint64_t cell_key(std::int32_t x, std::int32_t y) {
    return std::uint64_t{static_cast<std::uint32_t>(x)} | (std::uint64_t{static_cast<std::uint32_t>(y)} << 32);
}

// Closed overlap, as b2TestOverlap for finite boxes. Not short-circuited: each comparison
// alone is unpredictable, their conjunction nearly always false.
bool touch(const Aabb& a, const Aabb& b) {
    return (a.min.x <= b.max.x) & (b.min.x <= a.max.x) & (a.min.y <= b.max.y) & (b.min.y <= a.max.y);
}

// The same test between a box as `reversed` gives it and one as PairGrid stores it
// (min.x, min.y, -max.x, -max.y): all four lanes of f <= e.
#if defined(__SSE2__)
using Reversed = __m128;
Reversed reversed(const float* v) {  // (max.x, max.y, -min.x, -min.y)
    const __m128 b = _mm_load_ps(v);
    return _mm_xor_ps(_mm_shuffle_ps(b, b, _MM_SHUFFLE(1, 0, 3, 2)), _mm_set1_ps(-0.0f));
}
bool touch(Reversed e, const float* f) { return _mm_movemask_ps(_mm_cmple_ps(_mm_load_ps(f), e)) == 15; }
#else
struct Reversed {
    float v[4];
};
Reversed reversed(const float* v) { return {{-v[2], -v[3], -v[0], -v[1]}}; }
bool touch(const Reversed& e, const float* f) {
    return (f[0] <= e.v[0]) & (f[1] <= e.v[1]) & (f[2] <= e.v[2]) & (f[3] <= e.v[3]);
}
#endif

}  // namespace

void PairGrid::find(std::span<const GridItem> items, std::vector<GridPair>& out) { find(items, out, BigQuery{}); }

void PairGrid::find(std::span<const GridItem> items, std::vector<GridPair>& out, const BigQuery& big_query) {
    const auto n = static_cast<std::uint32_t>(items.size());
    if (n < 2) {
        out.clear();
        return;
    }
    JOSTLE_ASSERT(n <= kOrdinal + 1, "PairGrid: at most 2^29 items");

    // Cell size: 1.5 times a typical box's larger extent. Then each box spans at most four
    // cells unless it is half as large again as typical (those four are filled without a
    // branch on the box's shape, below), and each cell holds a few boxes. Typical: the mean of
    // the extents up to four times the plain mean, so that a few long walls do not set it.
    // (1.0 and 1.25 times were 18% and 3% slower on BM_Broadphase's boxes, 1.75 the same.)
    const auto extent = [&](std::uint32_t i) {  // in double: a finite box can be wider than FLT_MAX
        const Aabb& b = items[i].box;
        const double w = static_cast<double>(b.max.x) - b.min.x;
        const double h = static_cast<double>(b.max.y) - b.min.y;
        return w > h ? w : h;  // not fmax: no NaN here (asserted), and fmax is a call
    };
    double sum = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Aabb& b = items[i].box;
        JOSTLE_ASSERT(std::isfinite(b.min.x) && std::isfinite(b.min.y) && std::isfinite(b.max.x) &&
                          std::isfinite(b.max.y) && b.min.x <= b.max.x && b.min.y <= b.max.y,
                      "PairGrid: boxes must be finite with min <= max");
        JOSTLE_ASSERT(i == 0 || items[i - 1].id < items[i].id, "PairGrid: ids must ascend");
        sum += extent(i);
    }
    const double cap = 4.0 * sum / n;
    double kept_sum = 0.0;
    std::uint32_t kept = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const double e = extent(i);
        if (e <= cap) {
            kept_sum += e;
            ++kept;
        }
    }
    const double size = std::fmax(1.5 * (kept > 0 ? kept_sum / kept : 1.0), 1e-3);
    const auto inverse = static_cast<float>(1.0 / size);

    cells_.resize(n);
    boxes_.resize(n);
    big_.clear();
    std::size_t entry_count = 0;
    constexpr std::int32_t kHigh = std::numeric_limits<std::int32_t>::max();
    constexpr std::int32_t kLow = std::numeric_limits<std::int32_t>::min();
    Cells region{kHigh, kHigh, kLow, kLow};  // the cells the entries are in
    for (std::uint32_t i = 0; i < n; ++i) {
        const Aabb& b = items[i].box;
        boxes_[i] = {{b.min.x, b.min.y, -b.max.x, -b.max.y}};
        std::int32_t at[4];
        cells_of(b, inverse, at);
        Cells& c = cells_[i];
        c = {at[0], at[1], at[2], at[3]};
        const std::int64_t count = (std::int64_t{c.x1} - c.x0 + 1) * (std::int64_t{c.y1} - c.y0 + 1);
        if (count > kMaxCellsPerItem) {
            big_.push_back(i);
            c.x1 = c.x0 - 1;  // in no cell
        } else {
            entry_count += static_cast<std::size_t>(count);
            region = {std::min(region.x0, c.x0), std::min(region.y0, c.y0), std::max(region.x1, c.x1),
                      std::max(region.y1, c.y1)};
        }
    }

    // The pairs among the entries, then big items against every item they may touch (two
    // big ones once, from the lower): looked up through big_query when there is one, else
    // tested against all. Keys are (lower item, higher item) in one integer, sorted at the end.
    const int bits = std::bit_width(n - 1);
    // A dense grid over the entries' region when it has at most about two cells per entry
    // (a crowd), else cells hashed into buckets (boxes spread thinly, far apart).
    const std::int64_t region_cells =
        (std::int64_t{region.x1} - region.x0 + 1) * (std::int64_t{region.y1} - region.y0 + 1);
    const bool dense = entry_count > 0 && region_cells <= 2 * static_cast<std::int64_t>(entry_count) + 64 &&
                       region_cells <= (1 << 30);
    // keys_ is a buffer that only grows (growing a vector zeroes the new part): its first
    // `keys` are the pairs.
    std::size_t keys = dense ? gather<true>(items, entry_count, region, bits)
                             : gather<false>(items, entry_count, region, bits);
    const auto big = [&](std::uint32_t j) { return cells_[j].x0 > cells_[j].x1; };
    const auto pair_with = [&](std::uint32_t i, std::uint32_t j) {
        if (j == i || (j < i && big(j))) return;
        if ((items[i].active || items[j].active) && touch(items[i].box, items[j].box)) {
            if (keys == keys_.size()) keys_.resize(2 * keys + 16);
            keys_[keys++] = i < j ? (std::uint64_t{i} << bits) | j : (std::uint64_t{j} << bits) | i;
        }
    };
    for (const std::uint32_t i : big_) {
        if (!big_query) {
            for (std::uint32_t j = 0; j < n; ++j) pair_with(i, j);
            continue;
        }
        const std::size_t first = keys;
        big_query(items[i].box, [&](std::uint32_t id) {
            const auto it = std::lower_bound(items.begin(), items.end(), id,
                                             [](const GridItem& item, std::uint32_t v) { return item.id < v; });
            if (it != items.end() && it->id == id) pair_with(i, static_cast<std::uint32_t>(it - items.begin()));
        });
        // A query may report an item twice; keep each pair once.
        const auto from = keys_.begin() + static_cast<std::ptrdiff_t>(first);
        const auto to = keys_.begin() + static_cast<std::ptrdiff_t>(keys);
        std::sort(from, to);
        keys = static_cast<std::size_t>(std::unique(from, to) - keys_.begin());
    }
    sort_keys(n, bits, keys);
    out.resize(keys);
    const std::uint64_t low = (std::uint64_t{1} << bits) - 1;
    for (std::size_t k = 0; k < keys; ++k) {
        out[k] = {items[keys_[k] >> bits].id, items[keys_[k] & low].id};
    }
}

// Every entry into its cell (dense: the region's cells in rows; else a hash bucket, which
// may hold several cells), by counting sort so that each lists its entries in ascending item
// order; then the pairs, cell by cell, written to keys_ from 0. Returns how many.
template <bool kDense>
std::size_t PairGrid::gather(std::span<const GridItem> items, std::size_t entry_count, const Cells& region,
                             int bits) {
    const auto n = static_cast<std::uint32_t>(items.size());
    const std::uint32_t width = span(region.x1, region.x0) + 1;  // dense only
    std::uint32_t buckets = 0;
    std::uint32_t mask = 0;
    if constexpr (kDense) {
        buckets = width * (span(region.y1, region.y0) + 1);
    } else {
        // A power of two, about one per entry.
        buckets = static_cast<std::uint32_t>(std::bit_ceil(std::clamp<std::size_t>(entry_count, 16, 1u << 30)));
        mask = buckets - 1;
    }
    const auto bucket_at = [&](std::int32_t x, std::int32_t y) {
        if constexpr (kDense) {
            return span(y, region.y0) * width + span(x, region.x0);
        } else {
            return bucket_of(x, y, mask);
        }
    };
    // A dense grid puts a box of up to 2 x 2 cells (most) in four buckets without a branch
    // on its shape: the cells it lacks go to a spare bucket past the last, never searched.
    const std::uint32_t spare = buckets;
    const auto small = [](const Cells& c) {
        return (span(c.x1, c.x0) | span(c.y1, c.y0)) <= 1;
    };
    const auto four = [&](const Cells& c) {
        const std::uint32_t b = bucket_at(c.x0, c.y0);
        const auto wide = 0u - span(c.x1, c.x0);  // all ones or none
        const auto tall = 0u - span(c.y1, c.y0);
        return std::array<std::uint32_t, 4>{b, spare ^ ((spare ^ (b + 1)) & wide),
                                            spare ^ ((spare ^ (b + width)) & tall),
                                            spare ^ ((spare ^ (b + width + 1)) & wide & tall)};
    };
    starts_.assign(buckets + 2, 0);
    if constexpr (!kDense) bucket_of_entry_.resize(entry_count);
    std::size_t next = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Cells& c = cells_[i];
        if (kDense && small(c)) {
            for (const std::uint32_t b : four(c)) ++starts_[b + 1];
            continue;
        }
        for (std::int32_t y = c.y0; y <= c.y1 && c.x0 <= c.x1; ++y) {
            for (std::int32_t x = c.x0; x <= c.x1; ++x) {
                const std::uint32_t bucket = bucket_at(x, y);
                if constexpr (!kDense) bucket_of_entry_[next++] = bucket;
                ++starts_[bucket + 1];
            }
        }
    }
    for (std::uint32_t k = 0; k <= buckets; ++k) starts_[k + 1] += starts_[k];
    entries_.resize(starts_[buckets + 1]);
    if constexpr (!kDense) entry_cells_.resize(entry_count);
    fill_.assign(starts_.begin(), starts_.end() - 1);
    next = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const Cells& c = cells_[i];
        const std::uint32_t active = items[i].active ? kActive : 0u;
        if (kDense && small(c)) {
            const std::array<std::uint32_t, 4> b = four(c);
            const std::uint32_t item = i | active;
            entries_[fill_[b[0]]++] = item | kFirstColumn | kFirstRow;
            entries_[fill_[b[1]]++] = item | kFirstRow;
            entries_[fill_[b[2]]++] = item | kFirstColumn;
            entries_[fill_[b[3]]++] = item;
            continue;
        }
        for (std::int32_t y = c.y0; y <= c.y1 && c.x0 <= c.x1; ++y) {
            for (std::int32_t x = c.x0; x <= c.x1; ++x) {
                std::uint32_t bucket = 0;
                if constexpr (kDense) {
                    bucket = bucket_at(x, y);
                } else {
                    bucket = bucket_of_entry_[next++];
                }
                const std::uint32_t at = fill_[bucket]++;
                entries_[at] = i | (x == c.x0 ? kFirstColumn : 0u) | (y == c.y0 ? kFirstRow : 0u) | active;
                if constexpr (!kDense) entry_cells_[at] = cell_key(x, y);
            }
        }
    }

    // A pair shows up in every cell both boxes share; it is kept in one, the cell of the
    // corner (max of the mins) where their overlap starts: the shared cell in the first column
    // of one of them and the first row of one of them. The tests are combined without
    // branches (each alone is a coin toss) and every candidate's key is written, the count
    // advancing only for a real pair.
    std::size_t count = 0;
    for (std::uint32_t bucket = 0; bucket < buckets; ++bucket) {
        const std::uint32_t begin = starts_[bucket];
        const std::uint32_t end = starts_[bucket + 1];
        if (end - begin < 2) continue;
        for (std::uint32_t p = begin; p + 1 < end; ++p) {
            // Room for every candidate of this entry (the buffer grows with the pairs found,
            // not with the candidates tested).
            if (keys_.size() < count + (end - p)) keys_.resize(2 * (count + (end - p)));
            const std::uint32_t e = entries_[p];
            const Reversed e_box = reversed(boxes_[e & kOrdinal].v);
            const std::uint64_t high = std::uint64_t{e & kOrdinal} << bits;
            for (std::uint32_t q = p + 1; q < end; ++q) {
                const std::uint32_t f = entries_[q];
                constexpr std::uint32_t kAll = kFirstColumn | kFirstRow | kActive;
                bool here = ((e | f) & kAll) == kAll;
                if constexpr (!kDense) here &= entry_cells_[p] == entry_cells_[q];
                const bool hit = touch(e_box, boxes_[f & kOrdinal].v);
                keys_[count] = high | (f & kOrdinal);
                count += static_cast<std::size_t>(here & hit);
            }
        }
    }
    return count;
}

// The first `count` keys_ in order: counting sort by the lower item, then an insertion
// sort, which only has to order each item's few partners (bounded: a crowd's long runs go to
// std::sort instead).
void PairGrid::sort_keys(std::uint32_t n, int bits, std::size_t count) {
    const auto end = keys_.begin() + static_cast<std::ptrdiff_t>(count);
    if (count < 256) {
        std::sort(keys_.begin(), end);
        return;
    }
    fill_.assign(n + 1, 0);
    for (std::size_t k = 0; k < count; ++k) ++fill_[(keys_[k] >> bits) + 1];
    for (std::uint32_t i = 0; i < n; ++i) fill_[i + 1] += fill_[i];
    if (sorted_.size() < keys_.size()) sorted_.resize(keys_.size());
    for (std::size_t k = 0; k < count; ++k) sorted_[fill_[keys_[k] >> bits]++] = keys_[k];
    keys_.swap(sorted_);
    std::size_t moves = 0;
    for (std::size_t k = 1; k < count; ++k) {
        const std::uint64_t key = keys_[k];
        if (keys_[k - 1] <= key) continue;
        std::size_t m = k;
        for (; m > 0 && keys_[m - 1] > key; --m) keys_[m] = keys_[m - 1];
        keys_[m] = key;
        moves += k - m;
        if (moves > 4 * count) {
            std::sort(keys_.begin(), keys_.begin() + static_cast<std::ptrdiff_t>(count));
            return;
        }
    }
}

}  // namespace jostle::detail
