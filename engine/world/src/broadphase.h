// The broadphase: each collider's fat bounds, and Box2D's b2DynamicTree over them for region
// queries. Proxies hold fattened bounds and are re-fattened only when a collider's tight
// bounds leave them. The only file pair in jostle that includes Box2D (besides the
// differential tests).
//
// The fat bounds live in a flat array, the truth every caller reads; the tree is an index
// over them that catches up only when a query needs it. A step moves thousands of bodies and
// may query nothing (the candidate pairs come from the grid, pair_grid.h), so moving a proxy
// is an array write, and the tree's re-insertions happen once per proxy per query round,
// not at every move.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include <box2d/b2_dynamic_tree.h>

#include "jostle/collision.h"

namespace jostle::detail {

class Broadphase {
public:
    // Bounds beyond this (or not finite) get no proxy: such a collider meets nothing.
    static bool usable(const Aabb& tight);

    int create(const Aabb& tight, std::uint32_t index);  // usable(tight) required
    void destroy(int proxy);
    // Keeps the proxy when `tight` is still inside its fat bounds; otherwise re-fattens it by
    // a margin, stretched along `displacement` (this step's motion).
    void move(int proxy, const Aabb& tight, Vec2 displacement) {
        const Aabb& fat = proxies_[static_cast<std::size_t>(proxy)].fat;
        if (fat.min.x <= tight.min.x && fat.min.y <= tight.min.y && tight.max.x <= fat.max.x &&
            tight.max.y <= fat.max.y) {
            return;
        }
        refatten(proxy, tight, displacement);
    }
    Aabb fat_bounds(int proxy) const { return proxies_[static_cast<std::size_t>(proxy)].fat; }

    // Calls f(index) for every proxy whose fat bounds overlap `box` (touching counts), in
    // no promised order: callers sort what they keep. Safe to call from several threads at
    // once (the tree's catching up is locked), not alongside the changes above.
    template <typename F>
    void query(const Aabb& box, F&& f) const {
        if (behind_.load(std::memory_order_acquire)) catch_up();
        struct Callback {
            const Broadphase* self;
            const Aabb* box;
            F* f;
            bool QueryCallback(std::int32_t node) {
                const auto proxy = reinterpret_cast<std::uintptr_t>(self->tree_.GetUserData(node));
                const Proxy& p = self->proxies_[proxy];
                // The tree's boxes are a little larger than the fat bounds (it adds its own
                // margin): the answer is the fat bounds' own test, as b2TestOverlap writes it.
                if (overlap(p.fat, *box)) (*f)(p.index);
                return true;
            }
        } callback{this, &box, &f};
        tree_.Query(&callback, to_b2(box));
    }

private:
    struct Proxy {
        Aabb fat;
        std::uint32_t index = 0;  // the caller's (the World's slot)
        bool live = false;
        // The tree's bookkeeping, which catch_up (under const queries) changes:
        mutable bool queued = false;      // in queued_: the tree's node is behind `fat`
        mutable std::int32_t node = -1;   // in the tree; -1 before it first catches up
    };
    static bool overlap(const Aabb& a, const Aabb& b) {
        return !(b.min.x - a.max.x > 0.0f || b.min.y - a.max.y > 0.0f || a.min.x - b.max.x > 0.0f ||
                 a.min.y - b.max.y > 0.0f);
    }
    static b2AABB to_b2(const Aabb& box);
    static Aabb fatten(const Aabb& tight, Vec2 displacement);
    void refatten(int proxy, const Aabb& tight, Vec2 displacement);
    void enqueue(int proxy);
    void catch_up() const;  // re-inserts the queued proxies into the tree

    std::vector<Proxy> proxies_;
    std::vector<int> free_;  // proxy numbers to reuse, last-in first-out
    // The tree and its backlog change under const queries (catch_up), behind the lock.
    mutable std::vector<int> queued_;
    mutable b2DynamicTree tree_;
    mutable std::atomic<bool> behind_{false};
    mutable std::mutex catching_up_;
};

}  // namespace jostle::detail
