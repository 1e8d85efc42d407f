// Tunnelling: over 100,000 seeded random bullets and fast circles, at up to 20,000 px/s with
// dt = 1/60, fired at walls 1 px thick in every orientation (Obb, polygon quad, Aabb, segment,
// pixel-mask line or staircase): none may end a step on the far side of its wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "jostle/collision.h"
#include "jostle/core/rng.h"
#include "jostle/world.h"
#include "sanitizer_scale.h"

using namespace jostle;

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kMaxSpeed = 20000.0f;  // px/s: 333 px per step
constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxIncidence = 80.0 * kPi / 180.0;  // from the wall normal
// Each world holds kGrid x kGrid cells, one wall and one projectile per cell. Cells are
// kCell apart, so every coordinate stays within |x|, |y| <= 9200 + 1400 px.
constexpr int kGrid = 24;
constexpr double kCell = 800.0;
constexpr double kWallLength = 200.0;
// A projectile starts less than one step's travel from its wall (it reaches the wall in step 1)
// and its speed across the wall is at least r + 2 + half-thickness per step, so without the wall
// its centre would be past the far face by step 3 (see make_shot).
constexpr int kSteps = 3;
// 18 worlds of 576 cells = 10,368 projectiles per (projectile, wall kind) pair, 103,680 over the
// 10 pairs. Release runs that full count (the issue asks for at least 100,000); ASan a tenth.
constexpr int kWorldsPerCase = (18 + kSanitizerDivisor - 1) / kSanitizerDivisor;

// Tolerances.
// Bullets: the hit point must be on the near face within 0.01 px (the figure). Floats
// resolve 1/1024 px at |x| < 16384, so rounding is 10x smaller than that.
constexpr double kFaceTol = 0.01;
// Circles: the centre must stay at least r - 0.05 px from the near face. A sweep stops at first
// contact (distance r, up to float rounding of ~1e-3 px here), and the position phase may leave
// a resting contact up to `slop` (0.01 px) deep; 0.05 px is five times that, and still 1/10 of
// the thinnest circle's radius, so any real pass-through or deep entry is caught.
constexpr double kCircleTol = 0.05;

enum class WallKind { obb, polygon, aabb, segment, mask };
constexpr WallKind kWallKinds[] = {WallKind::obb, WallKind::polygon, WallKind::aabb, WallKind::segment,
                                   WallKind::mask};

const char* wall_name(WallKind k) {
    switch (k) {
        case WallKind::obb:
            return "obb";
        case WallKind::polygon:
            return "polygon";
        case WallKind::aabb:
            return "aabb";
        case WallKind::segment:
            return "segment";
        case WallKind::mask:
            return "mask";
    }
    return "?";
}

const char* response_name(BulletResponse r) {
    switch (r) {
        case BulletResponse::despawn:
            return "despawn";
        case BulletResponse::stop:
            return "stop";
        case BulletResponse::ricochet:
            return "ricochet";
    }
    return "?";
}

// A wall described in double precision, independently of the engine: a centre line through
// (cx, cy) with unit tangent t and unit normal n; the solid is |w| <= half (and |u| <= length/2)
// in the wall frame u = (p - c).t, w = (p - c).n. A mask wall is the set of pixels whose closed
// squares touch its centre line (so the line is covered and the pixels are 4-connected); its
// faces are staircases within |w| <= half = |n.x| + |n.y|.
struct Wall {
    WallKind kind = WallKind::obb;
    double cx = 0.0, cy = 0.0;
    double tx = 1.0, ty = 0.0;
    double nx = 0.0, ny = 1.0;
    double half = 0.5;
    std::shared_ptr<Mask> mask;
    int mask_x = 0, mask_y = 0;               // world pixel of the mask's pixel (0, 0)
    std::vector<std::pair<int, int>> pixels;  // set pixels, in world pixel coordinates

    double u(double x, double y) const { return (x - cx) * tx + (y - cy) * ty; }
    double w(double x, double y) const { return (x - cx) * nx + (y - cy) * ny; }
};

// Distance from p to the closed unit square of world pixel (i, j).
double distance_to_pixel(double px, double py, int i, int j) {
    const double dx = std::max({static_cast<double>(i) - px, 0.0, px - (i + 1.0)});
    const double dy = std::max({static_cast<double>(j) - py, 0.0, py - (j + 1.0)});
    return std::sqrt(dx * dx + dy * dy);
}

// Does the closed segment a->b touch the square of pixel (i, j) shrunk by `inset` on every side?
// (Liang-Barsky.)
bool segment_touches_pixel(double ax, double ay, double bx, double by, int i, int j, double inset) {
    double t0 = 0.0, t1 = 1.0;
    const double d[2] = {bx - ax, by - ay};
    const double p0[2] = {ax, ay};
    const double lo[2] = {i + inset, j + inset};
    const double hi[2] = {i + 1.0 - inset, j + 1.0 - inset};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0.0) {
            if (p0[k] < lo[k] || p0[k] > hi[k]) return false;
            continue;
        }
        double ta = (lo[k] - p0[k]) / d[k];
        double tb = (hi[k] - p0[k]) / d[k];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

// The pixels (in mask-local coordinates) whose closed squares touch the segment p0-p1.
std::vector<std::pair<int, int>> supercover(double x0, double y0, double x1, double y1) {
    std::vector<std::pair<int, int>> out;
    const bool by_columns = std::fabs(x1 - x0) >= std::fabs(y1 - y0);
    if (!by_columns) {
        // Walk rows instead: swap the axes, walk, swap back.
        auto swapped = supercover(y0, x0, y1, x1);
        for (auto& [a, b] : swapped) out.emplace_back(b, a);
        return out;
    }
    if (x0 > x1) {
        std::swap(x0, x1);
        std::swap(y0, y1);
    }
    const double slope = (y1 - y0) / (x1 - x0);
    for (int i = static_cast<int>(std::floor(x0)); i <= static_cast<int>(std::floor(x1)); ++i) {
        const double xa = std::max(static_cast<double>(i), x0);
        const double xb = std::min(i + 1.0, x1);
        if (xa > xb) continue;
        const double ya = y0 + slope * (xa - x0);
        const double yb = y0 + slope * (xb - x0);
        const double lo = std::min(ya, yb), hi = std::max(ya, yb);
        for (int j = static_cast<int>(std::ceil(lo)) - 1; j <= static_cast<int>(std::floor(hi)); ++j) {
            if (j + 1.0 >= lo && j <= hi) out.emplace_back(i, j);
        }
    }
    return out;
}

int layer_bit(int gx, int gy) {
    // Cells with the same layer bit are 4 cells (3200 px) apart in x and 8 in y: farther than
    // anything travels in kSteps, so a projectile only ever meets its own wall.
    return (gx % 4) + 4 * (gy % 8);
}

// Builds a wall of the given kind centred near (x, y) at a random angle and returns its
// description for create(), filling `wall` with the independent model.
EntityDesc make_wall(Rng& rng, WallKind kind, double x, double y, Wall& wall) {
    EntityDesc d;
    d.kind = BodyKind::static_body;
    wall.kind = kind;
    const auto half_len = static_cast<float>(kWallLength / 2.0);
    float angle = rng.uniform(-static_cast<float>(kPi), static_cast<float>(kPi));
    const Vec2 pos{static_cast<float>(x + rng.uniform(-20.0f, 20.0f)),
                   static_cast<float>(y + rng.uniform(-20.0f, 20.0f))};
    auto set_frame = [&](double a) {
        wall.tx = std::cos(a);
        wall.ty = std::sin(a);
        wall.nx = -wall.ty;
        wall.ny = wall.tx;
    };
    switch (kind) {
        case WallKind::obb: {
            // The entity's angle turns the box.
            d.position = pos;
            d.angle = angle;
            d.collider = Collider::box({half_len, 0.5f});
            wall.cx = pos.x;
            wall.cy = pos.y;
            wall.half = 0.5;
            set_frame(angle);
            break;
        }
        case WallKind::polygon: {
            // A 200 x 1 quad with its vertices already turned; the entity's angle stays 0.
            set_frame(angle);
            std::vector<Vec2> pts;
            const int su[4] = {-1, 1, 1, -1};
            const int sw[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                pts.push_back(
                    {static_cast<float>(su[k] * kWallLength / 2.0 * wall.tx + sw[k] * 0.5 * wall.nx),
                     static_cast<float>(su[k] * kWallLength / 2.0 * wall.ty + sw[k] * 0.5 * wall.ny)});
            }
            std::string error;
            const std::optional<Polygon> poly = make_polygon(pts, &error);
            EXPECT_TRUE(poly.has_value()) << error;
            d.position = pos;
            d.collider = Collider::polygon(poly.value_or(Polygon{}));
            wall.cx = pos.x;
            wall.cy = pos.y;
            wall.half = 0.5;
            break;
        }
        case WallKind::aabb: {
            // Horizontal or vertical (Aabb colliders never turn).
            const bool vertical = rng.below(2) == 1;
            d.position = pos;
            d.collider = vertical ? Collider::aabb({0.5f, half_len}) : Collider::aabb({half_len, 0.5f});
            wall.cx = pos.x;
            wall.cy = pos.y;
            wall.half = 0.5;
            set_frame(vertical ? kPi / 2.0 : 0.0);
            if (vertical) {  // exact frame: no cos(pi/2) rounding
                wall.tx = 0.0;
                wall.ty = 1.0;
                wall.nx = -1.0;
                wall.ny = 0.0;
            }
            break;
        }
        case WallKind::segment: {
            // Zero thickness. Half the walls turn by the entity's angle, half by their points.
            d.position = pos;
            wall.cx = pos.x;
            wall.cy = pos.y;
            wall.half = 0.0;
            set_frame(angle);
            if (rng.below(2) == 0) {
                d.angle = angle;
                d.collider = Collider::segment({-half_len, 0.0f}, {half_len, 0.0f});
            } else {
                const Vec2 a{static_cast<float>(-kWallLength / 2.0 * wall.tx),
                             static_cast<float>(-kWallLength / 2.0 * wall.ty)};
                d.collider = Collider::segment(a, -a);
                // The wall is the segment between the rounded points; refine the frame to it.
                const double len = std::hypot(2.0 * a.x, 2.0 * a.y);
                wall.tx = -2.0 * a.x / len;
                wall.ty = -2.0 * a.y / len;
                wall.nx = -wall.ty;
                wall.ny = wall.tx;
            }
            break;
        }
        case WallKind::mask: {
            // A third are straight axis-aligned lines (one pixel thick), the rest staircases at a
            // random angle. The line's centre has a random fractional position.
            const std::uint32_t shape = rng.below(3);
            if (shape == 0) angle = 0.0f;
            if (shape == 1) angle = static_cast<float>(kPi / 2.0);
            set_frame(angle);
            if (shape == 1) {
                wall.tx = 0.0;
                wall.ty = 1.0;
                wall.nx = -1.0;
                wall.ny = 0.0;
            }
            constexpr int kMargin = 104;
            constexpr int kSide = 2 * kMargin + 2;
            const int ox = static_cast<int>(std::lround(x)) - kMargin;
            const int oy = static_cast<int>(std::lround(y)) - kMargin;
            wall.mask_x = ox;
            wall.mask_y = oy;
            wall.cx = static_cast<double>(ox + kMargin) + static_cast<double>(rng.next_float());
            wall.cy = static_cast<double>(oy + kMargin) + static_cast<double>(rng.next_float());
            wall.half = std::fabs(wall.nx) + std::fabs(wall.ny);
            const double lx = wall.cx - ox, ly = wall.cy - oy;
            const double hx = kWallLength / 2.0 * wall.tx, hy = kWallLength / 2.0 * wall.ty;
            auto mask = std::make_shared<Mask>(kSide, kSide);
            for (const auto& [i, j] : supercover(lx - hx, ly - hy, lx + hx, ly + hy)) {
                if (i < 0 || j < 0 || i >= kSide || j >= kSide) continue;
                if (!mask->get(i, j)) {
                    mask->set(i, j, true);
                    wall.pixels.emplace_back(ox + i, oy + j);
                }
            }
            wall.mask = mask;
            d.position = {static_cast<float>(ox), static_cast<float>(oy)};
            d.collider = Collider::mask(mask, 0, 0);
            break;
        }
    }
    return d;
}

// One projectile and what the test saw of it.
struct Shot {
    bool bullet = false;
    BulletResponse response = BulletResponse::stop;
    float radius = 0.0f;
    float restitution = 0.0f;
    float speed = 0.0f;
    double incidence = 0.0;  // radians from the wall normal
    int side = 1;            // the start side along the wall normal
    Vec2 start;
    Vec2 velocity;
    Wall wall;
    EntityId id;
    EntityId wall_id;
    int world_index = 0;
    int cell = 0;
    // Seen during the run.
    bool hit_seen = false;  // bullet_hit (bullets) or contact_begin with the wall (circles)
    Vec2 hit_point;
    Vec2 last_position;
};

std::string describe(const Shot& s, const char* what, std::optional<Vec2> at = std::nullopt) {
    char buf[768];
    const Wall& w = s.wall;
    const std::string kind =
        s.bullet ? std::string("bullet/") + response_name(s.response) : std::string("circle");
    int n = std::snprintf(
        buf, sizeof buf,
        "%s: world %d cell %d, %s r=%.4g e=%.3g vs %s wall (centre (%.4f, %.4f), "
        "tangent (%.6f, %.6f), half-thickness %.3g); start (%.4f, %.4f) velocity (%.3f, %.3f) "
        "speed %.1f incidence %.2f deg side %+d",
        what, s.world_index, s.cell, kind.c_str(), static_cast<double>(s.radius),
        static_cast<double>(s.restitution), wall_name(w.kind), w.cx, w.cy, w.tx, w.ty, w.half,
        static_cast<double>(s.start.x), static_cast<double>(s.start.y), static_cast<double>(s.velocity.x),
        static_cast<double>(s.velocity.y), static_cast<double>(s.speed), s.incidence * 180.0 / kPi, s.side);
    std::string out(buf, static_cast<std::size_t>(std::max(n, 0)));
    if (at) {
        std::snprintf(buf, sizeof buf, "; at (%.4f, %.4f): u=%.4f, side*w=%.5f", static_cast<double>(at->x),
                      static_cast<double>(at->y), w.u(at->x, at->y), s.side * w.w(at->x, at->y));
        out += buf;
    }
    return out;
}

// Failures of one kind: how many, and the first few described.
struct Failures {
    explicit Failures(const char* what_failed) : what(what_failed) {}
    const char* what;
    int count = 0;
    std::vector<std::string> examples;
    void add(std::string example) {
        ++count;
        if (examples.size() < 4) examples.push_back(std::move(example));
    }
    std::string report() const {
        std::string out = std::string(what) + ": " + std::to_string(count) + " failures";
        for (const auto& e : examples) out += "\n  " + e;
        return out;
    }
};

// Chooses the projectile's path: incidence within +-80 degrees of the wall normal, a speed up
// to 20,000 px/s with at least r + 2 + half-thickness px per step across the wall, a start
// more than r + 1 px from the near face and less than one step's travel from its first contact,
// aimed so that first contact is in the middle half of the wall.
void make_shot(Rng& rng, Shot& s) {
    const Wall& w = s.wall;
    s.incidence = rng.uniform(static_cast<float>(-kMaxIncidence), static_cast<float>(kMaxIncidence));
    s.side = rng.below(2) == 0 ? 1 : -1;
    const double c = std::cos(s.incidence), sn = std::sin(s.incidence);
    const double min_speed = (s.radius + 2.0 + w.half) / (kDt * c);
    s.speed = rng.uniform(static_cast<float>(min_speed), kMaxSpeed);
    const double travel = static_cast<double>(s.speed) * kDt;
    // gap: from the near face (mask: from the band's outer bound) to the circle's edge.
    const double gap = rng.uniform(1.01f, static_cast<float>(0.999 * (travel * c - w.half)));
    const double u_hit =
        rng.uniform(static_cast<float>(-kWallLength / 4.0), static_cast<float>(kWallLength / 4.0));
    const double path = gap / c;
    const double u0 = u_hit - path * sn;
    const double w0 = s.side * (w.half + s.radius + gap);
    const double dx = -s.side * c * w.nx + sn * w.tx;
    const double dy = -s.side * c * w.ny + sn * w.ty;
    s.start = {static_cast<float>(w.cx + u0 * w.tx + w0 * w.nx),
               static_cast<float>(w.cy + u0 * w.ty + w0 * w.ny)};
    s.velocity = {static_cast<float>(s.speed * dx), static_cast<float>(s.speed * dy)};
}

struct Case {
    bool bullets;
    WallKind wall;
};

void PrintTo(const Case& c, std::ostream* os) {
    *os << (c.bullets ? "bullets" : "circles") << " vs " << wall_name(c.wall) << " walls";
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
    return std::string(info.param.bullets ? "bullets_" : "circles_") + wall_name(info.param.wall);
}

class Tunnelling : public testing::TestWithParam<Case> {};

}  // namespace

// Each projectile is counted once, under the first check it fails.
TEST_P(Tunnelling, NothingEndsOnTheFarSideOfAOnePixelWall) {
    const Case param = GetParam();
    Failures far_side{"ended a step on the far side of its wall"};
    Failures entered{
        "circle centre closer to the near face than r - 0.05 px (or a mask pixel centre inside it)"};
    Failures vanished{"projectile vanished or non-finite when it should not have"};
    Failures no_hit{"no bullet_hit / contact_begin naming its wall"};
    Failures wrong_hit{"bullet_hit naming another entity"};
    Failures bad_fraction{"bullet_hit fraction outside [0, 1] or not matching the point"};
    Failures off_face{"bullet_hit point not on the near face within 0.01 px"};
    Failures late{"bullet_hit point not the first contact along the path"};
    Failures moved{"stopped bullet not at its hit point"};
    Failures not_despawned{"despawning bullet still alive after its hit"};
    int total = 0;

    for (int wi = 0; wi < kWorldsPerCase; ++wi) {
        Rng rng(0x70e11e5ull + static_cast<std::uint64_t>(param.bullets) * 1000003ull +
                    static_cast<std::uint64_t>(param.wall) * 7919ull + static_cast<std::uint64_t>(wi),
                17);
        World world;  // no gravity
        std::vector<Shot> shots;
        shots.reserve(kGrid * kGrid);
        for (int gy = 0; gy < kGrid; ++gy) {
            for (int gx = 0; gx < kGrid; ++gx) {
                Shot s;
                s.world_index = wi;
                s.cell = gy * kGrid + gx;
                s.bullet = param.bullets;
                const double x = (gx - (kGrid - 1) / 2.0) * kCell;
                const double y = (gy - (kGrid - 1) / 2.0) * kCell;
                EntityDesc wd = make_wall(rng, param.wall, x, y, s.wall);
                const std::uint32_t bit = 1u << layer_bit(gx, gy);
                wd.layer = bit;
                wd.collides_with = bit;
                EntityDesc pd;
                if (s.bullet) {
                    pd.kind = BodyKind::bullet;
                    const std::uint32_t pick = rng.below(20);
                    s.response = pick < 10 ? BulletResponse::stop
                                           : (pick < 17 ? BulletResponse::despawn : BulletResponse::ricochet);
                    pd.on_hit = s.response;
                } else {
                    pd.kind = BodyKind::dynamic;
                    s.radius = rng.uniform(0.5f, 20.0f);
                    s.restitution = rng.below(2) == 0 ? 0.0f : rng.next_float();
                    pd.collider = Collider::circle(s.radius);
                    pd.restitution = s.restitution;
                    pd.gravity_scale = 0.0f;
                }
                make_shot(rng, s);
                pd.position = s.start;
                pd.velocity = s.velocity;
                pd.layer = bit;
                pd.collides_with = bit;
                pd.user_data = static_cast<std::uint64_t>(s.cell);
                // Both id orders: the wall first in half the cells, the projectile first in the rest.
                if (rng.below(2) == 0) {
                    s.wall_id = world.create(wd);
                    s.id = world.create(pd);
                } else {
                    s.id = world.create(pd);
                    s.wall_id = world.create(wd);
                }
                s.last_position = s.start;
                shots.push_back(std::move(s));
            }
        }
        total += static_cast<int>(shots.size());
        // Map from an entity's slot to its shot.
        std::vector<int> shot_of_slot(2 * shots.size() + 1, -1);
        for (std::size_t i = 0; i < shots.size(); ++i) shot_of_slot[shots[i].id.index] = static_cast<int>(i);
        std::vector<char> failed(shots.size(), 0);
        auto fail = [&](Failures& f, std::size_t i, const char* what, std::optional<Vec2> at = std::nullopt) {
            if (!failed[i]) f.add(describe(shots[i], what, at));
            failed[i] = 1;  // one example per shot: its first failure
        };

        for (int step = 0; step < kSteps; ++step) {
            std::vector<Vec2> before(shots.size());
            for (std::size_t i = 0; i < shots.size(); ++i) {
                if (const EntityDesc* e = world.get(shots[i].id)) before[i] = e->position;
            }
            world.step(kDt);

            for (const Event& ev : world.events()) {
                if (ev.type == EventType::bullet_hit) {
                    if (ev.a.index >= shot_of_slot.size() || shot_of_slot[ev.a.index] < 0) continue;
                    const auto i = static_cast<std::size_t>(shot_of_slot[ev.a.index]);
                    Shot& s = shots[i];
                    if (ev.a != s.id) continue;
                    if (ev.b != s.wall_id) {
                        fail(wrong_hit, i, "bullet_hit names another entity", ev.point);
                        continue;
                    }
                    if (s.hit_seen) continue;  // only the first hit is checked in detail
                    s.hit_seen = true;
                    s.hit_point = ev.point;
                    const Wall& w = s.wall;
                    const double px = ev.point.x, py = ev.point.y;
                    // The path of this step.
                    const double fx = before[i].x, fy = before[i].y;
                    const double vx = static_cast<double>(s.velocity.x) * kDt,
                                 vy = static_cast<double>(s.velocity.y) * kDt;
                    const double len = std::hypot(vx, vy);
                    if (!(ev.fraction >= 0.0f && ev.fraction <= 1.0f) ||
                        std::hypot(fx + ev.fraction * vx - px, fy + ev.fraction * vy - py) > 0.02) {
                        fail(bad_fraction, i, ("fraction " + std::to_string(ev.fraction)).c_str(), ev.point);
                        continue;
                    }
                    // On the path of the step.
                    const double off_path = std::fabs((px - fx) * vy - (py - fy) * vx) / len;
                    if (w.kind != WallKind::mask) {
                        const double face = s.side * w.w(px, py) - w.half;
                        if (std::fabs(face) > kFaceTol || off_path > kFaceTol ||
                            std::fabs(w.u(px, py)) > kWallLength / 2.0 + kFaceTol) {
                            fail(off_face, i, "hit point off the near face", ev.point);
                        }
                    } else {
                        double nearest = std::numeric_limits<double>::infinity();
                        for (const auto& [pi, pj] : w.pixels)
                            nearest = std::min(nearest, distance_to_pixel(px, py, pi, pj));
                        if (nearest > kFaceTol || off_path > kFaceTol || s.side * w.w(px, py) < -kFaceTol) {
                            fail(off_face, i, "hit point not on a set pixel's square", ev.point);
                        } else {
                            // Nothing may be touched before it, beyond rounding: the path up to
                            // 0.02 px before the hit may not enter a set pixel's square shrunk by
                            // 0.01 px. (A path may graze a corner by less than a float resolves
                            // here, 1/4096 px at |x| >= 2048; such a graze may be missed.)
                            const double bx = px - 0.02 * vx / len, by = py - 0.02 * vy / len;
                            for (const auto& [pi, pj] : w.pixels) {
                                if (segment_touches_pixel(fx, fy, bx, by, pi, pj, kFaceTol)) {
                                    fail(late, i, "the path touches a set pixel before the hit point",
                                         ev.point);
                                    break;
                                }
                            }
                        }
                    }
                } else if (ev.type == EventType::contact_begin && !param.bullets) {
                    for (EntityId id : {ev.a, ev.b}) {
                        if (id.index < shot_of_slot.size() && shot_of_slot[id.index] >= 0) {
                            Shot& s = shots[static_cast<std::size_t>(shot_of_slot[id.index])];
                            if (s.id == id && (ev.a == s.wall_id || ev.b == s.wall_id)) s.hit_seen = true;
                        }
                    }
                }
            }

            for (std::size_t i = 0; i < shots.size(); ++i) {
                Shot& s = shots[i];
                const Wall& w = s.wall;
                const EntityDesc* e = world.get(s.id);
                if (e == nullptr) {
                    if (!(s.bullet && s.response == BulletResponse::despawn && s.hit_seen)) {
                        fail(vanished, i, "gone");
                    }
                    continue;
                }
                const Vec2 p = e->position;
                s.last_position = p;
                if (!is_finite(p)) {
                    fail(vanished, i, "non-finite position", p);
                    continue;
                }
                const double sw = s.side * w.w(p.x, p.y);
                if (s.bullet) {
                    const double near_face = w.kind == WallKind::mask ? 0.0 : w.half;
                    if (sw < near_face - kFaceTol) {
                        fail(far_side, i, "bullet beyond the near face", p);
                        continue;
                    }
                    if (s.hit_seen && s.response == BulletResponse::despawn) {
                        fail(not_despawned, i, "still alive", p);
                        continue;
                    }
                    if (s.hit_seen && s.response == BulletResponse::stop &&
                        std::hypot(p.x - s.hit_point.x, p.y - s.hit_point.y) > kFaceTol) {
                        fail(moved, i, "stopped bullet moved", p);
                        continue;
                    }
                } else {
                    if (sw < 0.0) {
                        fail(far_side, i, "circle centre past the wall's centre line", p);
                        continue;
                    }
                    if (w.kind != WallKind::mask) {
                        if (sw < w.half + s.radius - kCircleTol)
                            fail(entered, i, "circle entered the wall", p);
                    } else {
                        // The pixel rule: no set pixel's centre may lie inside the circle.
                        double nearest = std::numeric_limits<double>::infinity();
                        for (const auto& [pi, pj] : w.pixels) {
                            nearest = std::min(nearest, std::hypot(pi + 0.5 - p.x, pj + 0.5 - p.y));
                        }
                        if (nearest < s.radius - kCircleTol) {
                            fail(
                                entered, i,
                                ("a pixel centre " + std::to_string(nearest) + " px from the centre").c_str(),
                                p);
                        }
                    }
                }
            }
        }
        for (std::size_t i = 0; i < shots.size(); ++i) {
            if (!shots[i].hit_seen) fail(no_hit, i, "never hit its wall", shots[i].last_position);
        }
    }

    EXPECT_GE(total, 10000 / kSanitizerDivisor);
    const Failures* all[] = {&far_side,     &entered,  &vanished, &no_hit, &wrong_hit,
                             &bad_fraction, &off_face, &late,     &moved,  &not_despawned};
    for (const Failures* f : all) EXPECT_EQ(f->count, 0) << "of " << total << " projectiles, " << f->report();
}

namespace {

std::vector<Case> all_cases() {
    std::vector<Case> out;
    for (bool bullets : {true, false}) {
        for (WallKind k : kWallKinds) out.push_back({bullets, k});
    }
    return out;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Walls, Tunnelling, testing::ValuesIn(all_cases()), case_name);
