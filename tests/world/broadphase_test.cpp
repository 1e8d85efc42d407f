// Broadphase (engine/world/src/broadphase.h, private): the fat bounds live in a flat array and
// the b2DynamicTree over them catches up only when queried. Checked here:
// - the fat bounds are, to the bit, those of a b2DynamicTree driven the way the broadphase
//   drove it before it went lazy (the candidate pairs, and so every recorded scenario, depend
//   on them);
// - every query answers exactly the proxies whose fat bounds overlap the box (touching
//   counts), however creates, moves, destroys and reuses of proxy numbers interleave with
//   queries, whether the queries catch the tree up at once, scan the bounds while it waits,
//   or (the default) do either as it costs;
// - const queries from two threads at once, right after changes, both answer right. (Under
//   ThreadSanitizer, the tsan preset: Box2D is the system's uninstrumented build, so the
//   tree's own reads and writes are not watched, but the broadphase's backlog and counters
//   around them are, and removing the catch-up lock fails there.)
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include <box2d/b2_dynamic_tree.h>

#include "broadphase.h"  // engine/world/src (private)
#include "jostle/core/rng.h"

namespace jostle::detail {
namespace {

Aabb box_at(Vec2 c, Vec2 h) { return {c - h, c + h}; }

// Box2D's b2TestOverlap, the test the tree's queries have always answered.
bool b2_overlap(const Aabb& a, const Aabb& b) {
    return !(b.min.x - a.max.x > 0.0f || b.min.y - a.max.y > 0.0f || a.min.x - b.max.x > 0.0f ||
             a.min.y - b.max.y > 0.0f);
}

bool same_bits(const Aabb& a, const Aabb& b) {
    const auto bits = [](float v) { return std::bit_cast<std::uint32_t>(v); };
    return bits(a.min.x) == bits(b.min.x) && bits(a.min.y) == bits(b.min.y) && bits(a.max.x) == bits(b.max.x) &&
           bits(a.max.y) == bits(b.max.y);
}

// The broadphase as it was before the tree went lazy: every move checked against the tree's
// own fat box and re-inserted at once (kMargin, stretched by twice the motion up to 256
// px; the tree adds b2_aabbExtension itself).
class EagerTree {
public:
    int create(const Aabb& tight) { return tree_.CreateProxy(to_b2(fatten(tight, {})), nullptr); }
    void destroy(int proxy) { tree_.DestroyProxy(proxy); }
    void move(int proxy, const Aabb& tight, Vec2 d) {
        const Aabb fat = fat_bounds(proxy);
        if (fat.min.x <= tight.min.x && fat.min.y <= tight.min.y && tight.max.x <= fat.max.x &&
            tight.max.y <= fat.max.y) {
            return;
        }
        tree_.MoveProxy(proxy, to_b2(fatten(tight, d)), b2Vec2(0.0f, 0.0f));
    }
    Aabb fat_bounds(int proxy) const {
        const b2AABB& f = tree_.GetFatAABB(proxy);
        return {{f.lowerBound.x, f.lowerBound.y}, {f.upperBound.x, f.upperBound.y}};
    }

private:
    static b2AABB to_b2(const Aabb& box) {
        b2AABB out;
        out.lowerBound.Set(box.min.x, box.min.y);
        out.upperBound.Set(box.max.x, box.max.y);
        return out;
    }
    static Aabb fatten(const Aabb& tight, Vec2 d) {
        constexpr float m = detail::Broadphase::kMargin;
        Aabb fat{{tight.min.x - m, tight.min.y - m}, {tight.max.x + m, tight.max.y + m}};
        const auto stretch = [](float v) { return std::fmin(std::fabs(2.0f * v), 256.0f); };
        if (d.x > 0.0f) fat.max.x += stretch(d.x);
        if (d.x < 0.0f) fat.min.x -= stretch(d.x);
        if (d.y > 0.0f) fat.max.y += stretch(d.y);
        if (d.y < 0.0f) fat.min.y -= stretch(d.y);
        return fat;
    }
    b2DynamicTree tree_;
};

struct Body {
    int proxy = -1;  // in the Broadphase
    int eager = -1;  // in the EagerTree
    Vec2 centre;
    Vec2 half;
};

std::vector<std::uint32_t> query_sorted(const Broadphase& bp, const Aabb& box) {
    std::vector<std::uint32_t> got;
    bp.query(box, [&](std::uint32_t i) { got.push_back(i); });
    std::sort(got.begin(), got.end());
    return got;
}

std::vector<std::uint32_t> expected_hits(const Broadphase& bp, const std::vector<Body>& bodies, const Aabb& box) {
    std::vector<std::uint32_t> want;
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].proxy >= 0 && b2_overlap(bp.fat_bounds(bodies[i].proxy), box)) want.push_back(i);
    }
    return want;
}

class BroadphaseScanning : public ::testing::TestWithParam<std::size_t> {};

TEST_P(BroadphaseScanning, FatBoundsAndQueriesMatchTheEagerTreeThroughAnyInterleaving) {
    Rng rng(17);
    for (int scene = 0; scene < 12; ++scene) {
        Broadphase bp(GetParam());
        EagerTree eager;
        std::vector<Body> bodies(200 + rng.below(200));
        const float spread = scene % 3 == 0 ? 5e5f : 300.0f;  // some scenes far from the origin
        for (std::uint32_t i = 0; i < bodies.size(); ++i) {
            Body& b = bodies[i];
            b.centre = {rng.uniform(-spread, spread), rng.uniform(-spread, spread)};
            b.half = {rng.uniform(0.5f, 10.0f), rng.uniform(0.5f, 10.0f)};
            if (rng.below(4) == 0) continue;  // created later
            b.proxy = bp.create(box_at(b.centre, b.half), i);
            b.eager = eager.create(box_at(b.centre, b.half));
        }
        for (int round = 0; round < 60; ++round) {
            for (std::uint32_t i = 0; i < bodies.size(); ++i) {
                Body& b = bodies[i];
                const std::uint32_t what = rng.below(20);
                if (b.proxy < 0) {
                    if (what < 3) {  // (re)create: may reuse a number still waiting for the tree
                        b.proxy = bp.create(box_at(b.centre, b.half), i);
                        b.eager = eager.create(box_at(b.centre, b.half));
                    }
                } else if (what == 0) {
                    bp.destroy(b.proxy);
                    eager.destroy(b.eager);
                    b.proxy = b.eager = -1;
                } else if (what < 14) {
                    // Mostly small steps (inside the margin), sometimes a jump.
                    const float reach = what == 1 ? 50.0f : 1.5f;
                    const Vec2 d{rng.uniform(-reach, reach), rng.uniform(-reach, reach)};
                    b.centre += d;
                    bp.move(b.proxy, box_at(b.centre, b.half), d);
                    eager.move(b.eager, box_at(b.centre, b.half), d);
                }
                if (b.proxy >= 0) {
                    ASSERT_TRUE(same_bits(bp.fat_bounds(b.proxy), eager.fat_bounds(b.eager)))
                        << "scene " << scene << " round " << round << " body " << i;
                }
            }
            // Queries only every few rounds, so the tree has a backlog of every kind.
            if (round % 3 != 0) continue;
            for (int q = 0; q < 20; ++q) {
                Aabb box;
                if (q >= 18) {
                    // Not finite: Box2D's test lets a NaN or an endless box meet everything.
                    // (Last: such a query catches the tree up, the scans before it do not.)
                    const float v = q == 18 ? NAN : INFINITY;
                    box = {{-v, -v}, {v, v}};
                } else if (q % 4 == 0) {
                    // Exactly touching a body's fat bounds from outside: touching counts.
                    const Body& b = bodies[rng.below(static_cast<std::uint32_t>(bodies.size()))];
                    if (b.proxy < 0) continue;
                    const Aabb fat = bp.fat_bounds(b.proxy);
                    box = {{fat.max.x, fat.min.y}, {fat.max.x + 5.0f, fat.min.y + 1.0f}};
                } else {
                    const Vec2 c{rng.uniform(-spread, spread), rng.uniform(-spread, spread)};
                    box = box_at(c, {rng.uniform(0.0f, 60.0f), rng.uniform(0.0f, 60.0f)});
                }
                ASSERT_EQ(query_sorted(bp, box), expected_hits(bp, bodies, box))
                    << "scene " << scene << " round " << round << " query " << q;
            }
        }
        // Each setting took the paths it is meant to.
        const Broadphase::Counts counts = bp.counts();
        EXPECT_GT(counts.catch_ups, 0u) << "scene " << scene;  // the non-finite boxes at least
        if (GetParam() == 0) {
            EXPECT_EQ(counts.scans, 0u) << "scene " << scene;
        } else {
            EXPECT_GT(counts.scans, counts.catch_ups) << "scene " << scene;
        }
    }
}

// The budget: with k of n proxies moved, queries scan while the scans (n each) stay within
// kScanPerInsert * k, then one catches the tree up; proxies destroyed while queued cost
// nothing to catch up, so with only those the first query catches up at once.
TEST(Broadphase, ScansWithinTheBudgetThenCatchesUp) {
    Broadphase bp;
    std::vector<int> proxy;
    for (std::uint32_t i = 0; i < 1000; ++i) {
        proxy.push_back(bp.create(box_at({static_cast<float>(i % 40) * 25.0f, static_cast<float>(i / 40) * 25.0f}, {3, 3}), i));
    }
    const Aabb box = box_at({100, 100}, {40, 40});
    const auto query = [&] {
        std::size_t hits = 0;
        bp.query(box, [&](std::uint32_t) { ++hits; });
        return hits;
    };
    // A first query would scan (1,000 creations queued); a non-finite box catches up at once.
    bp.query(Aabb{{-INFINITY, -INFINITY}, {INFINITY, INFINITY}}, [](std::uint32_t) {});
    EXPECT_EQ(bp.counts().scans, 0u);
    EXPECT_EQ(bp.counts().catch_ups, 1u);
    const std::size_t hits = query();  // nothing behind
    EXPECT_EQ(hits, 9u);                // 3 x 3 of the grid
    EXPECT_EQ(bp.counts().catch_ups, 1u);
    for (int i = 0; i < 10; ++i) bp.move(proxy[static_cast<std::size_t>(i)], box_at({5000, 5000}, {3, 3}), {});
    const std::size_t k = 10, n = 1000, scans = Broadphase::kScanPerInsert * k / n;
    ASSERT_GE(scans, 1u);
    for (std::size_t q = 0; q < scans; ++q) query();
    EXPECT_EQ(bp.counts().scans, scans);
    EXPECT_EQ(bp.counts().catch_ups, 1u);
    query();
    EXPECT_EQ(bp.counts().catch_ups, 2u);
    query();  // nothing behind: neither
    EXPECT_EQ(bp.counts().scans, scans);
    EXPECT_EQ(bp.counts().catch_ups, 2u);
    for (int i = 10; i < 20; ++i) bp.move(proxy[static_cast<std::size_t>(i)], box_at({6000, 6000}, {3, 3}), {});
    for (int i = 10; i < 20; ++i) bp.destroy(proxy[static_cast<std::size_t>(i)]);
    EXPECT_EQ(query(), hits);  // the moved and destroyed ones sit in row 0, away from the box
    EXPECT_EQ(bp.counts().scans, scans);
    EXPECT_EQ(bp.counts().catch_ups, 3u);
}

// The tree may keep a node it already has (Box2D's MoveProxy returns early when the node
// holds the new box and is not much larger): a proxy moved away and back between two
// queries, its fat bounds again what they were, is still found exactly.
TEST(Broadphase, AProxyMovedAwayAndBackBetweenQueriesIsFound) {
    Broadphase bp(0);
    const Aabb home = box_at({10, 10}, {3, 3});
    const int p = bp.create(home, 7);
    const int other = bp.create(box_at({40, 10}, {3, 3}), 8);
    EXPECT_EQ(query_sorted(bp, box_at({10, 10}, {1, 1})), std::vector<std::uint32_t>{7});
    bp.move(p, box_at({500, 500}, {3, 30}), {});
    bp.move(p, home, {});
    bp.move(other, box_at({41, 10}, {3, 3}), {});
    EXPECT_EQ(query_sorted(bp, box_at({10, 10}, {1, 1})), std::vector<std::uint32_t>{7});
    EXPECT_EQ(query_sorted(bp, box_at({500, 500}, {1, 1})), std::vector<std::uint32_t>{});
    EXPECT_EQ(query_sorted(bp, box_at({25, 10}, {20, 1})), (std::vector<std::uint32_t>{7, 8}));
}

// Never scanning (the tree catches up at every query after a change), the default, and
// scanning for a long while before catching up.
INSTANTIATE_TEST_SUITE_P(Broadphase, BroadphaseScanning,
                         ::testing::Values(std::size_t{0}, Broadphase::kScanPerInsert, std::size_t{100000}));

TEST_P(BroadphaseScanning, ConstQueriesFromTwoThreadsAnswerAlike) {
    Rng rng(3);
    Broadphase bp(GetParam());
    std::vector<Body> bodies(2000);
    for (std::uint32_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        b.centre = {rng.uniform(0.0f, 1000.0f), rng.uniform(0.0f, 1000.0f)};
        b.half = {rng.uniform(1.0f, 8.0f), rng.uniform(1.0f, 8.0f)};
        b.proxy = bp.create(box_at(b.centre, b.half), i);
    }
    std::vector<Aabb> boxes;
    for (int q = 0; q < 200; ++q) {
        boxes.push_back(box_at({rng.uniform(0.0f, 1000.0f), rng.uniform(0.0f, 1000.0f)}, {30.0f, 30.0f}));
    }
    for (int round = 0; round < 5; ++round) {
        for (Body& b : bodies) {  // every proxy leaves its fat bounds: a full backlog
            const Vec2 d{rng.uniform(-20.0f, 20.0f), rng.uniform(-20.0f, 20.0f)};
            b.centre += d;
            bp.move(b.proxy, box_at(b.centre, b.half), d);
        }
        std::vector<std::vector<std::uint32_t>> got[2];
        const Broadphase& view = bp;
        const auto run = [&](int t) {
            for (const Aabb& box : boxes) got[t].push_back(query_sorted(view, box));
        };
        std::thread other(run, 1);
        run(0);
        other.join();
        for (std::size_t q = 0; q < boxes.size(); ++q) {
            const std::vector<std::uint32_t> want = expected_hits(bp, bodies, boxes[q]);
            ASSERT_EQ(got[0][q], want) << "round " << round << " query " << q;
            ASSERT_EQ(got[1][q], want) << "round " << round << " query " << q;
        }
    }
}

}  // namespace
}  // namespace jostle::detail
