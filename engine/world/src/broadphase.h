// The broadphase: Box2D's b2DynamicTree behind a small interface. Proxies hold fattened
// bounds and are re-inserted only when a collider's tight bounds leave them. The only file
// pair in jostle that includes Box2D (besides the differential tests).
#pragma once

#include <cstdint>
#include <box2d/b2_dynamic_tree.h>

#include "jostle/collision.h"

namespace jostle::detail {

class Broadphase {
public:
    // Bounds beyond this (or not finite) get no proxy: such a collider meets nothing.
    static bool usable(const Aabb& tight);

    int create(const Aabb& tight, std::uint32_t index);  // usable(tight) required
    void destroy(int proxy);
    // Keeps the proxy when `tight` is still inside its fat bounds; otherwise re-inserts it,
    // fattened by a margin and stretched along `displacement` (this step's motion).
    void move(int proxy, const Aabb& tight, Vec2 displacement);
    Aabb fat_bounds(int proxy) const;

    // Calls f(index) for every proxy whose fat bounds overlap `box` (in tree order; callers
    // sort what they keep).
    template <typename F>
    void query(const Aabb& box, F&& f) const {
        struct Callback {
            const b2DynamicTree* tree;
            F* f;
            bool QueryCallback(std::int32_t proxy) {
                (*f)(static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(tree->GetUserData(proxy))));
                return true;
            }
        } callback{&tree_, &f};
        tree_.Query(&callback, to_b2(box));
    }

private:
    static b2AABB to_b2(const Aabb& box);
    static Aabb fatten(const Aabb& tight, Vec2 displacement);
    b2DynamicTree tree_;
};

}  // namespace jostle::detail
