// tests/fuzz/collision_fuzz.cpp: fuzzes the collision module's generic dispatch (collide,
// overlaps, cast, sweep, closest_point, bounds, contacts) with two shapes of any kind built from
// the input bytes: small grid values (touching, coincident, degenerate), special floats (NaN,
// infinities, huge, denormal, -0) and raw float bits, optionally scaled and moved far out.
//
// Every input: results are defined (collision.h, TOLERANCES): a miss is all zeros, a hit has a
// finite depth >= 0 and a unit normal, t in [0, 1]; a shape with a NaN or infinite coordinate
// hits nothing; overlaps() agrees with collide().hit; a mask's MTD against a convex shape is the
// same with and without the search's shortcuts.
// Finite, well-formed, non-mask inputs within the manual's LIMITS (|x|, |y| <= 1e5): the
// module agrees with the double-precision oracle (tests/collision/oracle.h, shared with the
// property tests): the MTD separates, casts never miss a crossed shape, sweeps never tunnel.
#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "collision/oracle.h"
#include "fuzz_support.h"
#include "jostle/collision.h"

namespace jostle {
namespace {

using fuzz::fuzz_fail;
using test::D2;
using test::d2;

// The manual's LIMITS: coordinates within 1e5 px keep full precision.
constexpr float kLimit = 1e5f;

class Reader {
public:
    Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    std::uint32_t word() {
        std::uint32_t bits = 0;
        for (int i = 0; i < 4; ++i) bits = (bits << 8) | byte();
        return bits;
    }
    float raw() { return std::bit_cast<float>(word()); }
    // A float: mostly quarter steps in [-24, 24) (so shapes touch, coincide and degenerate),
    // sometimes a special value, sometimes any bit pattern.
    float number() {
        const std::uint8_t tag = byte();
        if (tag < 0xc0) return static_cast<float>(static_cast<int>(tag) - 96) / 4.0f;
        if (tag < 0xe0) {
            static constexpr float special[] = {
                0.0f, -0.0f, std::numeric_limits<float>::quiet_NaN(), INFINITY, -INFINITY, FLT_MAX, -FLT_MAX,
                FLT_MIN, std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
                1e5f, -1e5f, 99999.99f, 1e-30f, 1e30f, 0.5f, 1e-7f, 3.14159265f, 1.5707964f, 1e6f, -1e6f,
                16777216.0f, 1.0f + FLT_EPSILON, 1e-3f};
            return special[(tag - 0xc0) % std::size(special)];
        }
        return raw();
    }
    int integer() {
        const std::uint8_t tag = byte();
        if (tag < 0xf0) return static_cast<int>(tag) - 120;
        static constexpr int special[] = {std::numeric_limits<int>::max(), std::numeric_limits<int>::min(),
                                          std::numeric_limits<int>::max() - 3, std::numeric_limits<int>::min() + 3,
                                          100000, -100000, 1 << 30, -(1 << 30)};
        if (tag < 0xf8) return special[tag - 0xf0];
        return std::bit_cast<int>(word());
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

// How the input places coordinates: scaled, then moved (to reach the LIMITS' far corners).
struct Frame {
    float scale = 1.0f;
    float offset = 0.0f;
    Vec2 point(Reader& r) const { return {r.number() * scale + offset, r.number() * scale + offset}; }
    Vec2 vector(Reader& r) const { return {r.number() * scale, r.number() * scale}; }
    float length(Reader& r) const { return r.number() * scale; }
};

Frame read_frame(Reader& r) {
    static constexpr float scales[] = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f / 64, 64.0f, 1e-4f, 4000.0f};
    static constexpr float offsets[] = {0.0f, 0.0f, 0.0f, 0.0f, 1e4f, -1e5f + 64, 1e5f - 64, 0.5f};
    const std::uint8_t b = r.byte();
    return {scales[b & 7], offsets[(b >> 3) & 7]};
}

Shape read_shape(Reader& r, const Frame& f, Mask& mask_storage) {
    switch (r.byte() % 6) {
        case 0: {
            const Vec2 a = f.point(r);
            return Aabb{a, a + f.vector(r)};  // may be malformed (min > max): a defined miss
        }
        case 1: {
            const Vec2 c = f.point(r);
            const Vec2 h = f.vector(r);
            return Obb{c, h, r.number()};
        }
        case 2: {
            const std::uint8_t mode = r.byte();
            const int n = 3 + mode % 14;
            std::array<Vec2, kMaxPolygonVertices> pts{};
            if (mode & 0x80) {
                for (int i = 0; i < n; ++i) pts[static_cast<std::size_t>(i)] = f.point(r);
            } else {
                // Around an ellipse: usually convex, so the fuzzer reaches polygon code quickly.
                const Vec2 c = f.point(r);
                const float rx = f.length(r), ry = f.length(r), turn = r.number();
                for (int i = 0; i < n; ++i) {
                    const float a = turn + 6.2831853f * static_cast<float>(i) / static_cast<float>(n);
                    pts[static_cast<std::size_t>(i)] = (mode & 0x40 ? Vec2{} : c) + Vec2{rx * std::cos(a), ry * std::sin(a)};
                }
                // Or made about the origin, then turned and moved in float as the world places its
                // colliders (the rounded vertices may be a rounding off convex).
                if (mode & 0x40) {
                    const Polygon local =
                        make_polygon(std::span<const Vec2>(pts.data(), static_cast<std::size_t>(n))).value_or(Polygon{});
                    return local.transformed({c, Rot::from_angle(r.number())});
                }
            }
            return make_polygon(std::span<const Vec2>(pts.data(), static_cast<std::size_t>(n))).value_or(Polygon{});
        }
        case 3: {
            const Vec2 c = f.point(r);
            return Circle{c, f.length(r)};
        }
        case 4: {
            const Vec2 a = f.point(r);
            return Segment{a, f.point(r)};
        }
        default: {
            const int w = r.byte() % 9, h = r.byte() % 9;  // 0 x 0 masks too
            mask_storage = Mask(w, h);
            for (int y = 0; y < h; ++y) {
                const std::uint8_t bits = r.byte();
                for (int x = 0; x < w; ++x) mask_storage.set(x, y, (bits >> x) & 1);
            }
            const int x = r.integer();
            return PlacedMask{&mask_storage, x, r.integer()};
        }
    }
}

std::string describe_all(const Shape& a, const Shape& b, const std::string& more) {
    return test::describe(a) + " / " + test::describe(b) + (more.empty() ? "" : ": " + more);
}

std::string f2s(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}
std::string v2s(Vec2 v) {
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "(" + string.
    std::string s = "(";
    s += f2s(v.x);
    s += ", ";
    s += f2s(v.y);
    s += ")";
    return s;
}

bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool is_unit(Vec2 v) { return finite(v) && std::fabs(std::hypot(v.x, v.y) - 1.0f) <= 1e-4f; }
bool zero(Vec2 v) { return v.x == 0.0f && v.y == 0.0f; }

// Every coordinate of the shape (for masks: its pixel rectangle's corners).
std::vector<float> coordinates(const Shape& s) {
    std::vector<float> out;
    auto add = [&](Vec2 v) {
        out.push_back(v.x);
        out.push_back(v.y);
    };
    if (const auto* a = std::get_if<Aabb>(&s)) add(a->min), add(a->max);
    if (const auto* o = std::get_if<Obb>(&s)) add(o->center), add(o->half), out.push_back(o->angle());
    if (const auto* p = std::get_if<Polygon>(&s)) for (Vec2 v : p->points()) add(v);
    if (const auto* c = std::get_if<Circle>(&s)) add(c->center), out.push_back(c->radius);
    if (const auto* g = std::get_if<Segment>(&s)) add(g->a), add(g->b);
    return out;
}

bool all_finite(const Shape& s) {
    const auto c = coordinates(s);
    return std::all_of(c.begin(), c.end(), [](float v) { return std::isfinite(v); });
}

// Within the manual's LIMITS and well formed (the oracle's domain): no mask, no empty polygon,
// min <= max, half extents and radius >= 0, and every coordinate (angles too) within 1e5. A
// polygon turned and moved in float must still pass make_polygon or have collapsed to one
// point (smaller than the float spacing where it lies: the oracle's point, and the module's);
// where rounding has made it flat or reversed at a vertex (tried without this rule: a thin
// 11-gon at 1e5 px, not convex at a vertex, gave a depth 0.38 px from the oracle's), its
// normals no longer describe its vertices, and the manual promises only a defined result
// (Polygon::moved; LIMITS).
// The same holds, vertices still convex, where a turn between neighbouring faces is no larger
// than the vertices' rounding can tilt a face (the float spacing over the shorter face): the
// manual's "a turn smaller than that rounding can come out flat or reversed". The turned
// normals then disagree with the rounded vertices by as much as the turn, and which face is
// the nearest is decided by rounding (found by CI's 60 s run: 11-gon slivers 0.013 px thick
// turned to 1e4, their faces 2e-4 rad apart, gave depths 0.06 and 0.1 px from the oracle's).
// A polygon made in place (its normals its own vertices') stays under the oracle.
bool collapsed_to_a_point(const Polygon& p) {
    return std::all_of(p.points().begin(), p.points().end(), [&](Vec2 v) { return v == p.points()[0]; });
}
bool turned_within_rounding(const Polygon& p) {
    const std::optional<Polygon> own = make_polygon(p.points());
    if (!own || std::equal(own->normals().begin(), own->normals().end(), p.normals().begin())) return false;
    const int n = p.count();
    float mag = 0.0f;
    for (const Vec2 v : p.points()) mag = std::max({mag, std::fabs(v.x), std::fabs(v.y)});
    const double spacing = static_cast<double>(FLT_EPSILON) * mag;
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n, k = (i + 2) % n;
        const double shorter = std::min(test::dlen(d2(p.points()[j]) - d2(p.points()[i])),
                                        test::dlen(d2(p.points()[k]) - d2(p.points()[j])));
        const double turn = static_cast<double>(cross(p.normals()[i], p.normals()[j]));
        if (turn < 4.0 * spacing / shorter) return true;
    }
    return false;
}
bool in_limits(const Shape& s) {
    if (std::holds_alternative<PlacedMask>(s)) return false;
    if (const auto* p = std::get_if<Polygon>(&s);
        p && (p->count() == 0 || !(make_polygon(p->points()).has_value() || collapsed_to_a_point(*p)) ||
              turned_within_rounding(*p)))
        return false;
    if (const auto* a = std::get_if<Aabb>(&s); a && !(a->min.x <= a->max.x && a->min.y <= a->max.y)) return false;
    if (const auto* o = std::get_if<Obb>(&s); o && !(o->half.x >= 0 && o->half.y >= 0)) return false;
    if (const auto* c = std::get_if<Circle>(&s); c && !(c->radius >= 0)) return false;
    const auto c = coordinates(s);
    return std::all_of(c.begin(), c.end(), [](float v) { return std::isfinite(v) && std::fabs(v) <= kLimit; });
}

float magnitude(const Shape& s) {
    float m = 0.0f;
    for (float v : coordinates(s)) m = std::max(m, std::fabs(v));
    return m;
}

// The oracle's tolerance: 1e-4 of the sizes involved (the manual's LIMITS), plus the rounding of
// a float at the coordinates' magnitude (1/128 px at 1e5), which no computation in float avoids.
double tolerance(double size, double mag) { return 2e-4 * size + 16.0 * FLT_EPSILON * mag + 1e-6; }

// LIMITS: a half-plane test's rounding (about a float of the coordinates' magnitude) moves a
// cast's or sweep's answer near a polygon corner of interior angle theta by up to that much
// / sin theta along the corner: at a sliver's sharp tip (theta ~ 1e-6 rad) float cannot place
// the tip closer than pixels. The oracle's slack for it (0 for corners of 90 degrees or more,
// which the rounding term of tolerance() already covers).
double corner_slack(const Shape& s, double mag) {
    const auto* p = std::get_if<Polygon>(&s);
    if (!p) return 0.0;
    const int n = p->count();
    double sharpest = 1.0;
    for (int i = 0; i < n; ++i) {
        const D2 e0 = d2(p->points()[static_cast<std::size_t>((i + 1) % n)]) - d2(p->points()[static_cast<std::size_t>(i)]);
        const D2 e1 = d2(p->points()[static_cast<std::size_t>((i + 2) % n)]) - d2(p->points()[static_cast<std::size_t>((i + 1) % n)]);
        const double sine = std::fabs(test::dcross(e0, e1)) / (test::dlen(e0) * test::dlen(e1));  // of the turn, = of the corner
        if (sine < sharpest) sharpest = sine;
    }
    return sharpest >= 1.0 ? 0.0 : 16.0 * FLT_EPSILON * mag / std::max(sharpest, 1e-30);
}

// Does the oracle have anything to say? Two shapes without area or length on any axis (points)
// give it no axis.
bool oracle_applies(const Shape& a, const Shape& b) {
    if (std::holds_alternative<Circle>(a) || std::holds_alternative<Circle>(b)) return true;
    std::vector<D2> axes;
    test::add_axes(test::vertices(a), axes);
    test::add_axes(test::vertices(b), axes);
    return !axes.empty();
}

void check_manifold(const Manifold& m, const Shape& a, const Shape& b, const char* what) {
    if (!m.hit) {
        if (m.depth != 0.0f || !zero(m.normal)) fuzz_fail(std::string(what) + ": a miss with non-zero fields: " + describe_all(a, b, ""));
        return;
    }
    if (!std::isfinite(m.depth) || !(m.depth >= 0.0f) || !is_unit(m.normal)) {
        fuzz_fail(std::string(what) + ": a hit with depth " + f2s(m.depth) + " normal " + v2s(m.normal) + ": " +
                  describe_all(a, b, ""));
    }
    if (!all_finite(a) || !all_finite(b)) fuzz_fail(std::string(what) + ": a non-finite shape hit: " + describe_all(a, b, ""));
}

template <class Hit>
void check_contact(const Hit& h, const std::string& what) {
    if (!h.hit) {
        if (h.t != 0.0f || !zero(h.point) || !zero(h.normal)) fuzz_fail(what + ": a miss with non-zero fields");
        return;
    }
    if (!(h.t >= 0.0f && h.t <= 1.0f) || !finite(h.point) || !(zero(h.normal) || is_unit(h.normal))) {
        fuzz_fail(what + ": hit with t " + f2s(h.t) + " point " + v2s(h.point) + " normal " + v2s(h.normal));
    }
}

void collide_properties(const Shape& a, const Shape& b) {
    const Manifold m = collide(a, b);
    check_manifold(m, a, b, "collide");
    check_manifold(collide(b, a), b, a, "collide (reversed)");
    if (overlaps(a, b) != m.hit) fuzz_fail("overlaps != collide().hit: " + describe_all(a, b, ""));
    if (!in_limits(a) || !in_limits(b) || !oracle_applies(a, b)) return;
    const double size = std::max(test::shape_size(a), test::shape_size(b));
    // LIMITS: a shape below 1e-4 of the other's size or of their distance is a point to float.
    const Aabb ba = bounds(a), bb = bounds(b);
    const double distance = test::dlen(0.5 * (d2(ba.min) + d2(ba.max)) - 0.5 * (d2(bb.min) + d2(bb.max)));
    const double smallest = std::min(test::shape_size(a), test::shape_size(b));
    if (smallest > 0 && smallest < 1e-4 * std::max(size, distance)) return;
    const double tol = tolerance(size, std::max(magnitude(a), magnitude(b)));
    const double pen = test::penetration(a, b);
    const std::string ctx = describe_all(a, b, "hit " + std::to_string(m.hit) + " depth " + f2s(m.depth) + " normal " +
                                                   v2s(m.normal) + ", oracle penetration " + f2s(pen) + ", tolerance " + f2s(tol));
    if (pen > tol && (!m.hit || std::fabs(m.depth - pen) > tol)) fuzz_fail("depth differs from the oracle: " + ctx);
    if (pen < -tol && m.hit) fuzz_fail("a hit where the oracle separates: " + ctx);
    if (m.hit) {
        const Shape moved = test::moved(a, m.mtd());
        if (!in_limits(moved)) return;
        const double after = test::penetration(moved, b);
        if (after > tol) fuzz_fail("after moving A by mtd() the penetration is " + f2s(after) + ": " + ctx);
    }
}

void cast_properties(Vec2 from, Vec2 to, const Shape& b) {
    const CastHit h = cast(from, to, b);
    const std::string what = "cast " + v2s(from) + " -> " + v2s(to) + " vs " + test::describe(b) + ": hit " +
                             std::to_string(h.hit) + " t " + f2s(h.t) + " point " + v2s(h.point);
    check_contact(h, what);
    if (h.hit && (!finite(from) || !finite(to) || !all_finite(b))) fuzz_fail(what + ": non-finite input hit");
    if (!in_limits(b) || std::holds_alternative<Segment>(b) || !in_limits(Segment{from, to})) return;
    const double mag = std::max({magnitude(b), magnitude(Segment{from, to})});
    const double tol = tolerance(test::shape_size(b) + length(to - from), mag) + corner_slack(b, mag);
    constexpr int kSamples = 64;
    for (int k = 0; k <= kSamples; ++k) {
        const double tau = static_cast<double>(k) / kSamples;
        const D2 p = d2(from) + tau * (d2(to) - d2(from));
        if (test::signed_distance(b, p) < -tol) {
            if (!h.hit || h.t > tau + 1e-5) fuzz_fail(what + ": misses sample " + std::to_string(k) + " inside the shape (tolerance " + f2s(tol) + ")");
            break;
        }
    }
}

void sweep_properties(const Circle& a, Vec2 va, const Shape& b, Vec2 vb) {
    const SweepHit s = sweep(a, va, b, vb);
    const std::string what = "sweep " + test::describe(a) + " by " + v2s(va) + " vs " + test::describe(b) + " by " +
                             v2s(vb) + ": hit " + std::to_string(s.hit) + " t " + f2s(s.t) + " point " + v2s(s.point);
    check_contact(s, what);
    if (s.hit && !is_unit(s.normal)) fuzz_fail(what + ": a sweep hit without a unit normal");
    if (!in_limits(a) || !in_limits(b) || !in_limits(Segment{va, vb})) return;
    const Vec2 rel = va - vb;
    if (!in_limits(Segment{a.center, a.center + rel})) return;
    if (a.radius == 0.0f && std::holds_alternative<Segment>(b)) return;  // a point against a line: measure zero
    const double mag = std::max({magnitude(a), magnitude(b), magnitude(Segment{va, vb})});
    const double tol = tolerance(std::max(test::shape_size(b), 2.0f * a.radius) + length(rel), mag) + corner_slack(b, mag);
    auto gap_at = [&](double tau) {
        const D2 c = d2(a.center) + tau * d2(rel);
        return test::signed_distance(b, c) - a.radius;
    };
    if (gap_at(0.0) <= tol) {
        // In contact at the start (within the tolerance, which may leave a gap the sweep then
        // closes at t > 0): the moving-away rule decides whether it is a hit (property tests);
        // a hit at t = 0 has its point where the circle's surface meets B along the normal, on
        // B (a mask's MTD is whole pixels, not the distance: its point may lie inside).
        if (s.hit && s.t == 0.0f && !std::holds_alternative<PlacedMask>(b) &&
            std::fabs(test::signed_distance(b, d2(s.point))) > tol) {
            fuzz_fail(what + ": in contact at the start, the point is " + f2s(test::signed_distance(b, d2(s.point))) +
                      " from B (tolerance " + f2s(tol) + ")");
        }
        return;
    }
    // Never tunnels: no overlap deeper than the tolerance before t (or along the whole path on a miss).
    const double end = s.hit ? static_cast<double>(s.t) : 1.0;
    constexpr int kSamples = 64;
    for (int k = 0; k < kSamples || (!s.hit && k == kSamples); ++k) {
        const double tau = end * k / kSamples;
        if (gap_at(tau) < -tol) fuzz_fail(what + ": overlap " + f2s(gap_at(tau)) + " at " + f2s(tau) + " (tolerance " + f2s(tol) + ")");
    }
    if (s.hit && std::fabs(gap_at(s.t)) > tol) fuzz_fail(what + ": gap at t is " + f2s(gap_at(s.t)) + " (tolerance " + f2s(tol) + ")");
}

void contact_set_properties(const Shape& a, const Shape& b) {
    ContactSet cs;
    const auto* oa = std::get_if<Obb>(&a);
    const auto* ob = std::get_if<Obb>(&b);
    const auto* pa = std::get_if<Polygon>(&a);
    const auto* pb = std::get_if<Polygon>(&b);
    if (oa && ob) {
        cs = contacts(*oa, *ob);
    } else if (pa && pb) {
        cs = contacts(*pa, *pb);
    } else {
        return;
    }
    check_manifold(cs.manifold, a, b, "contacts");
    if (cs.count < 0 || cs.count > 2 || (cs.manifold.hit != (cs.count > 0))) {
        fuzz_fail("contacts: " + std::to_string(cs.count) + " points for hit " + std::to_string(cs.manifold.hit) + ": " + describe_all(a, b, ""));
    }
    for (int k = 0; k < cs.count; ++k) {
        const float d = cs.depths[static_cast<std::size_t>(k)];
        if (!finite(cs.points[static_cast<std::size_t>(k)]) || !std::isfinite(d) || d < 0.0f) {
            fuzz_fail("contacts: point " + std::to_string(k) + " not finite or negative depth: " + describe_all(a, b, ""));
        }
    }
}

}  // namespace
}  // namespace jostle

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace jostle;
    Reader r(data, size);
    const Frame frame = read_frame(r);
    Mask mask_a, mask_b;
    const Shape a = read_shape(r, frame, mask_a);
    const Shape b = read_shape(r, frame, mask_b);
    // LIMITS: a mask's MTD takes time in proportion to the push it finds (about 1 ms per
    // 1,000 px), so a mask deep inside a shape far beyond the coordinate limit is slow by
    // design (a 1e6 px polygon: 0.5 s, 12 s under the sanitizers), not a hang to report.
    const auto beyond = [](const Shape& s) {
        const auto c = coordinates(s);
        return std::any_of(c.begin(), c.end(), [](float v) { return std::isfinite(v) && std::fabs(v) > kLimit; });
    };
    const bool slow_mask_mtd = (std::holds_alternative<PlacedMask>(a) && beyond(b)) ||
                               (std::holds_alternative<PlacedMask>(b) && beyond(a));
    if (!slow_mask_mtd) {
        collide_properties(a, b);
        contact_set_properties(a, b);
        // A mask against a convex shape: the search's shortcuts give the plain scan's answer.
        const bool a_is_mask = std::holds_alternative<PlacedMask>(a), b_is_mask = std::holds_alternative<PlacedMask>(b);
        if (a_is_mask != b_is_mask && !std::holds_alternative<Segment>(a_is_mask ? b : a)) {
            const Manifold fast = collide(a, b);
            detail::use_mask_search_shortcuts(false);
            const Manifold plain = collide(a, b);
            detail::use_mask_search_shortcuts(true);
            if (fast.hit != plain.hit || std::bit_cast<std::uint32_t>(fast.depth) != std::bit_cast<std::uint32_t>(plain.depth) ||
                std::bit_cast<std::uint64_t>(fast.normal) != std::bit_cast<std::uint64_t>(plain.normal)) {
                fuzz_fail("mask MTD with the search's shortcuts " + f2s(fast.depth) + " " + v2s(fast.normal) +
                          ", plain scan " + f2s(plain.depth) + " " + v2s(plain.normal) + " for " + test::describe(a) +
                          " and " + test::describe(b));
            }
        }
    }

    const Aabb box = bounds(a);
    if (all_finite(a) && !std::holds_alternative<PlacedMask>(a) && in_limits(a)) {
        // The bounds contain the shape: every oracle vertex (up to rounding).
        const double tol = tolerance(test::shape_size(a), magnitude(a));
        for (const D2& v : test::vertices(a)) {
            if (v.x < box.min.x - tol || v.x > box.max.x + tol || v.y < box.min.y - tol || v.y > box.max.y + tol) {
                fuzz_fail("bounds " + v2s(box.min) + " - " + v2s(box.max) + " leave out a vertex of " + test::describe(a));
            }
        }
    }

    const Vec2 q = frame.point(r);
    const ClosestPoint cp = closest_point(b, q);
    if (std::isnan(cp.distance) || cp.distance < 0.0f || (cp.distance < INFINITY && !finite(cp.point))) {
        fuzz_fail("closest_point " + v2s(q) + ": point " + v2s(cp.point) + " distance " + f2s(cp.distance) + " for " + test::describe(b));
    }

    const Vec2 from = frame.point(r);
    const Vec2 to = frame.point(r);
    cast_properties(from, to, a);
    cast_properties(from, to, b);

    const Vec2 c = frame.point(r);
    const Circle mover = std::holds_alternative<Circle>(a) ? std::get<Circle>(a) : Circle{c, frame.length(r)};
    const Vec2 va = frame.vector(r);
    const Vec2 vb = (r.byte() & 1) ? frame.vector(r) : Vec2{};
    sweep_properties(mover, va, b, vb);
    return 0;
}
