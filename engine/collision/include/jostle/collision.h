// jostle/collision.h: the collision module, the reference implementation of the
// 2D-intersection lecture (../shared/lecture-2d-intersection.txt, slides 09-0 to 09-130).
// Pure functions over plain shapes; depends on jostle/core and the standard library only.
//
// ===================================== MANUAL =====================================
//
// COORDINATES
//   Pixels, y pointing down (as in images). Angles in radians, positive from +x toward +y
//   (clockwise on screen). Floats throughout (as in Box2D); no query allocates or depends on
//   anything but its arguments (and the tests-only switches in detail::, which give the same
//   answers), so results are reproducible (only building a Mask allocates).
//
// SHAPES (all closed: a shape contains its boundary)
//   Aabb        {min, max}                   axis-aligned box, min <= max on both axes
//   Obb         Obb{center, half, angle}     oriented box; corners() gives its 4 corners; the
//                                            angle's cos/sin are computed once, when it is set
//   Polygon     make_polygon(points)         convex, 3..16 vertices, either winding accepted;
//                                            stored with cross(e[i], e[i+1]) > 0 and outward
//                                            unit normals; non-convex, collinear, repeated or
//                                            non-finite input is rejected with a message. Its
//                                            fields are private, so a Polygon is valid (or
//                                            empty) by construction
//   Circle      {center, radius}             radius >= 0 (0 is a point)
//   Segment     {a, b}                       a == b is a point
//   PlacedMask  {mask, x, y}                 a pixel Mask whose top-left pixel is at integer
//                                            world pixel (x, y); pixel (i, j) is the square
//                                            [x+i, x+i+1] x [y+j, y+j+1]
//   Shape       std::variant of the above, for the generic entry points.
//
// RESULTS, one convention for every pair (A is the first argument, B the second)
//   Manifold.hit     the closed shapes intersect; touching is a hit with depth 0
//   Manifold.normal  unit vector from A toward B (the direction to push B out of A)
//   Manifold.depth   >= 0; mtd() = -depth * normal is the shortest translation of A that
//                    separates the two (the lecture's circle MTD, 09-72, pushes circle 1
//                    away from circle 2: the same thing)
//   A miss is hit = false, depth = 0, normal = {0, 0}.
//   CastHit   {hit, t, point, normal}: a segment from->to first touches the shape at
//             from + t*(to-from), t in [0, 1]; normal is the shape's outward surface normal
//             there. A segment that starts inside (or on) the shape reports t = 0 and
//             point = from; if it starts strictly inside, normal = {0, 0} (for a mask: if it
//             starts on any set pixel).
//   SweepHit  {hit, t, point, normal}: a circle moving by va and a shape moving by vb over one
//             frame first touch at time t in [0, 1]; point is the contact point at that time,
//             normal points from A (the circle) toward B. A contact counts only while A
//             moves into B: dot((va - vb) / |va - vb|, normal) > 1e-5. So shapes already
//             touching or overlapping at t = 0 report t = 0 only when A moves into B; moving
//             off B, sliding along it or a path that only grazes it is no hit (the lecture's
//             moving-away early out, 09-114): a ball left touching a wall by the MTD push can
//             leave it, and a ball resting on a mask rolls over its pixel seams (one sunk
//             into it does not: see LIMITS). A start in overlap is judged along collide()'s
//             MTD normal: a circle deep inside moving along its MTD
//             face is no hit (the narrowphase resolves overlaps), and at an exact tie of faces
//             the shape's own face order decides (a box and the same box as a Polygon list
//             their faces differently).
//
// PAIR TABLE: how collide(A, B) is computed (the reverse order swaps and flips the normal;
// for two shapes of the same kind whose pushes tie, the first tied axis of A wins, so the
// reverse order may name the other tied axis)
//              Aabb         Obb         Polygon     Circle          Segment     Mask
//   Aabb       per-axis     SAT box     SAT         clamp 09-102    SAT         mask
//   Obb                     SAT box     SAT         local clamp     SAT         mask
//   Polygon                             SAT         closest 09-90   SAT         mask
//   Circle                                          09-71/72        closest     mask
//   Segment                                                         SAT         mask
//   Mask                                                                        mask
//   per-axis  09-23 separation test, MTD along the axis that needs the smaller push (09-34)
//   SAT box   09-58: the 2 + 2 edge normals of the boxes, projected radii, one gap test
//             over the four axes (in place of 09-50's early exit)
//   SAT       09-62: every edge normal of both shapes (two segments also try each one's
//             direction, since they have no area; a polygon or box against a segment needs
//             only its own faces and the segment's two sides), early exit on the first
//             separating axis, MTD along the axis of least push (09-60). For two polygons
//             each edge normal is tested on its outward side only: those are the faces of
//             the Minkowski difference, where the least push always lies
//   clamp     09-102: closest point in the box by "push in"; a centre inside the box is
//             pushed out through the nearest face
//   closest   09-87/09-90: closest point on the boundary to the circle's centre (found by
//             features: the face of largest separation, else the nearest vertex); a centre
//             inside the polygon is pushed out through the nearest edge.
//             collide_sat(Polygon, Circle) is the lecture's second method (09-96): SAT with
//             the extra axis from the centre to the nearest vertex; it gives the same result.
//   mask      pixels are decided on the mask's integer grid: a pixel meets a solid shape
//             (Aabb, Obb, Polygon, Circle) when the pixel's centre lies in the closed shape,
//             meets a Segment when the segment touches the pixel's closed square, and meets
//             another mask's pixel at the same world pixel. hit = some set pixel meets B;
//             the MTD is the shortest integer translation of the mask that leaves no set
//             pixel meeting B (ties broken toward pushing A away from B's centre). Mask pairs
//             have no "touching" case: a hit always has depth >= 1. "B's centre" for the tie
//             rule: a mask's pixel rectangle's centre, a box's or circle's centre, a
//             polygon's vertex mean, a segment's midpoint.
//
// MASKS
//   Mask::from_rows(rows)                  rows: std::string_views, '#' set, '.' clear (no
//                                          rows: a 0 x 0 mask); nullopt and *error when bad
//   Mask::from_alpha(rgba, w, h, t)        set where alpha > t
//   Queries (mask.cpp): overlaps, first_overlap (the first shared world pixel in reading
//   order: smallest y, then smallest x), count_overlap, collide (integer MTD), the same
//   against an Aabb, and reference::* (the lecture's brute-force loop, 09-3, corrected).
//   The bit-packed path keeps 64 pixels in a word and compares a word per AND; it gives the
//   same answers as the reference loop. count_overlap uses the CPU's POPCNT instruction when
//   it has one (checked at run time), with the same results either way.
//
// TOLERANCES
//   Touching is decided on the computed values with no epsilon: shapes that touch exactly
//   in float arithmetic (integer coordinates with axis-aligned edges) report hit with depth 0;
//   shapes that touch only up to rounding may report a tiny depth or a miss. Integer
//   coordinates alone are not enough: SAT's unit axes are rounded for any edge that is not
//   axis-aligned, so a segment touching another at an integer point may be a miss for
//   collide() and a hit for intersect() or cast(), which decide on cross products. A point
//   with integer coordinates on a segment with integer ends (lengths within 2^12) is on it
//   for closest_point, intersect() with a point segment, cast() of zero length and the
//   circle queries with radius 0: a zero cross product puts it on the line. Degenerate input
//   (zero length, zero radius, coincident centres, parallel edges) has a defined result:
//   coincident circle centres use normal {1, 0}. Any NaN or infinite coordinate in a shape
//   makes it hit nothing (a miss, all zeros), never undefined behaviour; closest_point then
//   answers point {0, 0} at distance +infinity (the closest points that answer a bare Vec2,
//   on a line, a segment, a circle or a polygon's boundary: {0, 0}, on edge -1), and so it
//   does for a NaN or infinite query point. So does a malformed shape (Aabb min > max,
//   negative half extents or radius, a radius whose square overflows (above about 1.8e19),
//   a box or segment whose size overflows (an Obb: whose centre plus or minus twice its
//   half extents' sum does), the empty Polygon),
//   and a cast or motion whose end or squared length (or a sweep whose contact point)
//   overflows to infinity.
//
// LIMITS
//   Polygon: 3..16 vertices (kMaxPolygonVertices). Mask: up to 4096 x 4096 pixels
//   (kMaxMaskSide). Coordinates: keep |x|, |y| <= 1e5 px (kMaxCoordinate; the game's level
//   files are held to it); floats then resolve 1/128 px, and
//   depths and normals agree with a double-precision computation to about 1e-4 of the
//   shapes' size. Beyond that, results stay defined but lose precision. So they do for a
//   shape smaller than about 1e-4 of the other's size or of their distance: to float it is a
//   point up to rounding, and the normal may be a neighbouring feature's. Near a polygon's
//   corner of interior angle theta, a cast or sweep is placed to within the coordinates'
//   rounding / sin theta: at a sliver's tip of 1e-5 rad, with coordinates near 30, about a
//   pixel (make_polygon rejects only turns within 1e-6 rad of straight). A sweep's "only
//   grazes" is decided by the contact normal's slant to the motion, which comes from F, the
//   path's distance from a circle's centre or a corner, taken from exact products
//   (F = cross(v, offset) / |v|): a path that grazes exactly (integer input with |v|^2 below
//   2^24: a circle of radius 1 from (-2, 0) by (6, 8) past one of radius 1 at (5, 6)) has
//   F = R and is a miss; a path within rounding of a graze has G = sqrt(R^2 - F^2) of about
//   sqrt(eps) of the radii and may be a hit at a slant of a few 1e-4. (A ray cast against a
//   circle counts touching: a grazing cast is a hit with t at the touch.) A circle sunk into a
//   mask (by more than rounding) meets the side of the next pixel when it rolls across a seam
//   between pixels: the mask's pixels are swept one by one. A mask's MTD takes
//   time that grows with the push it finds. Against a convex shape a push longer than 16 px
//   starts from the faces' exits and skips the columns that cannot hold it (a 32 px round
//   mask 8,700 px deep in a hexagon: 0.9 ms on a 2020s CPU; 8,000 px deep in a box: 0.01
//   ms). Around a mask at a circle's centre every column out to the push can hold it, and
//   against another mask there is no such shortcut: about 1 ms per 1,000 px (that mask 8,000
//   px deep at a circle's centre: 11 ms; a 20 x 20 one at the centre of a circle of radius
//   1e5 px: 7 ms). Nor against a segment, or a polygon thinner than a pixel, whose pixels are
//   no solid region: there (and between masks) the search jumps along the runs of set pixels
//   in the masks' columns, so a large solid mask crossed by a segment costs about the square
//   of its side (corner to corner: 256 px 7 ms, 1,024 px 0.11 s, 4,096 px 1.8 s, on a 2-core
//   AMD EPYC VM); crossed by a one-pixel line mask, whose runs are one pixel where it enters,
//   still nearly the cube (2.6 ms, 0.1 s, 5 s). The world tests a mask contact again at each
//   position pass.
// ==================================================================================
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "jostle/core/vec2.h"

namespace jostle {

inline constexpr int kMaxPolygonVertices = 16;
inline constexpr int kMaxMaskSide = 4096;
inline constexpr float kMaxCoordinate = 1e5f;

// ---------------------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------------------

struct Aabb {
    Vec2 min;
    Vec2 max;
};

// An oriented box. Its angle is turned into cos/sin once, when it is set (the constructor or
// set_angle), so that no query pays for a sine and a cosine; the angle is private so the two
// can never disagree.
struct Obb {
    Vec2 center;
    Vec2 half;  // half extents along the box's own x and y axes, >= 0

    Obb() = default;
    Obb(Vec2 center_, Vec2 half_, float angle = 0.0f) : center(center_), half(half_) { set_angle(angle); }

    float angle() const { return angle_; }  // radians, +x toward +y
    Rot rotation() const { return rotation_; }  // Rot::from_angle(angle())
    void set_angle(float radians) {
        angle_ = radians;
        rotation_ = Rot::from_angle(radians);
    }

private:
    float angle_ = 0.0f;
    Rot rotation_;
};

struct Circle {
    Vec2 center;
    float radius = 0.0f;
};

struct Segment {
    Vec2 a;
    Vec2 b;
};

namespace detail {
struct PolygonAccess;  // the collision module's own builders (box polygons, swept rectangles)
}

// A convex polygon. Only make_polygon (which validates) and the module's own conversions
// (to_polygon, moved, transformed) make one, so a Polygon is always well formed: 3..16
// finite vertices with cross(e[i], e[i+1]) > 0 (clockwise on screen, y down; after a move
// or turn, up to each vertex's float rounding: see moved) and normals()[i] the outward unit
// normal of edge points()[i] -> points()[i + 1]; or empty (count() == 0, the default), which
// hits nothing. Queries therefore never re-validate it.
class Polygon {
public:
    Polygon() = default;  // empty

    int count() const { return count_; }
    std::span<const Vec2> points() const { return {points_.data(), static_cast<std::size_t>(count_)}; }
    std::span<const Vec2> normals() const { return {normals_.data(), static_cast<std::size_t>(count_)}; }

    // The polygon translated by d, or rotated by xf.q then translated by xf.p (a rigid motion
    // keeps convexity, winding and unit normals, up to rounding: each vertex is rounded to
    // float, so far from the origin a turn smaller than that rounding can come out flat or
    // reversed; the pixel-mask queries decide a pixel by the edges' half-planes, whatever the
    // vertices). A result with a non-finite coordinate is the empty polygon, and so is a turn
    // by a Rot that is not a rotation (c^2 + s^2 further than 1e-4 from 1: Rot is a plain
    // pair, and scaling by it would leave normals that are not unit, or none at all).
    Polygon moved(Vec2 d) const;
    // out = moved(d), writing only the vertices in use when out already has this count
    // (every Polygon keeps its unused slots zero, so the result is the same object).
    void moved_into(Vec2 d, Polygon& out) const;
    Polygon transformed(const Transform& xf) const;
    // Rotated by q about the origin: rotated(xf.q).moved(xf.p) is transformed(xf), bit for
    // bit (the world turns a collider once per angle and moves it for each placement).
    Polygon rotated(Rot q) const;
    // out = rotated(q), writing only the vertices in use when out already has this count.
    void rotated_into(Rot q, Polygon& out) const;

private:
    friend std::optional<Polygon> make_polygon(std::span<const Vec2> points, std::string* error);
    friend struct detail::PolygonAccess;
    int count_ = 0;
    // The slots past count_ are always zero: the AVX2 paths read 8 slots for up to 8 vertices
    // and count on zero normals there (every way of making a Polygon keeps them so; tested).
    std::array<Vec2, kMaxPolygonVertices> points_{};
    std::array<Vec2, kMaxPolygonVertices> normals_{};
};

// A 1-bit pixel mask, bit-packed: row y holds words_per_row() 64-bit words, pixel x in bit
// (x % 64) of word (x / 64). Bits past the width are always clear.
class Mask {
public:
    Mask() = default;
    // All pixels clear. 0 <= width, height <= kMaxMaskSide (asserted).
    Mask(int width, int height);

    // '#' set, '.' clear; every row the same length. On bad input returns nullopt and, if
    // error is given, a message naming the row and column ("row 2, column 5: expected '#'
    // or '.', got 'x'").
    static std::optional<Mask> from_rows(std::span<const std::string_view> rows, std::string* error = nullptr);
    // Set where alpha > threshold. rgba is width*height straight RGBA bytes, row-major,
    // top row first.
    static Mask from_alpha(const std::uint8_t* rgba, int width, int height, std::uint8_t threshold);

    int width() const { return width_; }
    int height() const { return height_; }
    int words_per_row() const { return words_per_row_; }
    bool get(int x, int y) const;        // false outside the mask
    void set(int x, int y, bool value);  // asserts inside the mask
    const std::uint64_t* row(int y) const { return bits_.data() + static_cast<std::size_t>(y) * words_per_row_; }
    int count() const;                   // set pixels
    std::vector<std::string> to_rows() const;

private:
    int width_ = 0;
    int height_ = 0;
    int words_per_row_ = 0;
    std::vector<std::uint64_t> bits_;
};

// A mask placed in the world: its pixel (0, 0) covers world pixel (x, y). The mask is
// borrowed and must outlive the PlacedMask.
struct PlacedMask {
    const Mask* mask = nullptr;
    int x = 0;
    int y = 0;
};

using Shape = std::variant<Aabb, Obb, Polygon, Circle, Segment, PlacedMask>;

enum class ShapeKind { aabb, obb, polygon, circle, segment, mask };
ShapeKind kind_of(const Shape& s);
const char* name_of(ShapeKind k);  // "aabb", "obb", ...

// Validates and builds a convex polygon (3..16 finite vertices, either winding, no repeated
// or collinear vertices). On failure returns nullopt and, if error is given, says why.
std::optional<Polygon> make_polygon(std::span<const Vec2> points, std::string* error = nullptr);

// ---------------------------------------------------------------------------------------
// Results
// ---------------------------------------------------------------------------------------

struct Manifold {
    bool hit = false;
    float depth = 0.0f;  // >= 0
    Vec2 normal;         // unit, from A toward B; {0, 0} on a miss
    Vec2 mtd() const { return {0.0f - depth * normal.x, 0.0f - depth * normal.y}; }  // moves A out of B (never -0)
};

struct CastHit {
    bool hit = false;
    float t = 0.0f;  // fraction of from->to, in [0, 1]
    Vec2 point;      // from + t * (to - from)
    Vec2 normal;     // the shape's outward unit normal at point; {0,0} when starting inside
};

struct SweepHit {
    bool hit = false;
    float t = 0.0f;  // time of first contact, in [0, 1]
    Vec2 point;      // contact point at time t
    Vec2 normal;     // unit, from A (the moving circle) toward B at time t
};

// Where two overlapping polygons touch (for stacking, torque and debug drawing): the MTD
// and up to 2 contact points, made by clipping the incident edge (the face of the other
// shape most opposed to the MTD's face) to the MTD's face, as Box2D and most engines do.
// Each point lies on the incident shape's boundary, depths[k] (in [0, manifold.depth]) below
// the reference face. A miss has count 0; a hit has 1 or 2 points (2 when edges lie flat on
// each other).
struct ContactSet {
    Manifold manifold;
    int count = 0;
    std::array<Vec2, 2> points{};
    std::array<float, 2> depths{};
};

struct ClosestPoint {
    Vec2 point;             // the point of the closed shape nearest to the query
    float distance = 0.0f;  // 0 when the query point is inside
};

// ---------------------------------------------------------------------------------------
// AABB (aabb.cpp), slides 09-6 to 09-34
// ---------------------------------------------------------------------------------------

Aabb translate(const Aabb& box, Vec2 offset);  // 09-10
std::array<Vec2, 4> corners(const Aabb& box);  // min, (max.x,min.y), max, (min.x,max.y)
// 09-13: the AABB of the box's 4 corners after rotating them by `angle` about `pivot`.
Aabb rotated_bounds(const Aabb& box, float angle, Vec2 pivot);
// 09-17: the tight AABB of a rotated shape: rotate every model point, take min and max.
Aabb rotated_bounds(std::span<const Vec2> model_points, float angle, Vec2 pivot);
bool overlaps(const Aabb& a, const Aabb& b);                   // 09-23, touching counts
std::optional<Aabb> intersection(const Aabb& a, const Aabb& b);  // 09-28
Manifold collide(const Aabb& a, const Aabb& b);                 // 09-34

// Bounds of every shape (a mask's bounds are its whole rectangle of pixels).
Aabb bounds(const Obb& box);
Aabb bounds(const Polygon& poly);
Aabb bounds(const Circle& c);
Aabb bounds(const Segment& s);
Aabb bounds(const PlacedMask& m);
Aabb bounds(const Shape& s);

// ---------------------------------------------------------------------------------------
// OBB and convex polygons: separating axis theorem (sat.cpp), slides 09-35 to 09-69
// ---------------------------------------------------------------------------------------

std::array<Vec2, 4> corners(const Obb& box);  // in polygon order (positive cross)
Polygon to_polygon(const Obb& box);
Polygon to_polygon(const Aabb& box);

Manifold collide(const Obb& a, const Obb& b);
Manifold collide(const Aabb& a, const Obb& b);
Manifold collide(const Aabb& a, const Polygon& b);
Manifold collide(const Obb& a, const Polygon& b);
Manifold collide(const Polygon& a, const Polygon& b);
Manifold collide(const Aabb& a, const Segment& b);
Manifold collide(const Obb& a, const Segment& b);
// The MTD (the same as collide) with the contact points; see ContactSet.
ContactSet contacts(const Obb& a, const Obb& b);
ContactSet contacts(const Polygon& a, const Polygon& b);
Manifold collide(const Polygon& a, const Segment& b);
Manifold collide(const Segment& a, const Segment& b);

// ---------------------------------------------------------------------------------------
// Circles (circle.cpp), slides 09-70 to 09-72 and 09-86 to 09-102
// ---------------------------------------------------------------------------------------

Manifold collide(const Circle& a, const Circle& b);   // squared distances, 09-71
Manifold collide(const Polygon& a, const Circle& b);  // closest point on the boundary, 09-90
Manifold collide_sat(const Polygon& a, const Circle& b);  // SAT + centre-to-nearest-vertex axis, 09-96
Manifold collide(const Aabb& a, const Circle& b);     // clamp "push in", 09-102
Manifold collide(const Obb& a, const Circle& b);      // clamp in the box's frame
Manifold collide(const Segment& a, const Circle& b);  // 09-87/88

// ---------------------------------------------------------------------------------------
// Lines and closest points (lines.cpp), slides 09-73 to 09-102
// ---------------------------------------------------------------------------------------

// The line A x + B y = C through two points (09-77): A = y2 - y1, B = x1 - x2, C = A x1 + B y1.
struct Line {
    float a = 0.0f;
    float b = 0.0f;
    float c = 0.0f;
};
Line line_through(Vec2 p1, Vec2 p2);

enum class LineRelation { point, parallel, coincident };
struct LineIntersection {
    LineRelation kind = LineRelation::parallel;
    Vec2 point;  // the crossing point when kind == point; {0, 0} otherwise
};
// 09-75: x = (C2 B1 - B2 C1) / det, y = (C1 A2 - A1 C2) / det, det = A2 B1 - B2 A1;
// det == 0 means parallel, or coincident when the lines are the same, decided exactly for
// the given coefficients (the products are taken in double, where they are exact), however
// small or nearly parallel. Lines that cross beyond float's range (a rounding away from
// parallel) are reported as parallel. A line through two equal points is degenerate: it is
// "parallel" to everything.
LineIntersection intersect(const Line& l1, const Line& l2);

struct SegmentIntersection {
    bool hit = false;
    Vec2 point;  // a shared point: the crossing, or for collinear overlapping segments the
                 // shared point nearest to s1.a
};
// 09-78: the lines' crossing, then a range check on both segments (closed: endpoints count),
// on the crossing's parameters from cross products taken in double (no underflow makes a
// short segment a point).
SegmentIntersection intersect(const Segment& s1, const Segment& s2);

Vec2 closest_point(const Line& line, Vec2 p);       // 09-83: foot of the perpendicular
Vec2 closest_point(const Segment& seg, Vec2 p);     // 09-85
Vec2 closest_point_on(const Circle& c, Vec2 q);     // 09-98: the point on the circle nearest q
ClosestPoint closest_point(const Aabb& box, Vec2 q);   // 09-102: "push in"
ClosestPoint closest_point(const Obb& box, Vec2 q);
ClosestPoint closest_point(const Polygon& poly, Vec2 q);
ClosestPoint closest_point(const Circle& c, Vec2 q);   // in the closed disc
ClosestPoint closest_point(const PlacedMask& m, Vec2 q);  // nearest point of a set pixel's square
ClosestPoint closest_point(const Shape& s, Vec2 q);
// The point of the polygon's boundary nearest q, and the edge it lies on (-1 when there is
// none: the empty Polygon or a non-finite q, whose point is {0, 0}).
Vec2 closest_point_on_boundary(const Polygon& poly, Vec2 q, int* edge = nullptr);
bool contains(const Polygon& poly, Vec2 q);  // closed

// ---------------------------------------------------------------------------------------
// Casts: bullets as segments from last to next position (cast.cpp), slide 09-103
// ---------------------------------------------------------------------------------------

CastHit cast(Vec2 from, Vec2 to, const Circle& c);
CastHit cast(Vec2 from, Vec2 to, const Aabb& box);
CastHit cast(Vec2 from, Vec2 to, const Obb& box);
CastHit cast(Vec2 from, Vec2 to, const Polygon& poly);
CastHit cast(Vec2 from, Vec2 to, const Segment& seg);
CastHit cast(Vec2 from, Vec2 to, const PlacedMask& m);  // pixels as closed squares
CastHit cast(Vec2 from, Vec2 to, const Shape& s);

// ---------------------------------------------------------------------------------------
// Dynamic circles (sweep.cpp), slides 09-103 to 09-130
// ---------------------------------------------------------------------------------------

// Method #2 (09-111 to 09-122): a circle moving by v against a static circle, by the D/F/G
// closed form: moving-away early out, closest approach F, then first contact at D - G. The
// slide counts F = R (a graze) as a hit; here it is none, as for every sweep.
SweepHit sweep(const Circle& moving, Vec2 v, const Circle& fixed);
// Two moving circles: the same, with the relative velocity v1 - v2 (09-126/127).
SweepHit sweep(const Circle& a, Vec2 va, const Circle& b, Vec2 vb);

// Method #1 (09-106 to 09-110): the circle swept over a frame is a capsule: a rectangle
// and the circles at both ends. The rectangle's corners are c +- d and c + v +- d with
// d = [-v_y, v_x] r / |v| (the slide writes [-v_x, v_y], which is not perpendicular to v).
struct SweptCapsule {
    Circle start;
    Circle end;
    std::array<Vec2, 4> rectangle;  // c + d, c + v + d, c + v - d, c - d; all equal c when v = 0
};
SweptCapsule swept_capsule(const Circle& c, Vec2 v);
// Does the circle touch `fixed` anywhere along its path? (overlap test, no time; a path
// that only grazes, F = R, counts here, as it does for casts: only sweep() leaves it out)
bool swept_overlaps(const Circle& moving, Vec2 v, const Circle& fixed);

// A moving circle against a static box, polygon or segment: the earliest of the centre
// coming within r of a face (inside the face's window) or of a vertex, bounded by the centre
// itself entering the shape, so no fast ball passes through a thin wall, whatever its radius.
SweepHit sweep(const Circle& moving, Vec2 v, const Aabb& box);
SweepHit sweep(const Circle& moving, Vec2 v, const Obb& box);
SweepHit sweep(const Circle& moving, Vec2 v, const Polygon& poly);
SweepHit sweep(const Circle& moving, Vec2 v, const Segment& seg);
SweepHit sweep(const Circle& moving, Vec2 v, const PlacedMask& m);  // pixels as closed squares
// Generic: circle a moving by va, shape b moving by vb (solved with relative motion).
SweepHit sweep(const Circle& a, Vec2 va, const Shape& b, Vec2 vb);

// ---------------------------------------------------------------------------------------
// Pixel masks (mask.cpp), slides 09-0 to 09-5 and 09-30
// ---------------------------------------------------------------------------------------

struct Pixel {
    int x = 0;
    int y = 0;
    friend constexpr bool operator==(Pixel, Pixel) = default;
};

bool overlaps(const PlacedMask& a, const PlacedMask& b);
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b);  // world pixel
int count_overlap(const PlacedMask& a, const PlacedMask& b);
Manifold collide(const PlacedMask& a, const PlacedMask& b);  // integer MTD

// Against the other shapes, by the pixel rule in the pair table.
bool overlaps(const PlacedMask& a, const Aabb& b);
std::optional<Pixel> first_overlap(const PlacedMask& a, const Aabb& b);
int count_overlap(const PlacedMask& a, const Aabb& b);
Manifold collide(const PlacedMask& a, const Aabb& b);
Manifold collide(const PlacedMask& a, const Obb& b);
Manifold collide(const PlacedMask& a, const Polygon& b);
Manifold collide(const PlacedMask& a, const Circle& b);
Manifold collide(const PlacedMask& a, const Segment& b);
int count_overlap(const PlacedMask& a, const Shape& b);
std::optional<Pixel> first_overlap(const PlacedMask& a, const Shape& b);

namespace reference {
// The lecture's brute-force loop (09-3), kept as the reference the fast path is tested
// against, with its two mistakes fixed: pixel x of A lies at x - (x2 - x1) in B (the slide
// writes x + deltax), and the bounds are >= 0 (the slide writes > 0). It iterates over the
// AABB intersection region (09-30) rather than all of A.
bool overlaps(const PlacedMask& a, const PlacedMask& b);
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b);
int count_overlap(const PlacedMask& a, const PlacedMask& b);
// Exhaustive search for the mask MTD: every integer translation up to the bound, shortest
// first, same tie rule. Slow; for tests.
Manifold collide(const PlacedMask& a, const PlacedMask& b);
}  // namespace reference

namespace detail {
// The mask-pair queries run one of these kernels, the best the CPU has (chosen at run time;
// all give the same answers). For tests: run a given one; one the CPU lacks falls back to the
// best it has below it.
enum class MaskKernel { portable, bmi2, avx2, avx512 };
MaskKernel best_mask_kernel();
bool overlaps(const PlacedMask& a, const PlacedMask& b, MaskKernel k);
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k);
int count_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k);
// The polygon MTD takes faces eight at a time with AVX2 when the CPU has it (chosen at run
// time; same answers bit for bit). For tests: switch that path off and on again (on only
// where the CPU has AVX2); returns whether it is now on. Not thread-safe: tests only.
bool use_avx2_paths(bool on);
// The MTD of a mask against a convex shape, when the push is longer than 16 px, starts from
// the faces' own exits and skips runs of columns that cannot hold the answer; against any
// shape it jumps along the moving mask's own columns of set pixels (same answers). For tests
// and benchmarks: switch that off (the plain column scan) and on again. Not thread-safe.
bool use_mask_search_shortcuts(bool on);
}  // namespace detail

// ---------------------------------------------------------------------------------------
// Dispatch (dispatch.cpp): one entry point for any two shapes
// ---------------------------------------------------------------------------------------

Manifold collide(const Shape& a, const Shape& b);
bool overlaps(const Shape& a, const Shape& b);

}  // namespace jostle
