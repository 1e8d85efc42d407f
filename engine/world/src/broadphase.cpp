// The broadphase wrapper over b2DynamicTree (see broadphase.h).
#include "broadphase.h"

#include <cmath>

namespace jostle::detail {

namespace {
// Fat bounds margin in pixels. Box2D's own b2_aabbExtension is 0.1 length units, tuned for
// metres; in pixels a resting or slowly moving body would be re-inserted almost every step.
constexpr float kMargin = 2.0f;
// Tree bounds stay far inside float range so the tree's area heuristics stay finite.
constexpr float kFar = 1e12f;
}  // namespace

bool Broadphase::usable(const Aabb& tight) {
    const auto ok = [](float v) { return std::isfinite(v) && std::fabs(v) <= kFar; };
    return ok(tight.min.x) && ok(tight.min.y) && ok(tight.max.x) && ok(tight.max.y) &&
           tight.min.x <= tight.max.x && tight.min.y <= tight.max.y;
}

b2AABB Broadphase::to_b2(const Aabb& box) {
    b2AABB out;
    out.lowerBound.Set(box.min.x, box.min.y);
    out.upperBound.Set(box.max.x, box.max.y);
    return out;
}

Aabb Broadphase::fatten(const Aabb& tight, Vec2 displacement) {
    Aabb fat{{tight.min.x - kMargin, tight.min.y - kMargin}, {tight.max.x + kMargin, tight.max.y + kMargin}};
    // Stretch along the motion (as Box2D does with b2_aabbMultiplier), bounded so a fast
    // body does not drag a huge box around.
    const auto stretch = [](float d) { return std::fmin(std::fabs(2.0f * d), 256.0f); };
    if (displacement.x > 0.0f) fat.max.x += stretch(displacement.x);
    if (displacement.x < 0.0f) fat.min.x -= stretch(displacement.x);
    if (displacement.y > 0.0f) fat.max.y += stretch(displacement.y);
    if (displacement.y < 0.0f) fat.min.y -= stretch(displacement.y);
    return fat;
}

int Broadphase::create(const Aabb& tight, std::uint32_t index) {
    return tree_.CreateProxy(to_b2(fatten(tight, {})), reinterpret_cast<void*>(static_cast<std::uintptr_t>(index)));
}

void Broadphase::destroy(int proxy) { tree_.DestroyProxy(proxy); }

void Broadphase::move(int proxy, const Aabb& tight, Vec2 displacement) {
    const b2AABB& fat = tree_.GetFatAABB(proxy);
    if (fat.lowerBound.x <= tight.min.x && fat.lowerBound.y <= tight.min.y && tight.max.x <= fat.upperBound.x &&
        tight.max.y <= fat.upperBound.y) {
        return;
    }
    // MoveProxy re-inserts whenever the given box is not inside the tree's; ours never is.
    tree_.MoveProxy(proxy, to_b2(fatten(tight, displacement)), b2Vec2(0.0f, 0.0f));
}

Aabb Broadphase::fat_bounds(int proxy) const {
    const b2AABB& fat = tree_.GetFatAABB(proxy);
    return {{fat.lowerBound.x, fat.lowerBound.y}, {fat.upperBound.x, fat.upperBound.y}};
}

}  // namespace jostle::detail
