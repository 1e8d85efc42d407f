// The broadphase: each collider's fat bounds, and Box2D's b2DynamicTree over them for region
// queries. Proxies hold fattened bounds and are re-fattened only when a collider's tight
// bounds leave them. The only file pair in jostle that includes Box2D (besides the
// differential tests).
//
// The fat bounds live in a flat array, the truth every caller reads; the tree is an index
// over them that catches up only when a query needs it. A step moves thousands of bodies and
// may query nothing (the candidate pairs come from the grid, pair_grid.h), so moving a proxy
// is an array write. And a step's few queries (the sweeps of its fast bodies) scan the array
// rather than pay for re-inserting every proxy that moved since the last: a query scans
// while the scans since the tree last caught up cost less than catching up would (about
// kScanPerInsert box tests a re-insertion), then catches up. Like renting skis until the
// rent would have bought them, neither a few queries among many moves nor many queries
// among few moves pay more than about twice the better choice.
#pragma once

#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <box2d/b2_dynamic_tree.h>

#include "jostle/collision.h"

namespace jostle::detail {

class Broadphase {
public:
    // Fat bounds margin in pixels. Box2D's own b2_aabbExtension is 0.1 length units, tuned for
    // metres; in pixels a resting or slowly moving body would be re-fattened almost every
    // step. 1 px: a body is re-fattened after a pixel of drift (cheap: the fat bounds are an
    // array, the tree catches up only when queried), and its candidates are the bodies within
    // about 2 px, enough for a kept contact's 1 px gap. 2 px gave a crowd of 3-20 px bodies
    // twice the pairs (the 10,000-body stress scene: 13% more time a step, in every phase that
    // walks the pairs).
    static constexpr float kMargin = 1.0f;
    // Box tests a scanning query may spend per proxy waiting for the tree, before catching
    // up is cheaper: a re-insertion descends and rebalances the tree (110-175 ns at 2,000 to
    // 20,000 proxies with the tree in cache), a scan tests a box in 0.9 ns, so one
    // re-insertion costs 120-210 box tests, and more when the tree is out of cache, as it is
    // by the time a step queries it. (The world stress scene's 1,120 steps at 2,000 bodies, a
    // few queries a step, ran 6.63 G instructions with 128, 6.22 G with 256, 6.01 G with 512
    // and 5.91 G with 1,024; many queries a step would lose by larger values.) 0: never scan.
    static constexpr std::size_t kScanPerInsert = 256;
    explicit Broadphase(std::size_t scan_per_insert = kScanPerInsert) : scan_per_insert_(scan_per_insert) {}

    // Bounds beyond this (or not finite) get no proxy: such a collider meets nothing.
    static bool usable(const Aabb& tight);

    int create(const Aabb& tight, std::uint32_t index);  // usable(tight) required
    void destroy(int proxy);
    // Keeps the proxy when `tight` is still inside its fat bounds; otherwise re-fattens it by
    // a margin, stretched along `displacement` (this step's motion). True when it re-fattened.
    bool move(int proxy, const Aabb& tight, Vec2 displacement) {
        const Aabb& fat = fat_[static_cast<std::size_t>(proxy)];
        if (fat.min.x <= tight.min.x && fat.min.y <= tight.min.y && tight.max.x <= fat.max.x &&
            tight.max.y <= fat.max.y) {
            return false;
        }
        refatten(proxy, tight, displacement);
        return true;
    }
    Aabb fat_bounds(int proxy) const { return fat_[static_cast<std::size_t>(proxy)]; }
    // The test query() applies to fat bounds: whether `fat` overlaps `box` (touching counts).
    static bool overlap(const Aabb& fat, const Aabb& box) { return overlap_lanes(fat, lanes(box)); }

    // How the queries that found the tree behind went: scanned, or caught it up (for tests;
    // read while no query runs).
    struct Counts {
        std::size_t scans = 0;
        std::size_t catch_ups = 0;
    };
    Counts counts() const { return counts_; }

    // Calls f(index) for every proxy whose fat bounds overlap `box` (touching counts), in
    // no promised order: callers sort what they keep. Safe to call from several threads at
    // once (the tree's catching up is locked), not alongside the changes above.
    template <typename F>
    void query(const Aabb& box, F&& f) const {
        if (behind_.load(std::memory_order_acquire) && !catch_up_or_scan(finite(box))) {
            // The scan, 64 proxies at a time: their tests into a word of bits without a
            // branch, then a call for each bit set. A free proxy's bounds are kFree, which no
            // finite box touches.
            const std::size_t n = fat_.size();
            const Lanes q = lanes(box);
            for (std::size_t base = 0; base < n; base += 64) {
                const std::size_t count = n - base < 64 ? n - base : 64;
                std::uint64_t hits = 0;
                for (std::size_t i = 0; i < count; ++i) hits |= std::uint64_t{overlap_lanes(fat_[base + i], q)} << i;
                for (; hits != 0; hits &= hits - 1) f(proxies_[base + static_cast<std::size_t>(std::countr_zero(hits))].index);
            }
            return;
        }
        struct Callback {
            const Broadphase* self;
            Lanes box;
            F* f;
            bool QueryCallback(std::int32_t node) {
                const auto proxy = reinterpret_cast<std::uintptr_t>(self->tree_.GetUserData(node));
                // The tree's boxes are a little larger than the fat bounds (it adds its own
                // margin): the answer is the fat bounds' own test, as b2TestOverlap writes it.
                if (overlap_lanes(self->fat_[proxy], box)) (*f)(self->proxies_[proxy].index);
                return true;
            }
        } callback{this, lanes(box), &f};
        tree_.Query(&callback, to_b2(box));
    }

private:
    // The bounds of a free proxy number: inside out, so that no finite box overlaps them.
    static constexpr Aabb kFree{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
    struct Proxy {  // all but the fat bounds, which fat_ packs for the scans
        std::uint32_t index = 0;  // the caller's (the World's slot)
        bool live = false;
        // The tree's bookkeeping, which catch_up (under const queries) changes:
        mutable bool queued = false;      // in queued_: the tree's node is behind `fat`
        mutable std::int32_t node = -1;   // in the tree; -1 before it first catches up
    };
    // Whether a and b overlap (touching counts) as b2TestOverlap decides it: none of
    // b.min - a.max and a.min - b.max is > 0 on either axis (a NaN difference is not, so a
    // NaN box meets everything). The four differences side by side, each lane the scalar
    // subtraction, b given in lanes: a scan runs without a branch a proxy.
    using Lanes = float __attribute__((vector_size(16)));
    static Lanes lanes(const Aabb& box) { return Lanes{box.min.x, box.min.y, box.max.x, box.max.y}; }
    using LaneBits = std::int32_t __attribute__((vector_size(16)));
    static bool overlap_lanes(const Aabb& a, Lanes b) {
        Lanes f;
        static_assert(sizeof(Aabb) == sizeof(Lanes));
        std::memcpy(&f, &a, sizeof f);
        // {b.min.x - a.max.x, b.min.y - a.max.y, a.min.x - b.max.x, a.min.y - b.max.y} > 0
        const LaneBits apart = __builtin_shufflevector(b, f, 0, 1, 4, 5) - __builtin_shufflevector(f, b, 2, 3, 6, 7) >
                               Lanes{0.0f, 0.0f, 0.0f, 0.0f};
#if defined(__SSE__)
        return _mm_movemask_ps(reinterpret_cast<__m128>(apart)) == 0;
#else
        return ((apart[0] | apart[1]) | (apart[2] | apart[3])) == 0;
#endif
    }
    static bool finite(const Aabb& box) {
        return std::isfinite(box.min.x) && std::isfinite(box.min.y) && std::isfinite(box.max.x) &&
               std::isfinite(box.max.y);
    }
    static b2AABB to_b2(const Aabb& box);
    static Aabb fatten(const Aabb& tight, Vec2 displacement);
    void refatten(int proxy, const Aabb& tight, Vec2 displacement);
    void enqueue(int proxy);
    // Under the lock: true when the tree is up to date (it caught up, here or in another
    // query), false when this query should scan instead (counted as scanned; only when
    // `may_scan`: the scan answers finite boxes).
    bool catch_up_or_scan(bool may_scan) const;

    std::vector<Aabb> fat_;  // by proxy number, kFree when free
    std::vector<Proxy> proxies_;
    std::vector<int> free_;  // proxy numbers to reuse, last-in first-out
    std::size_t scan_per_insert_;
    // The tree and its backlog change under const queries (catch_up), behind the lock.
    mutable std::vector<int> queued_;
    mutable std::size_t queued_live_ = 0;  // of queued_, those still live (what catching up costs)
    mutable std::size_t scanned_ = 0;  // proxy numbers scanned since the tree last caught up
    mutable Counts counts_;
    mutable b2DynamicTree tree_;
    mutable std::atomic<bool> behind_{false};
    mutable std::mutex catching_up_;
};

}  // namespace jostle::detail
