// The broadphase's fat bounds and the b2DynamicTree over them (see broadphase.h).
#include "broadphase.h"

#include <cmath>

namespace jostle::detail {

namespace {
// Tree bounds stay far inside float range so the tree's area heuristics stay finite.
constexpr float kFar = 1e12f;
}  // namespace

bool Broadphase::usable(const Aabb& tight) {
    // |v| <= kFar is false for NaN and the infinities too. The tests are combined as
    // integers with & rather than &&: one test, no branch per coordinate (every body's
    // bounds are asked each step).
    const auto ok = [](float v) -> unsigned { return std::fabs(v) <= kFar; };
    const auto ordered = [](float lo, float hi) -> unsigned { return lo <= hi; };
    return (ok(tight.min.x) & ok(tight.min.y) & ok(tight.max.x) & ok(tight.max.y) & ordered(tight.min.x, tight.max.x) &
            ordered(tight.min.y, tight.max.y)) != 0;
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
    // And b2_aabbExtension on every side, as the tree adds it to what it is given: the fat
    // bounds were the tree's own boxes until the tree became a lazy index, and the candidate
    // pairs (and so every recorded scenario) depend on them to the last bit.
    fat.min.x -= b2_aabbExtension;
    fat.min.y -= b2_aabbExtension;
    fat.max.x += b2_aabbExtension;
    fat.max.y += b2_aabbExtension;
    return fat;
}

int Broadphase::create(const Aabb& tight, std::uint32_t index) {
    int proxy;
    if (free_.empty()) {
        proxy = static_cast<int>(proxies_.size());
        proxies_.emplace_back();
        fat_.push_back(kFree);
    } else {
        proxy = free_.back();
        free_.pop_back();
    }
    Proxy& p = proxies_[static_cast<std::size_t>(proxy)];
    fat_[static_cast<std::size_t>(proxy)] = fatten(tight, {});
    p.index = index;
    p.node = -1;
    p.live = true;
    if (p.queued) {
        ++queued_live_;  // a number destroyed while queued: in queued_ already, live again
        behind_.store(true, std::memory_order_relaxed);
    } else {
        enqueue(proxy);
    }
    return proxy;
}

void Broadphase::destroy(int proxy) {
    Proxy& p = proxies_[static_cast<std::size_t>(proxy)];
    if (p.node >= 0) tree_.DestroyProxy(p.node);
    p.node = -1;
    p.live = false;  // catch_up skips it if it is still queued
    if (p.queued) --queued_live_;
    fat_[static_cast<std::size_t>(proxy)] = kFree;
    free_.push_back(proxy);
}

void Broadphase::refatten(int proxy, const Aabb& tight, Vec2 displacement) {
    fat_[static_cast<std::size_t>(proxy)] = fatten(tight, displacement);
    enqueue(proxy);
}

void Broadphase::enqueue(int proxy) {
    Proxy& p = proxies_[static_cast<std::size_t>(proxy)];
    if (!p.queued) {
        p.queued = true;
        queued_.push_back(proxy);
        ++queued_live_;
    }
    behind_.store(true, std::memory_order_relaxed);  // changes never race with queries
}

bool Broadphase::catch_up_or_scan(bool may_scan) const {
    const std::lock_guard lock(catching_up_);
    if (!behind_.load(std::memory_order_relaxed)) return true;  // another query caught up first
    // A scan walks every proxy number, free ones too; catching up costs a re-insertion for
    // each queued proxy still live (a destroyed one left the tree at once).
    const std::size_t scan = fat_.size();
    if (may_scan && scan_per_insert_ > 0 && scanned_ + scan <= scan_per_insert_ * queued_live_) {
        scanned_ += scan;
        ++counts_.scans;
        return false;
    }
    ++counts_.catch_ups;
    for (const int proxy : queued_) {
        const Proxy& p = proxies_[static_cast<std::size_t>(proxy)];
        p.queued = false;
        if (!p.live) continue;
        void* user_data = reinterpret_cast<void*>(static_cast<std::uintptr_t>(proxy));
        // The node contains the fat bounds, so a query finds every proxy the fat bounds' own
        // test accepts: the tree makes the node the given box plus b2_aabbExtension, or keeps
        // the node it has when that still contains the given box (MoveProxy returns early
        // when the node holds the box and is not much larger: say a rod turned tall and back
        // between two queries).
        if (p.node < 0) {
            p.node = tree_.CreateProxy(to_b2(fat_[static_cast<std::size_t>(proxy)]), user_data);
        } else {
            tree_.MoveProxy(p.node, to_b2(fat_[static_cast<std::size_t>(proxy)]), b2Vec2(0.0f, 0.0f));
        }
    }
    queued_.clear();
    queued_live_ = 0;
    scanned_ = 0;
    behind_.store(false, std::memory_order_release);
    return true;
}

}  // namespace jostle::detail
