// Property tests on seeded random shapes (jostle::Rng), checked against an independent
// double-precision oracle in test_shapes.h: the MTD separates, no SAT axis beats the reported
// depth, sweeps touch at t and never overlap before it, casts never miss a crossed shape, and
// collide_sat agrees with collide for polygon-circle. Tolerance: 1e-4 of the shapes' size
// (the header's LIMITS).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "test_shapes.h"

namespace jostle {
namespace {

using test::D2;
using test::d2;
using test::describe;
using test::Kind;
using test::kAllKinds;

// Collects failures of one property, reports the first few in full and the total.
class Failures {
public:
    explicit Failures(const char* property) : property_(property) {}
    ~Failures() {
        if (count_ > 0) {
            ADD_FAILURE() << property_ << ": " << count_ << " of " << cases_ << " cases failed"
                          << (count_ > kMaxFailures ? " (stopped early)" : "");
        }
    }
    void add_case() { ++cases_; }
    // Returns true when the caller should stop (too many failures).
    bool fail(const std::string& what) {
        ++count_;
        if (count_ <= 8) ADD_FAILURE() << property_ << ": " << what;
        return count_ > kMaxFailures;
    }
    int count() const { return count_; }

private:
    static constexpr int kMaxFailures = 200;
    const char* property_;
    int cases_ = 0;
    int count_ = 0;
};

std::string vec(Vec2 v) {
    std::ostringstream s;
    s.precision(9);
    s << "(" << v.x << ", " << v.y << ")";
    return s.str();
}

std::string manifold(const Manifold& m) {
    std::ostringstream s;
    s.precision(9);
    s << "hit=" << m.hit << " depth=" << m.depth << " normal=" << vec(m.normal);
    return s.str();
}

bool is_polygonal(Kind k) { return k != Kind::circle; }

constexpr int kCasesPerPair = 240;  // 25 ordered pairs of kinds

TEST(Property, CollideMatchesTheOracleAndTheMtdSeparates) {
    Failures f("collide vs oracle / mtd");
    Rng rng(0x5eed0001u);
    int hits = 0;
    for (Kind ka : kAllKinds) {
        for (Kind kb : kAllKinds) {
            for (int i = 0; i < kCasesPerPair; ++i) {
                const Shape a = test::random_shape(rng, ka, 12.0f);
                const Shape b = test::random_shape(rng, kb, 12.0f);
                f.add_case();
                const float size = std::max(test::shape_size(a), test::shape_size(b));
                const double tol = 1e-4 * size;
                const Manifold m = collide(a, b);
                const double pen = test::penetration(a, b);
                const std::string ctx = std::string(test::kind_name(ka)) + " vs " + test::kind_name(kb) + ": " +
                                        describe(a) + " / " + describe(b) + " -> " + manifold(m) +
                                        ", oracle penetration " + std::to_string(pen);
                if (overlaps(a, b) != m.hit && f.fail("overlaps != collide.hit: " + ctx)) return;
                if (pen > tol && (!m.hit || std::fabs(m.depth - pen) > tol)) {
                    if (f.fail("depth differs from the oracle: " + ctx)) return;
                }
                if (pen < -tol && !test::is_miss(m)) {
                    if (f.fail("hit where the oracle separates: " + ctx)) return;
                }
                if (m.hit) {
                    ++hits;
                    if (!test::is_unit(m.normal) || !(m.depth >= 0.0f)) {
                        if (f.fail("bad normal or depth: " + ctx)) return;
                        continue;
                    }
                    // Moving A by mtd() leaves at most a touch.
                    const double after = test::penetration(test::moved(a, m.mtd()), b);
                    if (after > tol) {
                        if (f.fail("after moving A by mtd the penetration is " + std::to_string(after) + ": " + ctx)) {
                            return;
                        }
                    }
                }
            }
        }
    }
    // The generator must exercise hits and misses alike.
    EXPECT_GT(hits, 25 * kCasesPerPair / 5);
    EXPECT_LT(hits, 25 * kCasesPerPair * 4 / 5);
}

TEST(Property, CollideFarFromTheOriginAgreesWithDouble) {
    // LIMITS: for |x|, |y| <= 1e5 depths agree with a double-precision computation to about
    // 1e-4 of the shapes' size. Same random pairs as near the origin, moved to (o, o); the
    // oracle works on the same float inputs. Tolerance 2e-4 of the size ("about").
    Failures f("collide far from the origin");
    for (const float o : {10000.0f, 100000.0f, -100000.0f}) {
        Rng rng(0x5eed000au);
        for (Kind ka : kAllKinds) {
            for (Kind kb : kAllKinds) {
                for (int i = 0; i < 60; ++i) {
                    const Shape a = test::moved(test::random_shape(rng, ka, 12.0f), {o, o});
                    const Shape b = test::moved(test::random_shape(rng, kb, 12.0f), {o, o});
                    f.add_case();
                    const double tol = 2e-4 * std::max(test::shape_size(a), test::shape_size(b));
                    const Manifold m = collide(a, b);
                    const double pen = test::penetration(a, b);
                    if ((pen > tol && (!m.hit || std::fabs(m.depth - pen) > tol)) || (pen < -tol && m.hit)) {
                        if (f.fail(std::string(test::kind_name(ka)) + " vs " + test::kind_name(kb) + ": " +
                                   describe(a) + " / " + describe(b) + " -> " + manifold(m) + ", oracle " +
                                   std::to_string(pen) + ", tolerance " + std::to_string(tol))) {
                            return;
                        }
                    }
                }
            }
        }
    }
}

TEST(Property, NoSatAxisGivesAShorterPushThanDepth) {
    // For polygonal pairs, every candidate axis (edge normals of both, a segment's direction),
    // computed here in double, needs a push of at least depth.
    Failures f("SAT axes");
    Rng rng(0x5eed0002u);
    int hits = 0;
    for (Kind ka : kAllKinds) {
        for (Kind kb : kAllKinds) {
            if (!is_polygonal(ka) || !is_polygonal(kb)) continue;
            for (int i = 0; i < kCasesPerPair; ++i) {
                const Shape a = test::random_shape(rng, ka, 10.0f);
                const Shape b = test::random_shape(rng, kb, 10.0f);
                f.add_case();
                const Manifold m = collide(a, b);
                if (!m.hit) continue;
                ++hits;
                const double tol = 1e-4 * std::max(test::shape_size(a), test::shape_size(b));
                const auto va = test::vertices(a);
                const auto vb = test::vertices(b);
                std::vector<D2> axes;
                test::add_axes(va, axes);
                test::add_axes(vb, axes);
                double best = 1e300;
                for (const D2& ax : axes) best = std::min(best, test::axis_push(va, vb, ax));
                if (static_cast<double>(m.depth) > best + tol) {
                    if (f.fail(describe(a) + " / " + describe(b) + ": depth " + std::to_string(m.depth) +
                               " but an axis needs only " + std::to_string(best))) {
                        return;
                    }
                }
                // Along the reported normal (A toward B), A's far side passes B's near side by depth.
                double alo = 0, ahi = 0, blo = 0, bhi = 0;
                test::project(va, d2(m.normal), alo, ahi);
                test::project(vb, d2(m.normal), blo, bhi);
                const double along = ahi - blo;
                if (std::fabs(along - m.depth) > tol) {
                    if (f.fail(describe(a) + " / " + describe(b) + ": push along the normal " + std::to_string(along) +
                               " != depth " + std::to_string(m.depth))) {
                        return;
                    }
                }
            }
        }
    }
    EXPECT_GT(hits, 1000);
}

TEST(Property, CollideIsSymmetric) {
    Failures f("collide(a,b) vs collide(b,a)");
    Rng rng(0x5eed0003u);
    for (Kind ka : kAllKinds) {
        for (Kind kb : kAllKinds) {
            for (int i = 0; i < kCasesPerPair / 2; ++i) {
                const Shape a = test::random_shape(rng, ka, 12.0f);
                const Shape b = test::random_shape(rng, kb, 12.0f);
                f.add_case();
                const double tol = 1e-4 * std::max(test::shape_size(a), test::shape_size(b));
                const Manifold ab = collide(a, b);
                const Manifold ba = collide(b, a);
                const std::string ctx = describe(a) + " / " + describe(b) + ": " + manifold(ab) + " vs " + manifold(ba);
                if (std::fabs(test::penetration(a, b)) <= tol) continue;  // touching up to rounding
                if (ab.hit != ba.hit || std::fabs(ab.depth - ba.depth) > tol) {
                    if (f.fail(ctx)) return;
                    continue;
                }
                if (ab.hit && !test::vec_near(ab.normal, -ba.normal, 1e-3f)) {
                    // A near tie may pick another axis; then both pushes must still separate.
                    const double pa = test::penetration(test::moved(a, ab.mtd()), b);
                    const double pb = test::penetration(test::moved(b, ba.mtd()), a);
                    if (pa > tol || pb > tol) {
                        if (f.fail("normals not opposite: " + ctx)) return;
                    }
                }
            }
        }
    }
}

TEST(Property, CollideSatEqualsCollideForPolygonCircle) {
    Failures f("collide_sat vs collide");
    Rng rng(0x5eed0004u);
    for (int i = 0; i < 4000; ++i) {
        const Polygon p = test::random_polygon(rng, 10.0f);
        const Circle c = test::random_circle(rng, 10.0f);
        f.add_case();
        const double tol = 1e-4 * std::max(test::shape_size(p), test::shape_size(c));
        const Manifold a = collide(p, c);
        const Manifold b = collide_sat(p, c);
        const std::string ctx = describe(p) + " / " + describe(c) + ": collide " + manifold(a) + ", collide_sat " +
                                manifold(b);
        if (std::fabs(test::penetration(p, c)) <= tol) continue;
        if (a.hit != b.hit || std::fabs(a.depth - b.depth) > tol) {
            if (f.fail(ctx)) return;
            continue;
        }
        if (a.hit && !test::vec_near(a.normal, b.normal, 1e-3f)) {
            const double pa = test::penetration(test::moved(Shape{p}, a.mtd()), c);
            const double pb = test::penetration(test::moved(Shape{p}, b.mtd()), c);
            if (pa > tol || pb > tol) {
                if (f.fail("normals differ: " + ctx)) return;
            }
        }
    }
}

// Signed distance from the centre of `moving` at time tau to `target` (moving by vb), minus r.
double gap_at(const Circle& moving, Vec2 va, const Shape& target, Vec2 vb, double tau) {
    const D2 c = d2(moving.center) + tau * (d2(va) - d2(vb));
    return test::signed_distance(target, c) - moving.radius;
}

// The smallest gap along the whole frame, sampled finely (enough to tell a path that goes
// into B from one that only grazes it).
double gap_min_along_path(const Circle& a, Vec2 va, const Shape& b, Vec2 vb) {
    double m = INFINITY;
    for (int k = 0; k <= 256; ++k) m = std::min(m, gap_at(a, va, b, vb, k / 256.0));
    return m;
}

TEST(Property, SweepTouchesAtTAndNeverOverlapsBefore) {
    Failures f("sweep");
    Rng rng(0x5eed0005u);
    constexpr int kSamples = 64;
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const Kind kb = kAllKinds[rng.below(5)];
        const float radius = rng.below(8) == 0 ? 0.0f : rng.uniform(0.5f, 5.0f);
        const Circle a{test::random_point(rng, 25.0f), radius};
        const Shape b = test::random_shape(rng, kb, 10.0f);
        const float speed = rng.uniform(0.0f, 60.0f);
        const float ang = rng.uniform(-test::kPi, test::kPi);
        const Vec2 va{speed * std::cos(ang), speed * std::sin(ang)};
        const Vec2 vb = rng.below(4) == 0 ? test::random_point(rng, 10.0f) : Vec2{0, 0};
        f.add_case();
        const SweepHit s = sweep(a, va, b, vb);
        const double size = std::max(test::shape_size(b), 2.0f * a.radius) + length(va - vb);
        if (radius == 0.0f && kb == Kind::segment) continue;  // a point against a line: measure zero
        const double tol = 1e-4 * size;
        std::ostringstream ctx;
        ctx.precision(9);
        ctx << describe(Shape{a}) << " by " << vec(va) << " vs " << describe(b) << " by " << vec(vb) << " -> hit "
            << s.hit << " t " << s.t << " point " << vec(s.point) << " normal " << vec(s.normal);
        const double g0 = gap_at(a, va, b, vb, 0.0);
        if (g0 <= tol) {
            // In contact at t = 0: a contact at t = 0 while moving into B, no hit while moving
            // off or along it (the manual's moving-away rule).
            const double h = 1e-6;
            const double slope = (gap_at(a, va, b, vb, h) - g0) / h;  // < 0: getting deeper
            const double slope_tol = 1e-3 * length(va - vb) + tol;
            if ((g0 < -tol && s.hit && s.t != 0.0f) || (!s.hit && slope < -slope_tol && gap_min_along_path(a, va, b, vb) < -tol) ||
                (s.hit && s.t == 0.0f && slope > slope_tol)) {
                ctx << "; in contact at t = 0 (gap " << g0 << "), gap slope " << slope;
                if (f.fail(ctx.str())) return;
            }
            // The contact point lies on B: where the circle's surface meets it along the normal.
            if (s.hit && s.t == 0.0f) {
                const double on_b = std::fabs(test::signed_distance(b, d2(s.point)));
                if (on_b > tol) {
                    ctx << "; in contact at t = 0, point off B by " << on_b;
                    if (f.fail(ctx.str())) return;
                }
            }
            if (s.hit) ++hits;
            continue;
        }
        const double end = s.hit ? static_cast<double>(s.t) : 1.0;
        // No overlap before t (or anywhere along the path on a miss).
        for (int k = 0; k <= kSamples; ++k) {
            const double tau = end * k / kSamples;
            if (s.hit && tau >= end) break;
            const double g = gap_at(a, va, b, vb, tau);
            if (g < -tol) {
                ctx << "; overlap " << g << " at tau " << tau;
                if (f.fail(ctx.str())) return;
                break;
            }
        }
        if (!s.hit) {
            if (!test::is_miss(s) && f.fail("miss with non-zero fields: " + ctx.str())) return;
            continue;
        }
        ++hits;
        if (!(s.t >= 0.0f && s.t <= 1.0f) || !test::is_unit(s.normal, 1e-4f)) {
            if (f.fail("bad t or normal: " + ctx.str())) return;
            continue;
        }
        const double g = gap_at(a, va, b, vb, s.t);
        if (s.t > 0.0f ? std::fabs(g) > tol : g > tol) {
            ctx << "; gap at t is " << g;
            if (f.fail(ctx.str())) return;
            continue;
        }
        {
            // The module agrees: at t the circle at most touches B (depth ~0).
            const Manifold at_t = collide(Shape{Circle{a.center + s.t * va, a.radius}}, test::moved(b, s.t * vb));
            if (s.t > 0.0f && at_t.depth > tol) {
                ctx << "; collide at t gives depth " << at_t.depth;
                if (f.fail(ctx.str())) return;
                continue;
            }
        }
        if (s.t > 0.0f) {
            // The contact point lies on B (at time t) and r from the centre along the normal.
            const Shape bt = test::moved(b, s.t * vb);
            const Vec2 centre = a.center + s.t * va;
            const double on_b = std::fabs(test::signed_distance(bt, d2(s.point)));
            const Vec2 expected_point = centre + a.radius * s.normal;
            if (on_b > tol || !test::vec_near(s.point, expected_point, static_cast<float>(10 * tol))) {
                ctx << "; point off B by " << on_b << ", centre + r n = " << vec(expected_point);
                if (f.fail(ctx.str())) return;
            }
        }
    }
    EXPECT_GT(hits, 400);  // the generator must exercise hits, not only misses
}

TEST(Property, SweptOverlapsAgreesWithSweep) {
    Failures f("swept_overlaps vs sweep");
    Rng rng(0x5eed0006u);
    for (int i = 0; i < 4000; ++i) {
        const Circle a{test::random_point(rng, 20.0f), rng.uniform(0.0f, 5.0f)};
        const Circle b{test::random_point(rng, 20.0f), rng.uniform(0.0f, 5.0f)};
        const float speed = rng.uniform(0.0f, 50.0f);
        const float ang = rng.uniform(-test::kPi, test::kPi);
        const Vec2 v{speed * std::cos(ang), speed * std::sin(ang)};
        f.add_case();
        // Closest approach of the centre's path to b's centre, in double.
        const D2 p = d2(a.center);
        const D2 q = d2(a.center + v);
        const double closest = test::dist_point_segment(d2(b.center), p, q);
        const double rr = static_cast<double>(a.radius) + b.radius;
        if (std::fabs(closest - rr) <= 1e-4 * (rr + speed)) continue;  // tangent up to rounding
        const bool expected = closest < rr;
        const bool so = swept_overlaps(a, v, b);
        const bool sw = sweep(a, v, b).hit;
        // A sweep that starts in contact reports a hit only when moving into B; the capsule
        // test does not care about direction. Compare sweep only for separate starts.
        const bool starts_apart = test::dlen(d2(b.center) - d2(a.center)) > rr;
        if (so != expected || (starts_apart && sw != expected)) {
            std::ostringstream s;
            s << describe(Shape{a}) << " by " << vec(v) << " vs " << describe(Shape{b}) << ": expected " << expected
              << ", swept_overlaps " << so << ", sweep " << sw;
            if (f.fail(s.str())) return;
        }
    }
}

TEST(Property, CastNeverMissesACrossedShape) {
    Failures f("cast");
    Rng rng(0x5eed0007u);
    constexpr int kSamples = 64;
    const Kind solid[] = {Kind::aabb, Kind::obb, Kind::polygon, Kind::circle};
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const Shape b = test::random_shape(rng, solid[rng.below(4)], 10.0f);
        const Vec2 from = test::random_point(rng, 30.0f);
        const Vec2 to = rng.below(16) == 0 ? from : test::random_point(rng, 30.0f);
        f.add_case();
        const CastHit h = cast(from, to, b);
        const double tol = 1e-4 * (test::shape_size(b) + length(to - from));
        std::ostringstream ctx;
        ctx.precision(9);
        ctx << vec(from) << " -> " << vec(to) << " vs " << describe(b) << ": hit " << h.hit << " t " << h.t
            << " point " << vec(h.point) << " normal " << vec(h.normal);
        // The first sample strictly inside the shape.
        int first_inside = -1;
        for (int k = 0; k <= kSamples; ++k) {
            const double tau = static_cast<double>(k) / kSamples;
            const D2 p = d2(from) + tau * (d2(to) - d2(from));
            if (test::signed_distance(b, p) < -tol) {
                first_inside = k;
                break;
            }
        }
        if (first_inside >= 0) {
            const double limit = static_cast<double>(first_inside) / kSamples + 1e-5;
            if (!h.hit || h.t > limit) {
                ctx << "; sample " << first_inside << " is inside";
                if (f.fail(ctx.str())) return;
                continue;
            }
        }
        if (!h.hit) {
            if (!test::is_miss(h) && f.fail("miss with non-zero fields: " + ctx.str())) return;
            continue;
        }
        ++hits;
        const Vec2 expected_point = from + h.t * (to - from);
        const double at_point = test::signed_distance(b, d2(h.point));
        const double at_from = test::signed_distance(b, d2(from));
        bool bad = !(h.t >= 0.0f && h.t <= 1.0f) || !test::vec_near(h.point, expected_point, static_cast<float>(tol));
        if (h.t > 0.0f) {
            // Contact on the boundary, facing the bullet, and the start was outside.
            bad = bad || std::fabs(at_point) > tol || !test::is_unit(h.normal, 1e-4f) ||
                  dot(h.normal, to - from) > tol || at_from < -tol;
        } else {
            bad = bad || at_from > tol || h.point != from;
            if (at_from < -tol) bad = bad || h.normal != Vec2{};  // strictly inside: no normal
        }
        if (bad) {
            ctx << "; distance at point " << at_point << ", at from " << at_from;
            if (f.fail(ctx.str())) return;
        }
    }
    EXPECT_GT(hits, 400);
}

TEST(Property, CastAgainstSegmentsMatchesAnIntersectionTest) {
    Failures f("cast vs segment");
    Rng rng(0x5eed0008u);
    for (int i = 0; i < 4000; ++i) {
        const Segment wall = test::random_segment(rng, 10.0f);
        const Vec2 from = test::random_point(rng, 25.0f);
        const Vec2 to = test::random_point(rng, 25.0f);
        f.add_case();
        // Parameters of the crossing in double: from + t d = a + u e.
        const D2 d = d2(to) - d2(from);
        const D2 e = d2(wall.b) - d2(wall.a);
        const D2 w = d2(wall.a) - d2(from);
        const double den = test::dcross(d, e);
        if (std::fabs(den) < 1e-3 * test::dlen(d) * test::dlen(e)) continue;  // nearly parallel
        const double t = test::dcross(w, e) / den;
        const double u = test::dcross(w, d) / den;
        const double margin = 1e-4;
        const bool inside = t > margin && t < 1 - margin && u > margin && u < 1 - margin;
        const bool outside = t < -margin || t > 1 + margin || u < -margin || u > 1 + margin;
        const CastHit h = cast(from, to, wall);
        std::ostringstream ctx;
        ctx.precision(9);
        ctx << vec(from) << " -> " << vec(to) << " vs " << describe(Shape{wall}) << ": hit " << h.hit << " t " << h.t
            << ", expected t " << t;
        if (inside && (!h.hit || std::fabs(h.t - t) > 1e-4 || !test::is_unit(h.normal, 1e-4f) ||
                       dot(h.normal, to - from) > 0.0f)) {
            if (f.fail(ctx.str())) return;
        }
        if (outside && !test::is_miss(h)) {
            if (f.fail(ctx.str())) return;
        }
    }
}

TEST(Property, ClosestPointIsOnTheShapeAndNearest) {
    // closest_point(shape, q): distance matches the oracle, and the point is in the shape.
    Failures f("closest_point");
    Rng rng(0x5eed0009u);
    const Kind kinds[] = {Kind::aabb, Kind::obb, Kind::polygon, Kind::circle, Kind::segment};
    for (int i = 0; i < 4000; ++i) {
        const Shape s = test::random_shape(rng, kinds[rng.below(5)], 10.0f);
        const Vec2 q = test::random_point(rng, 15.0f);
        f.add_case();
        const double tol = 1e-4 * (test::shape_size(s) + 15.0);
        const ClosestPoint c = closest_point(s, q);
        const double sd = test::signed_distance(s, d2(q));
        const double expected = std::max(sd, 0.0);
        const double point_in = test::signed_distance(s, d2(c.point));
        const double q_to_point = test::dlen(d2(q) - d2(c.point));
        if (std::fabs(c.distance - expected) > tol || point_in > tol || std::fabs(q_to_point - expected) > tol) {
            std::ostringstream ctx;
            ctx << describe(s) << " q " << vec(q) << ": point " << vec(c.point) << " distance " << c.distance
                << ", expected distance " << expected;
            if (f.fail(ctx.str())) return;
        }
    }
}

TEST(Property, SegmentIntersectionMatchesAnOrientationTest) {
    Failures f("intersect(Segment, Segment)");
    Rng rng(0x5eed000bu);
    for (int i = 0; i < 4000; ++i) {
        const Segment s1 = test::random_segment(rng, 8.0f);
        const Segment s2 = test::random_segment(rng, 8.0f);
        f.add_case();
        // Robust classification in double: orientations of each segment's ends against the other.
        auto orient = [](Vec2 a, Vec2 b, Vec2 c) { return test::dcross(d2(b) - d2(a), d2(c) - d2(a)); };
        const double l1 = test::dlen(d2(s1.b) - d2(s1.a));
        const double l2 = test::dlen(d2(s2.b) - d2(s2.a));
        const double eps = 1e-4 * l1 * l2;
        const double o1 = orient(s1.a, s1.b, s2.a), o2 = orient(s1.a, s1.b, s2.b);
        const double o3 = orient(s2.a, s2.b, s1.a), o4 = orient(s2.a, s2.b, s1.b);
        const bool crosses = ((o1 > eps && o2 < -eps) || (o1 < -eps && o2 > eps)) &&
                             ((o3 > eps && o4 < -eps) || (o3 < -eps && o4 > eps));
        const bool apart = (o1 > eps && o2 > eps) || (o1 < -eps && o2 < -eps) || (o3 > eps && o4 > eps) ||
                           (o3 < -eps && o4 < -eps);
        const SegmentIntersection r = intersect(s1, s2);
        std::ostringstream ctx;
        ctx << describe(Shape{s1}) << " / " << describe(Shape{s2}) << ": hit " << r.hit << " point " << vec(r.point);
        if ((crosses && !r.hit) || (apart && r.hit)) {
            if (f.fail(ctx.str())) return;
            continue;
        }
        if (r.hit) {
            const double d1 = test::dist_point_segment(d2(r.point), d2(s1.a), d2(s1.b));
            const double d2_ = test::dist_point_segment(d2(r.point), d2(s2.a), d2(s2.b));
            if (d1 > 1e-4 * l1 || d2_ > 1e-4 * l2) {
                if (f.fail(ctx.str() + " is not on both segments")) return;
            }
        }
    }
}

TEST(Property, ContainsAndClosestPointOnBoundaryMatchTheOracle) {
    Failures f("contains / closest_point_on_boundary");
    Rng rng(0x5eed000cu);
    for (int i = 0; i < 4000; ++i) {
        const Polygon p = test::random_polygon(rng, 5.0f);
        const Vec2 q = test::random_point(rng, 15.0f);
        f.add_case();
        const double tol = 1e-4 * test::shape_size(p);
        const double sd = test::signed_distance(p, d2(q));
        int edge = -1;
        const Vec2 b = closest_point_on_boundary(p, q, &edge);
        const bool in = contains(p, q);
        std::ostringstream ctx;
        ctx << describe(p) << " q " << vec(q) << ": contains " << in << ", boundary point " << vec(b) << " edge "
            << edge << ", oracle signed distance " << sd;
        bool bad = (sd < -tol && !in) || (sd > tol && in) || edge < 0 || edge >= p.count();
        if (!bad) {
            // On the boundary, on the reported edge, at distance |sd| from q.
            const auto e = static_cast<std::size_t>(edge);
            const auto e1 = static_cast<std::size_t>((edge + 1) % p.count());
            bad = test::dist_point_segment(d2(b), d2(p.points()[e]), d2(p.points()[e1])) > tol ||
                  std::fabs(test::dlen(d2(q) - d2(b)) - std::fabs(sd)) > tol;
        }
        if (bad && f.fail(ctx.str())) return;
    }
}

TEST(Property, BoundsContainTheShapeAndAreTight) {
    Failures f("bounds / rotated_bounds");
    Rng rng(0x5eed000du);
    for (int i = 0; i < 2000; ++i) {
        const Kind k = kAllKinds[rng.below(5)];
        const Shape s = test::random_shape(rng, k, 20.0f);
        f.add_case();
        const Aabb b = bounds(s);
        double lo_x = 1e300, lo_y = 1e300, hi_x = -1e300, hi_y = -1e300;
        if (const auto* c = std::get_if<Circle>(&s)) {
            lo_x = c->center.x - c->radius;
            hi_x = c->center.x + c->radius;
            lo_y = c->center.y - c->radius;
            hi_y = c->center.y + c->radius;
        } else {
            for (const D2& v : test::vertices(s)) {
                lo_x = std::min(lo_x, v.x);
                hi_x = std::max(hi_x, v.x);
                lo_y = std::min(lo_y, v.y);
                hi_y = std::max(hi_y, v.y);
            }
        }
        const double tol = 1e-4 * test::shape_size(s);
        if (std::fabs(b.min.x - lo_x) > tol || std::fabs(b.min.y - lo_y) > tol || std::fabs(b.max.x - hi_x) > tol ||
            std::fabs(b.max.y - hi_y) > tol) {
            if (f.fail(describe(s) + ": bounds " + vec(b.min) + " - " + vec(b.max))) return;
        }
        // rotated_bounds of the box's corners = the tight bounds of the turned corners.
        const float angle = rng.uniform(-test::kPi, test::kPi);
        const Vec2 pivot = test::random_point(rng, 20.0f);
        const Aabb rb = rotated_bounds(b, angle, pivot);
        const auto cs = corners(b);
        const Aabb tight = rotated_bounds(std::span<const Vec2>(cs), angle, pivot);
        const double ca = std::cos(static_cast<double>(angle)), sa = std::sin(static_cast<double>(angle));
        double rlo_x = 1e300, rlo_y = 1e300, rhi_x = -1e300, rhi_y = -1e300;
        for (const Vec2& c : cs) {
            const double x = c.x - pivot.x, y = c.y - pivot.y;
            const double rx = ca * x - sa * y + pivot.x, ry = sa * x + ca * y + pivot.y;
            rlo_x = std::min(rlo_x, rx);
            rhi_x = std::max(rhi_x, rx);
            rlo_y = std::min(rlo_y, ry);
            rhi_y = std::max(rhi_y, ry);
        }
        const double rtol = 1e-4 * (test::shape_size(s) + 60.0);
        for (const Aabb& r : {rb, tight}) {
            if (std::fabs(r.min.x - rlo_x) > rtol || std::fabs(r.min.y - rlo_y) > rtol ||
                std::fabs(r.max.x - rhi_x) > rtol || std::fabs(r.max.y - rhi_y) > rtol) {
                if (f.fail(describe(Shape{b}) + " turned by " + std::to_string(angle) + " about " + vec(pivot) +
                           ": " + vec(r.min) + " - " + vec(r.max))) {
                    return;
                }
            }
        }
    }
}

}  // namespace
}  // namespace jostle
