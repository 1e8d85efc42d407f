// Circles, slides 09-70 to 09-102: circle-circle by squared distances, polygon-circle by the
// closest point on the boundary and by SAT with the centre-to-vertex axis, box-circle by
// the "push in" clamp, segment-circle. The slides test "< r" (09-71, 09-87); here touching
// (== r) is a hit with depth 0, the convention for every pair.
#include <cfloat>
#include <bit>
#include <cmath>
#include <cstring>

#include "internal.h"

namespace jostle {

using detail::hit_with;
using detail::valid;

namespace {
// collide(Circle, Circle) past its distance test, kept out of line (a tail call) so that the
// miss, the common answer, is a short function whose {} needs no packing of a hit's fields.
[[gnu::noinline]] Manifold circle_circle_near(const Circle& a, const Circle& b, float dx, float dy,
                                              float dist2, float r) {
    // The radii as valid(Circle) checks them (r >= 0 and r^2 finite, so r1 + r2 is finite and
    // so is the depth), in one test; an infinite dist2 (r^2 may overflow) is a miss too.
    if (!((a.radius >= 0.0f) & (a.radius * a.radius < INFINITY) & (b.radius >= 0.0f) &
          (b.radius * b.radius < INFINITY) & (dist2 != INFINITY)))
        return {};
    // 09-72: mtd = (c1 - c2)/|c1 - c2| (r1 + r2 - |c1 - c2|) = -depth * normal. Coincident
    // centres have no direction; {1, 0} is the defined one (as in Box2D). One square root for
    // the depth and the normal, in every lane (SQRTPS: each lane std::sqrt's value), so that
    // one DIVPS divides both components (each lane the scalar division's quotient).
    using detail::Float4;
    const Float4 len = detail::sqrt_nonneg(Float4{dist2, dist2, dist2, dist2});
    Float4 n = {1.0f, 0.0f, 1.0f, 0.0f};
    if (dist2 >= 0x1p-126f) {
        n = detail::plain_zeros(Float4{dx, dy, dx, dy} / len);
    } else if (dist2 > 0.0f) [[unlikely]] {
        // A denormal dist2 lost bits (its root is off by up to a few percent): the direction
        // rescaled (fuzz: a normal 1.05 long).
        const Vec2 u = detail::normalize_rescaled(Vec2{dx, dy}, Vec2{1.0f, 0.0f});
        n = detail::plain_zeros(Float4{u.x, u.y, u.x, u.y});
    }
    // hit_with without its finiteness test, which cannot fail here: r is finite (valid
    // radii), so are dist2 (tested), d (d.x^2 <= dist2) and len, and |d.x| / len is at most
    // about 1 (dist2 >= fl(d.x^2); a dist2 rounded to 0 takes the {1, 0} branch).
    const float depth = r - len[0];
    Manifold m;
    m.hit = true;
    m.depth = depth > 0.0f ? depth : 0.0f;
    std::memcpy(static_cast<void*>(&m.normal), &n, sizeof m.normal);  // lanes 0 and 1, kept in a register
    return m;
}
}  // namespace

Manifold collide(const Circle& a, const Circle& b) {
    // 09-71: compare squared distances, so no square root for a miss. The radii are checked
    // only for an answer that would be a hit (an invalid circle is a miss, and the arithmetic
    // on any input is defined): a NaN or infinite centre makes dist2 NaN or infinite, which
    // the comparison here or the test of dist2 there turns into a miss.
    const Vec2 d = b.center - a.center;
    const float dist2 = dot(d, d);
    const float r = a.radius + b.radius;
    if (!(dist2 <= r * r)) return {};
    return circle_circle_near(a, b, d.x, d.y, dist2, r);
}

namespace {
using detail::Float4;
using detail::Int4;

// A pair of floats (Vec2, Rot) in lanes 0 and 1 and zeros above (one 8-byte MOVQ load).
template <class Pair>
inline Float4 lanes_xy(const Pair& v) {
    static_assert(sizeof(Pair) == 8);
#if defined(__SSE2__)
    return reinterpret_cast<Float4>(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&v)));
#else
    float f[2];
    std::memcpy(f, static_cast<const void*>(&v), sizeof f);
    return Float4{f[0], f[1], 0.0f, 0.0f};
#endif
}

// The slots of a 4-slot group past the first `live` (0..4): all bits set, which OR-ed into a
// float makes it NaN, a value no comparison picks.
constexpr Int4 kDeadSlots[5] = {
    {-1, -1, -1, -1}, {0, -1, -1, -1}, {0, 0, -1, -1}, {0, 0, 0, -1}, {0, 0, 0, 0}};
inline Float4 dead_to_nan(Float4 v, int live) {
    return reinterpret_cast<Float4>(reinterpret_cast<Int4>(v) | kDeadSlots[live]);
}

// Slots 4k..4k+3 of a Polygon's arrays (x, y, x, y: two 16-byte loads each; every Polygon has
// 16 slots, so the loads stay inside it), each slot's x and y terms summed in the scalar
// order, x term + y term: lane j is then the scalar value for slot 4k + j bit for bit.
// `terms` gives each slot's two terms from the points (and normals) of two slots; the caller
// turns the slots past the last vertex into NaN.
template <class Terms>
inline Float4 slot_quad(const Polygon& poly, int k, Terms&& terms) {
    Float4 p0, p1, u0, u1;
    std::memcpy(&p0, poly.points().data() + 4 * k, sizeof p0);
    std::memcpy(&p1, poly.points().data() + 4 * k + 2, sizeof p1);
    std::memcpy(&u0, poly.normals().data() + 4 * k, sizeof u0);
    std::memcpy(&u1, poly.normals().data() + 4 * k + 2, sizeof u1);
    const Float4 m0 = terms(p0, u0), m1 = terms(p1, u1);
    return __builtin_shufflevector(m0, m1, 0, 2, 4, 6) + __builtin_shufflevector(m0, m1, 1, 3, 5, 7);
}

// dot(n_i, c - p_i) for faces 4k..4k+3.
inline Float4 face_separations(const Polygon& poly, Float4 cc, int k) {
    return slot_quad(poly, k, [cc](Float4 p, Float4 u) { return u * (cc - p); });
}

// |c - p_i|^2 as dot(o, o), o = c - p_i, for vertices 4k..4k+3.
inline Float4 vertex_distances(const Polygon& poly, Float4 cc, int k) {
    return slot_quad(poly, k, [cc](Float4 p, Float4) {
        const Float4 o = cc - p;
        return o * o;
    });
}

// Each lane's larger value, `s > top ? s : top` as a loop keeps it (a NaN s never wins): MAXPS,
// written out because GCC compiles the expression with a constant `top` into a compare and
// a blend.
inline Float4 lane_max(Float4 s, Float4 top) {
#if defined(__SSE__)
    return reinterpret_cast<Float4>(_mm_max_ps(reinterpret_cast<__m128>(s), reinterpret_cast<__m128>(top)));
#else
    return s > top ? s : top;
#endif
}

// Each lane's largest of the four groups' (-inf for a lane of NaNs).
inline Float4 lanes_max(Float4 s0, Float4 s1, Float4 s2, Float4 s3) {
    const Float4 none = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
    return lane_max(s3, lane_max(s2, lane_max(s1, lane_max(s0, none))));
}

// The separations of a polygon's faces, four to a register (up to 16 faces: NaN in the slots
// past the last face; the groups past the last are copies of s0, which change neither the
// maximum nor the first face at it), and each lane's largest (-inf for a lane of NaNs).
struct FaceSeparations {
    Float4 s0, s1, s2, s3, top;
};
inline FaceSeparations face_separations(const Polygon& poly, Float4 cc) {
    FaceSeparations f;
    const int n = poly.count();
    const Float4 none = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
    f.s0 = face_separations(poly, cc, 0);
    if (n <= 4) {
        f.s0 = dead_to_nan(f.s0, n);
        f.s1 = f.s2 = f.s3 = f.s0;
        f.top = lane_max(f.s0, none);
    } else {
        f.s1 = face_separations(poly, cc, 1);
        if (n <= 8) {
            f.s1 = dead_to_nan(f.s1, n - 4);
            f.s2 = f.s3 = f.s0;
            f.top = lane_max(f.s1, lane_max(f.s0, none));
        } else {
            f.s2 = face_separations(poly, cc, 2);
            if (n <= 12) {
                f.s2 = dead_to_nan(f.s2, n - 8);
                f.s3 = f.s0;
            } else {
                f.s3 = dead_to_nan(face_separations(poly, cc, 3), n - 12);
            }
            f.top = lanes_max(f.s0, f.s1, f.s2, f.s3);
        }
    }
    return f;
}

// How far the point is outside the farthest face (the edge normals as separating axes, 09-95:
// a separation past r is a gap): the largest of the
// lanes' maxima. Only the sign of a zero maximum may depend on the order of the search, which
// no use of it can tell (r - max_sep is +-0 either way, and a zero depth is returned as +0).
inline float largest(Float4 top) {
    top = lane_max(__builtin_shufflevector(top, top, 2, 3, 2, 3), top);
    return top[1] > top[0] ? top[1] : top[0];
}

// The first face whose separation is `most` (from lane masks, with no branch on the data): the
// face a loop keeping the first strict maximum would name, or 0 when every face is NaN. s2 and
// s3 are copies of s0 for 8 faces or fewer (see FaceSeparations), so only past 8 are they read.
inline int first_face_at(int count, Float4 s0, Float4 s1, Float4 s2, Float4 s3, float most) {
    const Float4 m = {most, most, most, most};
    unsigned faces = detail::lane_bits(s0 == m) | detail::lane_bits(s1 == m) << 4;
    if (count > 8) faces |= detail::lane_bits(s2 == m) << 8 | detail::lane_bits(s3 == m) << 12;
    return faces == 0 ? 0 : std::countr_zero(faces);
}

// The vertex nearest the point and its squared distance: the first i of least dot(o, o),
// o = c - p_i (a loop keeping the first strict minimum), dist2 = +inf and vertex 0 when every
// distance overflows. Four vertices a step, each lane keeping its own first minimum, so
// neither a branch per vertex nor a second pass is needed.
struct NearestVertex {
    float dist2 = INFINITY;
    int vertex = 0;
};
inline NearestVertex nearest_vertex(const Polygon& poly, Float4 cc) {
    Float4 best = {INFINITY, INFINITY, INFINITY, INFINITY};
    Int4 index = {0, 0, 0, 0};
    Int4 at = {0, 1, 2, 3};
    for (int k = 0; k < (poly.count() + 3) / 4; ++k) {
        const int live = poly.count() - 4 * k;
        const Float4 d2 = dead_to_nan(vertex_distances(poly, cc, k), live < 4 ? live : 4);
        const Int4 closer = d2 < best;
        best = closer ? d2 : best;
        index = closer ? at : index;
        at += 4;
    }
    // The lanes' minima, lanes 2 and 3 against 0 and 1, then lane 1 against lane 0: the
    // smaller distance, or on a tie the smaller index (lane masks: which lane wins is data,
    // too random for a branch).
    const auto fold = [&](Float4 b_other, Int4 i_other) {
        const Int4 take = (b_other < best) | ((b_other == best) & (i_other < index));
        best = take ? b_other : best;
        index = take ? i_other : index;
    };
    fold(__builtin_shufflevector(best, best, 2, 3, 2, 3), __builtin_shufflevector(index, index, 2, 3, 2, 3));
    fold(__builtin_shufflevector(best, best, 1, 1, 1, 1), __builtin_shufflevector(index, index, 1, 1, 1, 1));
    return {best[0], index[0]};
}

// A hit for the polygon-circle pair: hit_with(depth, n) with n in lanes 0-1 of `normal`, and
// valid(b) asked here, of a would-be hit only. Every normal offered is finite (a face's, or the
// centre's direction from a vertex within r, which is finite), so the test of finiteness is
// of the depth and of r^2 (so r is finite), in one sum of x - x terms (see detail::all_finite),
// and r >= 0 beside it. A centre that is not finite needs no test of its own: every separation
// is then +-inf or NaN, so either the early out takes it (+inf > r) or the largest is -inf, and
// the depth r + inf is not finite.
inline Manifold polygon_circle_hit(const Circle& b, float depth, Float4 normal) {
    const float r2 = b.radius * b.radius;
    if (!(((depth - depth) + (r2 - r2) == 0.0f) & (b.radius >= 0.0f))) return {};
    const Float4 n = detail::plain_zeros(normal);
    return Manifold{true, depth > 0.0f ? depth : 0.0f, Vec2{n[0], n[1]}};
}

// d / |d| as polygon_circle_answer forms the direction from the nearest vertex (its lanes
// do the same arithmetic), given d2 = |d|^2 and len = sqrt(d2): rescaled when d2 is denormal
// (the root lost bits), `fallback` when d is zero or its length overflowed.
Vec2 direction_of(Vec2 d, float d2, float len, Vec2 fallback) {
    if (d2 >= 0x1p-126f && len < INFINITY) return Vec2{d.x / len, d.y / len};
    if (d2 > 0.0f && d2 < 0x1p-126f) return detail::normalize_rescaled(d, fallback);
    return fallback;
}

// The contact through a neighbour of `vertex`, the nearest vertex, when the direction from
// `vertex` lies outside its cone: two vertices that float cannot tell apart (across a face
// shorter than their coordinates' rounding: fuzz, a face 1.8e-41 px long) tie in the search,
// the first wins, and the direction lies in the other's cone; that vertex is the contact. The
// tied vertices are walked forward, then backward, as far as they tie: a polygon turned and
// moved in float can collapse to one point (smaller than the float spacing where it lies),
// and then the vertex whose cone holds the direction may be any of them. No hit when none
// does. Out of line: the common path keeps its registers (inlined, it made
// collide(Polygon, Circle) 12-25% slower).
[[gnu::noinline, gnu::cold]] Manifold tied_neighbour_contact(const Polygon& a, const Circle& b, int vertex, float dist2,
                                                             Vec2 fallback) {
    const int count = a.count();
    for (int step = 1, other = vertex, walked = 0; walked < 2 * (count - 1); ++walked) {
        other = step > 0 ? detail::next_index(other, count) : detail::prev_index(other, count);
        const Vec2 d = b.center - a.points()[other];
        const float d2 = d.x * d.x + d.y * d.y;
        if (!(d2 <= dist2) || other == vertex) {  // the forward run ends: walk back from vertex
            if (step < 0) break;
            step = -1;
            other = vertex;
            continue;
        }
        const float len = detail::sqrt_nonneg(d2);
        const Vec2 u = direction_of(d, d2, len, fallback);
        const Vec2 n_prev = a.normals()[detail::prev_index(other, count)];
        const Vec2 n_next = a.normals()[other];
        if (cross(n_prev, u) >= 0.0f && cross(u, n_next) >= 0.0f) return polygon_circle_hit(b, b.radius - len, lanes_xy(u));
    }
    return {};
}

// The contact by 09-90 as the slide writes it, the closest point of the boundary found over
// every edge, for the centre whose direction from the nearest vertex lies outside that
// vertex's cone: one of the searches by features lost to rounding, and which feature is the
// contact is then the question. The faces' normals (turned in float) and the squared distances
// (rounded at the centre's distance) both decided it, and either can be wrong:
// - a face lost the largest-separation search (fuzz: an 11-gon sliver 0.013 px thick turned and
//   moved to 1e4 in float, the centre 0.57 px along the face and 1.8 px from its line);
// - a vertex won the nearest-vertex search by rounding (fuzz: an octagon 2e-7 px across 3 px
//   from the centre, where the squared distances, about 9, round alike: the direction was 26
//   degrees outside the winner's cone, inside its neighbour's);
// - a vertex on the far side of a sliver won it (a polygon 2e-7 px thick 2 px away).
// Here the points decide, by their distances: the MTD runs from the closest point to the centre
// (its normal, for a point inside a face, that face's perpendicular as its points give it).
// `fallback` is the normal when the centre is on the boundary. Out of line, as the walk above.
[[gnu::noinline, gnu::cold]] Manifold boundary_contact(const Polygon& a, const Circle& b, Vec2 fallback) {
    int edge = 0;
    const Vec2 off = detail::offset_from_boundary(a, b.center, &edge);
    const float d2 = off.x * off.x + off.y * off.y;
    const float len = detail::sqrt_nonneg(d2);
    return polygon_circle_hit(b, b.radius - len, lanes_xy(direction_of(off, d2, len, fallback)));
}

// collide(Polygon, Circle) once the centre is within r of every face's line, given the largest
// separation max_sep, the first face at it, and the nearest-vertex search (run only if needed).
template <class Nearest>
[[gnu::always_inline]] inline Manifold polygon_circle_answer(const Polygon& a, const Circle& b, Float4 cc, float max_sep,
                                                             int max_edge, Nearest&& nearest_vertex_of) {
    const Float4 face_normal = lanes_xy(a.normals()[max_edge]);
    if (max_sep <= 0.0f) return polygon_circle_hit(b, b.radius - max_sep, face_normal);  // centre inside
    // Beside the edge of greatest separation (c projects inside it, tested from each end so
    // that a long edge rounds neither), that edge is the nearest feature: its own normal and
    // the separation are exact where normalising c - p would round.
    // Both dot products side by side: dot(c - p0, e) in lane 0, dot(c - p1, e) in lane 2.
    const Float4 p0 = lanes_xy(a.points()[max_edge]);
    const Float4 p1 = lanes_xy(a.points()[detail::next_index(max_edge, a.count())]);
    const Float4 e = p1 - p0;
    const Float4 m =
        (cc - __builtin_shufflevector(p0, p1, 0, 1, 4, 5)) * __builtin_shufflevector(e, e, 0, 1, 0, 1);
    const Float4 along = m + __builtin_shufflevector(m, m, 1, 0, 3, 2);
    if ((along[0] > 0.0f) & (along[2] < 0.0f)) return polygon_circle_hit(b, b.radius - max_sep, face_normal);
    // Otherwise the nearest feature is a vertex: the direction from it to the centre, as a
    // plain difference of points (exact for nearby floats).
    const NearestVertex nearest = nearest_vertex_of();
    const float dist2 = nearest.dist2;
    if (!(dist2 <= b.radius * b.radius)) return {};
    const int vertex = nearest.vertex;
    const Float4 d = cc - lanes_xy(a.points()[vertex]);  // lanes 0-1; used only when dist2 is finite
    // The direction: normalize_or(d, ...) with the one square root that the depth needs too,
    // and one DIVPS for both components. A direction outside the vertex's cone of normals
    // means a search lost to rounding: a tied neighbour, or else 09-90's loop, decides.
    const Vec2 n_prev = a.normals()[detail::prev_index(vertex, a.count())];
    const Vec2 n_next = a.normals()[vertex];
    const float len = detail::sqrt_nonneg(dist2);
    Float4 n4 = face_normal;
    if (dist2 >= 0x1p-126f && len < INFINITY) {
        const Float4 q = d / Float4{len, len, len, len};
        n4 = Float4{q[0], q[1], 0.0f, 0.0f};
    } else if (dist2 > 0.0f && dist2 < 0x1p-126f) [[unlikely]] {  // denormal: the root lost bits, rescale
        const Vec2 u = detail::normalize_rescaled(Vec2{d[0], d[1]}, Vec2{face_normal[0], face_normal[1]});
        n4 = Float4{u.x, u.y, 0.0f, 0.0f};
    }
    const Vec2 n{n4[0], n4[1]};
    if (cross(n_prev, n) < 0.0f || cross(n, n_next) < 0.0f) {
        if (const Manifold tied = tied_neighbour_contact(a, b, vertex, dist2, Vec2{face_normal[0], face_normal[1]}); tied.hit) return tied;
        return boundary_contact(a, b, Vec2{face_normal[0], face_normal[1]});
    }
    return polygon_circle_hit(b, b.radius - len, n4);
}

// collide(Polygon, Circle) past its early out: the centre is within r of every face's line.
// Kept out of line (a tail call, the separations in registers) so that the common early out
// is a short function with nothing to save.
[[gnu::noinline]] Manifold polygon_circle_near(const Polygon& a, const Circle& b, Float4 cc, Float4 s0,
                                               Float4 s1, Float4 s2, Float4 s3) {
    const Float4 none = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
    Float4 top = lane_max(s1, lane_max(s0, none));
    if (a.count() > 8) top = lane_max(s3, lane_max(s2, top));  // else copies of s0
    const float max_sep = largest(top);
    const int max_edge = first_face_at(a.count(), s0, s1, s2, s3, max_sep);
    return polygon_circle_answer(a, b, cc, max_sep, max_edge, [&] { return nearest_vertex(a, cc); });
}

Manifold polygon_circle(const Polygon& a, const Circle& b) {
    if (!valid(a)) return {};
    const Float4 cc = {b.center.x, b.center.y, b.center.x, b.center.y};
    const FaceSeparations f = face_separations(a, cc);
    // An edge normal separates (some lane's maximum beyond r, as the largest would be): early out.
    if (detail::lane_bits(f.top > Float4{b.radius, b.radius, b.radius, b.radius}) != 0) return {};
    return polygon_circle_near(a, b, cc, f.s0, f.s1, f.s2, f.s3);
}

#ifdef JOSTLE_AVX2_PATHS
// Per count (3..8), all bits set in the lanes (VHADDPS's order) of the slots past the last
// vertex: OR-ed into a float they make it NaN, which no comparison picks.
constexpr auto kDeadHaddLanes = [] {
    std::array<std::array<std::int32_t, 8>, 9> dead{};
    for (int count = 0; count <= 8; ++count)
        for (int lane = 0; lane < 8; ++lane) dead[count][lane] = detail::kSlotOfHaddLane[lane] >= count ? -1 : 0;
    return dead;
}();

// c - p for slots 0-3 and 4-7 (x, y pairs as stored), the centre broadcast straight from the
// Circle, and each face's separation dot(n, c - p): each slot's x term plus its y term (VHADDPS
// adds y + x, the same sum), in VHADDPS's lane order.
struct CircleLanes {
    __m256 cc, o0, o1, side;  // cc: the centre's x, y in every pair of lanes
};
[[gnu::target("avx2"), gnu::always_inline]] inline CircleLanes circle_lanes(const Polygon& a, const Circle& b) {
    const __m256 cc = _mm256_castpd_ps(_mm256_broadcast_sd(reinterpret_cast<const double*>(&b.center)));
    const float* points = &a.points().data()->x;  // 8 slots read: a Polygon has 16
    const float* normals = &a.normals().data()->x;
    CircleLanes l;
    l.cc = cc;
    l.o0 = _mm256_sub_ps(cc, _mm256_loadu_ps(points));
    l.o1 = _mm256_sub_ps(cc, _mm256_loadu_ps(points + 8));
    l.side = _mm256_hadd_ps(_mm256_mul_ps(_mm256_loadu_ps(normals), l.o0),
                            _mm256_mul_ps(_mm256_loadu_ps(normals + 8), l.o1));
    return l;
}

// Past the early out, inlined (GCC still gives the early out's miss a short return of its own).
// Not a separate function taking the lanes: GCC gives a function with 256-bit arguments no
// VZEROUPPER, and the SSE code after it then waits on the upper halves (the world step's sincosf
// ran 60% slower).
[[gnu::target("avx2"), gnu::always_inline]] inline Manifold polygon_circle8_near(const Polygon& a, const Circle& b,
                                                                              const CircleLanes& l) {
    const __m256 dead = _mm256_loadu_ps(reinterpret_cast<const float*>(kDeadHaddLanes[a.count()].data()));
    const __m256 side = _mm256_or_ps(l.side, dead);
    const __m256 minus_inf = _mm256_set1_ps(-INFINITY);
    const __m256 top = detail::max8(_mm256_max_ps(side, minus_inf));  // VMAXPS gives -inf for NaN
    const float max_sep = _mm256_cvtss_f32(top);
    const int max_edge = detail::kFirstHaddSlot<0>[_mm256_movemask_ps(_mm256_cmp_ps(side, top, _CMP_EQ_OQ))];
    const Float4 c4 = reinterpret_cast<Float4>(_mm256_castps256_ps128(l.cc));
    return polygon_circle_answer(a, b, c4, max_sep, max_edge, [&]() __attribute__((target("avx2"))) {
        const __m256 d2 =
            _mm256_or_ps(_mm256_hadd_ps(_mm256_mul_ps(l.o0, l.o0), _mm256_mul_ps(l.o1, l.o1)), dead);
        const __m256 least = detail::min8(_mm256_min_ps(d2, _mm256_set1_ps(INFINITY)));  // VMINPS: +inf for NaN
        // The first vertex at the least distance (when it is +inf, any: that is a miss).
        return NearestVertex{_mm256_cvtss_f32(least),
                             detail::kFirstHaddSlot<0>[_mm256_movemask_ps(_mm256_cmp_ps(d2, least, _CMP_EQ_OQ))]};
    });
}

// collide(Polygon, Circle) (09-90) for 3 to 8 vertices with AVX2 (chosen at run time): every face's
// separation in one register instead of two, and, past the early out, the largest separation
// and the nearest vertex by folds over the lanes. The lanes do the SSE path's arithmetic, NaN
// past the last vertex; the folds see NaN as -inf (faces) or +inf (vertices), as the SSE
// path's comparisons skip it, and take the first lane equal to the result, in slot order: the
// same bits.
[[gnu::target("avx2")]] Manifold polygon_circle8(const Polygon& a, const Circle& b) {
    const CircleLanes l = circle_lanes(a, b);
    const __m256 side = l.side;
    // An edge normal separates: early out. The lanes past the last face need no mask here: their
    // normals are zero (a Polygon keeps its unused slots zero), so they hold +-0 or NaN, beyond no
    // valid radius (and a negative radius is a miss anyway).
    if (_mm256_movemask_ps(_mm256_cmp_ps(side, _mm256_broadcast_ss(&b.radius), _CMP_GT_OQ)) != 0) return {};
    return polygon_circle8_near(a, b, l);
}
#endif
}  // namespace

Manifold collide(const Polygon& a, const Circle& b) {
    // 09-90: the closest point p of the polygon's boundary to the centre c; the MTD has
    // direction p - c and length r - |p - c|. The slide assumes c is outside; when it is
    // inside, the shortest way out is through the nearest edge, by r plus c's depth.
    // p is found by features, not by the slide's loop over every edge: the face of largest
    // separation when c projects inside it, else the nearest vertex. That is the same point
    // (the slide's loop, literally, is detail::offset_from_boundary, which closest_point uses).
    // The circle is checked only for an answer that would be a hit (an invalid circle is a
    // miss, and the arithmetic on any input is defined); the empty polygon has no faces.
#ifdef JOSTLE_AVX2_PATHS
    if (static_cast<unsigned>(a.count() - 3) <= 5u && detail::has_avx2()) return polygon_circle8(a, b);
#endif
    return polygon_circle(a, b);
}

Manifold collide_sat(const Polygon& a, const Circle& b) {
    // 09-91 to 09-96: SAT, where a circle projects to its centre's projection +- r, and the
    // edge normals alone are not enough. The slide adds the axis from the centre to the
    // closest point on the polygon; the nearest vertex gives the same answer (in a vertex's
    // region the closest point is that vertex, elsewhere an edge normal already wins) and
    // needs no closest-point search.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 c = b.center;
    int nearest = 0;
    float nearest_d2 = INFINITY;
    for (int i = 0; i < a.count(); ++i) {
        const float d2 = length_squared(a.points()[i] - c);
        if (d2 < nearest_d2) { nearest_d2 = d2; nearest = i; }
    }
    float best = INFINITY;
    Vec2 best_normal{1.0f, 0.0f};
    auto test_axis = [&](Vec2 u) {
        // Relative to the centre, for precision far from the origin.
        float lo = dot(a.points()[0] - c, u), hi = lo;
        for (int i = 1; i < a.count(); ++i) {
            const float d = dot(a.points()[i] - c, u);
            lo = d < lo ? d : lo;
            hi = d > hi ? d : hi;
        }
        return detail::consider_axis(u, hi + b.radius, b.radius - lo, best, best_normal);
    };
    for (int i = 0; i < a.count(); ++i)
        if (!test_axis(a.normals()[i])) return {};
    const Vec2 to_vertex = a.points()[nearest] - c;
    if (to_vertex != Vec2{} && !test_axis(normalize_or(to_vertex, Vec2{1.0f, 0.0f}))) return {};
    return hit_with(best, best_normal);
}

namespace {
// The circle-vs-box test in the box's own frame, box [lo, hi] (09-102 "push in"), x and y
// side by side in lanes 0 and 1 (each lane the scalar arithmetic): false for a miss, else the
// depth and normal that hit_with makes the answer (not yet checked to be finite). Here, not
// behind a call, so that the box and circle pairs compile into one function each.
inline bool box_circle_reach(Float4 lo, Float4 hi, Float4 c, float r, float& depth, Vec2& normal) {
    // 09-102: "push in" the centre to find the closest point q of the box. A centre outside
    // leaves along c - q; a centre inside (or on the boundary, where c - q is zero or too
    // small to have a direction) is pushed out through the nearest face.
    // The clamp as a min then a max (MINPS/MAXPS, no branch on where the centre lies). With
    // lo <= hi it gives detail::clamp's value bit for bit, also for -0 and NaN.
    const Float4 t = hi < c ? hi : c;
    const Float4 d = c - (lo > t ? lo : t);
    const Float4 d2 = d * d;
    const float dist2 = d2[0] + d2[1];
    // The miss first, the common answer's one branch; whether the centre is inside is then
    // asked only of a hit. A NaN dist2 goes on to the inside test, as it always has; so does a
    // NaN r * r, whose NaN depth hit_with turns into the miss that `!(dist2 <= r * r)` gave.
    if (dist2 > r * r) return false;
    if (dist2 > 0.0f) {
        // One square root, one DIVPS for both components (each lane the scalar quotient).
        const Float4 dist = detail::sqrt_nonneg(Float4{dist2, dist2, dist2, dist2});
        const Float4 n = d / dist;
        depth = r - dist[0];
        normal = {n[0], n[1]};
        // A denormal dist2 lost bits (its root is off by up to a few percent): the direction
        // rescaled (fuzz: a normal 1.05 long).
        if (dist2 < 0x1p-126f) [[unlikely]] normal = detail::normalize_rescaled(Vec2{d[0], d[1]}, normal);
        return true;
    }
    // Inside: out through the nearest face, the first of least depth in the order -x, +x, -y,
    // +y (a NaN never wins; a NaN first depth stays): the depths side by side, their least by
    // a chain of selects (MINSS), the face as the first lane equal to it (a lane mask): which
    // face is data, too random for a branch.
    static constexpr Vec2 kFaceNormals[4] = {{-1.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, -1.0f}, {0.0f, 1.0f}};
    const Float4 face_depth =
        __builtin_shufflevector(c, hi, 0, 4, 1, 5) - __builtin_shufflevector(lo, c, 0, 4, 1, 5);
    depth = face_depth[0];
    for (int i = 1; i < 4; ++i) depth = face_depth[i] < depth ? face_depth[i] : depth;
    const unsigned at = detail::lane_bits(face_depth == Float4{depth, depth, depth, depth});
    const int face = at == 0 ? 0 : std::countr_zero(at);  // none: the first depth is NaN
    depth += r;
    normal = kFaceNormals[face];
    return true;
}
}  // namespace

Manifold collide(const Aabb& a, const Circle& b) {
    if (!valid(a) || !valid(b)) return {};
    float depth;
    Vec2 normal;
    if (!box_circle_reach(lanes_xy(a.min), lanes_xy(a.max), lanes_xy(b.center), b.radius, depth, normal))
        return {};
    return hit_with(depth, normal);
}

Manifold collide(const Obb& a, const Circle& b) {
    // The clamp in the box's own frame, then the normal turned back. The shapes are checked
    // only when the answer would be a hit: an invalid shape is a miss, so a miss needs no
    // check (the arithmetic on any input is defined, only the answer would be wrong).
    const Rot q = a.rotation();
    // inv_rotate(q, v) = {c vx + s vy, -s vx + c vy}, v = the centre from the box's: the two
    // coordinates side by side.
    const Float4 centre = lanes_xy(a.center), bc = lanes_xy(b.center);
    const Float4 v = bc - centre;
    const Float4 rot = lanes_xy(q);
    const Float4 local =
        detail::bit_xor(rot, Float4{0.0f, -0.0f, 0.0f, -0.0f}) * __builtin_shufflevector(v, v, 0, 0, 0, 0) +
        __builtin_shufflevector(rot, rot, 1, 0, 1, 0) * __builtin_shufflevector(v, v, 1, 1, 1, 1);
    const Float4 hi = lanes_xy(a.half);
    float depth;
    Vec2 normal;
    if (!box_circle_reach(detail::bit_xor(hi, Float4{-0.0f, -0.0f, 0.0f, 0.0f}), hi, local, b.radius, depth,
                          normal))
        return {};
    // hit_with's test (a finite depth and normal) and valid(a) && valid(b) in one: x - x is 0
    // exactly for a finite x (see detail::all_finite), lane by lane, and the half extents and
    // radius >= 0. A miss all the same, whichever fails. (The box's lanes are valid(Obb)'s:
    // its centre plus and minus twice the halves' sum, so that a size beyond float is a miss.)
    const float reach = 2.0f * (hi[0] + hi[1]);
    const Float4 box = __builtin_shufflevector(centre, centre, 0, 1, 0, 1) + Float4{reach, reach, -reach, -reach};
    const Float4 rest = {a.angle(), bc[0], bc[1], b.radius * b.radius};
    const Float4 answer = {depth, normal.x, normal.y, 0.0f};
    const Float4 zero = {0.0f, 0.0f, 0.0f, 0.0f};
    const detail::Int4 finite = ((box - box) + (rest - rest)) + (answer - answer) == zero;
    const detail::Int4 signs = Float4{hi[0], hi[1], b.radius, 0.0f} >= zero;
    if (detail::lane_bits(finite & signs) != 0xfu) return {};
    const Vec2 n = detail::plain_zeros(rotate(q, detail::plain_zeros(normal)));
    return Manifold{true, depth > 0.0f ? depth : 0.0f, n};
}

Manifold collide(const Segment& a, const Circle& b) {
    // 09-87/88: the closest point p on the segment to c; hit when |p - c| <= r; the MTD has
    // direction p - c and length r - |p - c|. A centre on the segment leaves by its normal.
    if (!valid(a) || !valid(b)) return {};
    const Vec2 d = detail::offset_from_segment(a.a, a.b, b.center);  // c - p
    const float dist2 = dot(d, d);
    if (!(dist2 <= b.radius * b.radius)) return {};
    const Vec2 e = a.b - a.a;
    const Vec2 side = a.a == a.b ? Vec2{1.0f, 0.0f} : normalize_or(Vec2{e.y, -e.x}, Vec2{1.0f, 0.0f});
    // Beside the segment (the closest point inside it), its normal on the centre's side and the
    // distance along it are exact where normalising c - p would round.
    if (dot(b.center - a.a, e) > 0.0f && dot(b.center - a.b, e) < 0.0f) {  // from each end, for precision
        const float along = dot(side, b.center - a.a);
        return hit_with(b.radius - std::fabs(along), along < 0.0f ? -side : side);
    }
    return hit_with(b.radius - std::sqrt(dist2), normalize_or(d, side));
}

}  // namespace jostle
