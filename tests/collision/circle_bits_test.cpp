// The circle pairs' lane-parallel code (circle.cpp: four faces or vertices to a register with
// NaN in the slots past the last, or eight with AVX2 for up to 8 vertices, x and y side by side,
// one DIVPS for a normal) against the plain scalar loops it replaced, bit for bit (polygons on
// both the SSE and the AVX2 path): hit, depth and normal, on seeded random shapes of
// every vertex count, centres inside, beside edges, in vertex regions, on vertices and on a
// grid of integers (ties), and on inputs past the limits (NaN, infinities, overflow).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "bits_check.h"
#include "internal.h"  // engine/collision/src: detail::offset_from_boundary, the lecture's loop
#include "test_shapes.h"

namespace jostle {
namespace {

using test::kInf;
using test::kNan;

bool finite3(float a, float b, float c) { return std::isfinite(a) && std::isfinite(b) && std::isfinite(c); }
bool valid_circle(const Circle& c) {
    return finite3(c.center.x, c.center.y, c.radius * c.radius) && c.radius >= 0.0f;
}
using test::same_bits;
constexpr auto hit = test::scalar_hit;

constexpr float kLeastNormal = 0x1p-126f;  // FLT_MIN: below it a square lost bits

Manifold scalar_circle_circle(const Circle& a, const Circle& b) {
    if (!valid_circle(a) || !valid_circle(b)) return {};
    const Vec2 d = b.center - a.center;
    const float dist2 = d.x * d.x + d.y * d.y;
    const float r = a.radius + b.radius;
    if (!(dist2 <= r * r) || dist2 == kInf) return {};
    const float len = std::sqrt(dist2);
    // A denormal dist2's root lost bits: the direction rescaled.
    const Vec2 u = dist2 >= kLeastNormal ? Vec2{d.x / len, d.y / len}
                   : len > 0.0f          ? detail::normalize_rescaled(d, Vec2{1.0f, 0.0f})
                                         : Vec2{1.0f, 0.0f};
    return hit(r - len, u);
}

Manifold scalar_polygon_circle(const Polygon& a, const Circle& b) {
    const int n = a.count();
    if (n < 3) return {};
    const Vec2 c = b.center;
    const auto P = a.points();
    const auto N = a.normals();
    float most = -kInf;
    int face = 0;
    for (int i = 0; i < n; ++i) {
        const float s = N[i].x * (c.x - P[i].x) + N[i].y * (c.y - P[i].y);
        if (s > most) {
            most = s;
            face = i;
        }
    }
    if (most > b.radius || !valid_circle(b)) return {};
    if (most <= 0.0f) return hit(b.radius - most, N[face]);
    const Vec2 p0 = P[face], p1 = P[(face + 1) % n], e = p1 - p0;
    if (dot(c - p0, e) > 0.0f && dot(c - p1, e) < 0.0f) return hit(b.radius - most, N[face]);
    float dist2 = kInf;
    int v = 0;
    for (int i = 0; i < n; ++i) {
        const Vec2 o = c - P[i];
        const float d2 = o.x * o.x + o.y * o.y;
        if (d2 < dist2) {
            dist2 = d2;
            v = i;
        }
    }
    if (!(dist2 <= b.radius * b.radius)) return {};
    const Vec2 d = c - P[v];
    const Vec2 n_prev = N[(v + n - 1) % n], n_next = N[v];
    const float len = std::sqrt(dist2);
    Vec2 u = dist2 >= kLeastNormal && len < kInf ? Vec2{d.x / len, d.y / len}
             : len > 0.0f && dist2 < kLeastNormal  ? detail::normalize_rescaled(d, N[face])
                                                   : N[face];
    if (cross(n_prev, u) < 0.0f || cross(u, n_next) < 0.0f) {
        // A search by features lost to rounding: 09-90's loop over every edge decides.
        int edge = 0;
        const Vec2 off = detail::offset_from_boundary(a, c, &edge);
        const float off2 = off.x * off.x + off.y * off.y;
        const float off_len = std::sqrt(off2);
        const Vec2 w = off2 >= kLeastNormal && off_len < kInf ? Vec2{off.x / off_len, off.y / off_len}
                       : off2 > 0.0f && off2 < kLeastNormal   ? detail::normalize_rescaled(off, N[face])
                                                              : N[face];
        return hit(b.radius - off_len, w);
    }
    return hit(b.radius - len, u);
}

Manifold scalar_box_circle(Vec2 lo, Vec2 hi, Vec2 c, float r) {
    const auto clamp = [](float v, float l, float h) {  // min, then max
        const float t = h < v ? h : v;
        return l > t ? l : t;
    };
    const Vec2 d = c - Vec2{clamp(c.x, lo.x, hi.x), clamp(c.y, lo.y, hi.y)};
    const float dist2 = d.x * d.x + d.y * d.y;
    if (dist2 > 0.0f) {
        if (!(dist2 <= r * r)) return {};
        const float dist = std::sqrt(dist2);
        const Vec2 u{d.x / dist, d.y / dist};
        return hit(r - dist, dist2 < kLeastNormal ? detail::normalize_rescaled(d, u) : u);
    }
    float depth = c.x - lo.x;
    Vec2 normal{-1.0f, 0.0f};
    if (hi.x - c.x < depth) {
        depth = hi.x - c.x;
        normal = {1.0f, 0.0f};
    }
    if (c.y - lo.y < depth) {
        depth = c.y - lo.y;
        normal = {0.0f, -1.0f};
    }
    if (hi.y - c.y < depth) {
        depth = hi.y - c.y;
        normal = {0.0f, 1.0f};
    }
    return hit(depth + r, normal);
}

Manifold scalar_aabb_circle(const Aabb& a, const Circle& b) {
    const bool box_ok = std::isfinite(a.min.x) && std::isfinite(a.min.y) && std::isfinite(a.max.x) &&
                        std::isfinite(a.max.y) && a.min.x <= a.max.x && a.min.y <= a.max.y &&
                        std::isfinite(a.max.x - a.min.x) && std::isfinite(a.max.y - a.min.y);
    if (!box_ok || !valid_circle(b)) return {};
    return scalar_box_circle(a.min, a.max, b.center, b.radius);
}

Manifold scalar_obb_circle(const Obb& a, const Circle& b) {
    const Rot q = a.rotation();
    Manifold m = scalar_box_circle(-a.half, a.half, inv_rotate(q, b.center - a.center), b.radius);
    if (!m.hit) return m;
    const float reach = 2.0f * (a.half.x + a.half.y);  // the size within float (valid(Obb))
    const bool box_ok = std::isfinite(a.center.x) && std::isfinite(a.center.y) && std::isfinite(a.half.x) &&
                        std::isfinite(a.half.y) && std::isfinite(a.angle()) && a.half.x >= 0.0f &&
                        a.half.y >= 0.0f && std::isfinite(a.center.x + reach) && std::isfinite(a.center.x - reach) &&
                        std::isfinite(a.center.y + reach) && std::isfinite(a.center.y - reach);
    if (!box_ok || !valid_circle(b)) return {};
    const Vec2 n = rotate(q, m.normal);
    m.normal = {n.x + 0.0f, n.y + 0.0f};
    return m;
}

// The draws: seeded, one value in 12 past the limits.
struct Draw : test::BitsDraw {
    Draw() : BitsDraw(20261126, 12) {}
};

Polygon random_convex(Draw& g, int n, float scale, bool integers) {
    for (;;) {
        std::vector<float> angle(static_cast<std::size_t>(n));
        for (float& t : angle) t = g.uniform(0.0f, 2.0f * test::kPi);
        std::sort(angle.begin(), angle.end());
        const float rx = scale * g.uniform(0.2f, 1.0f), ry = scale * g.uniform(0.2f, 1.0f);
        std::vector<Vec2> pts;
        for (const float t : angle) {
            Vec2 p{rx * std::cos(t), ry * std::sin(t)};
            if (integers) p = {std::round(p.x), std::round(p.y)};
            pts.push_back(p);
        }
        if (std::optional<Polygon> p = make_polygon(pts)) return *p;
    }
}

TEST(CircleBits, PolygonCircleEveryVertexCount) {
    Draw g;
    for (int n = 3; n <= kMaxPolygonVertices; ++n) {
        for (int k = 0; k < 3000; ++k) {
            const bool integers = k % 4 == 0;
            // Integer points, few enough per unit that most draws are strictly convex.
            const float scale = integers ? 4.0f * static_cast<float>(n) : g.uniform(0.5f, 20.0f);
            const Polygon poly = random_convex(g, n, scale, integers);
            const int count = poly.count();  // collinear integer points may have been dropped
            const int i = g.below(count);
            const Vec2 p = poly.points()[static_cast<std::size_t>(i)];
            const Vec2 u = poly.normals()[static_cast<std::size_t>(i)];
            Vec2 c;
            float r = g.uniform(0.0f, 0.5f * scale);
            switch (g.below(5)) {
                case 0:
                    c = p;
                    break;  // on a vertex
                case 1: {   // beside a face, or past its ends, at about distance r
                    const Vec2 q = poly.points()[static_cast<std::size_t>((i + 1) % count)];
                    const float t = g.uniform(-0.5f, 1.5f), h = g.uniform(-1.0f, 1.5f) * r;
                    c = p + t * (q - p) + h * u;
                    break;
                }
                case 2:
                    c = {g.uniform(-scale, scale), g.uniform(-scale, scale)};
                    break;
                case 3:
                    c = {std::round(g.uniform(-scale, scale)), std::round(g.uniform(-scale, scale))};
                    r = std::round(r);
                    break;
                default:
                    c = p + g.uniform(0.0f, 1.2f) * r *
                                normalize_or(
                                    u + poly.normals()[static_cast<std::size_t>((i + count - 1) % count)], u);
            }
            const Circle circle{{g.wild(c.x), g.wild(c.y)}, g.wild(r)};
            SCOPED_TRACE(testing::Message() << count << " vertices, case " << k);
            const Manifold want = scalar_polygon_circle(poly, circle);
            ASSERT_TRUE(same_bits(collide(poly, circle), want));
            if (detail::use_avx2_paths(false)) ADD_FAILURE() << "the AVX2 paths did not turn off";
            const Manifold sse = collide(poly, circle);
            detail::use_avx2_paths(true);
            ASSERT_TRUE(same_bits(sse, want)) << "(the SSE path)";
        }
    }
}

// Every way of making a Polygon keeps the slots past its vertices zero, which the AVX2 path's
// early out counts on (a nonzero normal there would be a face of its own):
// test::polygons_made_every_way.
TEST(CircleBits, PolygonsMadeEveryWay) {
    Draw g;
    Rng rng(0x510757u);
    Polygon reused = test::random_polygon(rng);  // moved_into's target, its count changing
    for (int k = 0; k < 3000; ++k) {
        const Polygon base = test::random_polygon(rng, 10.0f);
        const Vec2 shift{g.uniform(-5.0f, 5.0f), g.uniform(-5.0f, 5.0f)};
        const float angle = g.uniform(-3.0f, 3.0f);
        const Vec2 half{g.uniform(0.5f, 4.0f), g.uniform(0.5f, 4.0f)};
        for (const Polygon& poly : test::polygons_made_every_way(base, shift, angle, half, reused)) {
            for (int j = 0; j < 20; ++j) {
                const Circle circle{{g.uniform(-25.0f, 25.0f), g.uniform(-25.0f, 25.0f)}, g.uniform(0.0f, 8.0f)};
                SCOPED_TRACE(testing::Message() << poly.count() << " vertices, case " << k);
                ASSERT_TRUE(same_bits(collide(poly, circle), scalar_polygon_circle(poly, circle)));
            }
        }
        reused = test::random_polygon(rng);  // a new count, most of the time
    }
}

TEST(CircleBits, CircleCircle) {
    Draw g;
    for (int k = 0; k < 200000; ++k) {
        const float s = k % 5 == 0 ? std::pow(10.0f, g.uniform(-20.0f, 20.0f)) : g.uniform(0.5f, 20.0f);
        Circle a{{g.uniform(-s, s), g.uniform(-s, s)}, g.uniform(0.0f, s)};
        Circle b{{a.center.x + g.uniform(-2.0f, 2.0f) * s, a.center.y + g.uniform(-2.0f, 2.0f) * s},
                 g.uniform(0.0f, s)};
        if (k % 3 == 0) {  // integers: exact touching and coincident centres
            a = {{std::round(a.center.x), std::round(a.center.y)}, std::round(a.radius)};
            b = {{std::round(b.center.x), std::round(b.center.y)}, std::round(b.radius)};
        }
        if (k % 17 == 0) b.center = a.center;
        a = {{g.wild(a.center.x), g.wild(a.center.y)}, g.wild(a.radius)};
        b = {{g.wild(b.center.x), g.wild(b.center.y)}, g.wild(b.radius)};
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(same_bits(collide(a, b), scalar_circle_circle(a, b)));
    }
}

TEST(CircleBits, BoxCircle) {
    Draw g;
    for (int k = 0; k < 200000; ++k) {
        const float s = k % 5 == 0 ? std::pow(10.0f, g.uniform(-20.0f, 20.0f)) : g.uniform(0.5f, 20.0f);
        Obb box({g.uniform(-s, s), g.uniform(-s, s)}, {g.uniform(0.0f, s), g.uniform(0.0f, s)},
                k % 4 == 0 ? 0.0f : g.uniform(-7.0f, 7.0f));
        Circle c{{g.uniform(-2.0f, 2.0f) * s, g.uniform(-2.0f, 2.0f) * s}, g.uniform(0.0f, s)};
        if (k % 3 == 0) {  // integers and quarter turns: centres exactly on faces and corners
            box = Obb({std::round(box.center.x), std::round(box.center.y)},
                      {std::round(box.half.x), std::round(box.half.y)}, k % 2 == 0 ? 0.0f : test::kPi / 2.0f);
            c = {{std::round(c.center.x), std::round(c.center.y)}, std::round(c.radius)};
        }
        box = Obb({g.wild(box.center.x), g.wild(box.center.y)}, {g.wild(box.half.x), g.wild(box.half.y)},
                  box.angle());
        c = {{g.wild(c.center.x), g.wild(c.center.y)}, g.wild(c.radius)};
        SCOPED_TRACE(testing::Message() << "case " << k);
        ASSERT_TRUE(same_bits(collide(box, c), scalar_obb_circle(box, c)));
        const Aabb aabb{box.center - box.half, box.center + box.half};
        ASSERT_TRUE(same_bits(collide(aabb, c), scalar_aabb_circle(aabb, c)));
    }
}

}  // namespace
}  // namespace jostle
