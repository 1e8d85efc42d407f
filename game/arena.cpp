// arena.cpp: the arena game's rules, drawing and bookkeeping (see arena.h).
#include "arena.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <tuple>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/core/text.h"
#include "jostle/core/hash.h"
#include "jostle/render/overlay.h"
#include "jostle/render/png_io.h"
#include "level.h"

#ifndef JOSTLE_SOURCE_ASSETS
#define JOSTLE_SOURCE_ASSETS "assets"
#endif

namespace jostle::game {
namespace {

enum class Kind : std::uint8_t { player, wall, crate, rock, pickup, cannon, bullet, ball, prop, blob };
constexpr const char* kKindNames[] = {"player", "wall", "crate", "rock", "pickup", "cannon", "bullet", "ball", "prop", "blob"};
constexpr const char* kEventNames[] = {"fire",       "bullet_hit", "rock_hit",   "pickup",
                                       "cannon_fire", "player_hit", "ricochet", "blob_touch"};
// Bits of events_seen_, in the order of kEventNames.
enum GameEvent : int {
    kEventFire, kEventBulletHit, kEventRockHit, kEventPickup, kEventCannonFire, kEventPlayerHit, kEventRicochet, kEventBlobTouch
};
constexpr const char* kVariableNames[] = {"score", "shots", "balls", "fastest", "touches"};

std::string read_file(const std::string& path, const char* what = "the level file") { return read_text_file(path, what); }

// The sprite files (assets/sprites/*.png), by name, sorted.
std::vector<std::string> sprite_names(const std::string& assets_dir) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(assets_dir + "/sprites", ec)) {
        if (entry.path().extension() == ".png") names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

struct Thing {
    EntityId id;
    std::uint64_t serial = 0;  // the entity's user_data; creation order
    std::string name;
    Kind kind = Kind::wall;
    bool alive = true;
    int lifetime = -1;        // ticks left; -1 forever
    int period = 0;           // cannons
    float speed = 0.0f;       // cannons, blobs
    int bounces = 0;          // bullets: ricochets left
    Vec2 from, to;            // blobs: walking from `from` to `to`, then back
    std::string sprite;       // props
};

// Colours of the game's own drawing (the overlay has its own).
constexpr Color kBackground{24, 26, 32, 255};
constexpr Color kWallColor{110, 110, 120, 255};
constexpr Color kCrateColor{150, 105, 60, 255};
constexpr Color kRockColor{120, 112, 100, 255};
constexpr Color kPickupColor{250, 210, 60, 255};
constexpr Color kCannonColor{150, 40, 40, 255};
constexpr Color kBallColor{255, 140, 40, 255};
constexpr Color kBulletColor{255, 255, 200, 255};
constexpr Color kPlayerColor{90, 180, 255, 255};
constexpr Color kHudColor{230, 230, 230, 255};

// The game's pictures, and the collision masks made from them (alpha >= 128 is solid).
struct Sprites {
    std::map<std::string, Image, std::less<>> images;
    std::map<std::string, std::shared_ptr<const Mask>, std::less<>> masks;

    const Image& image(std::string_view name) const { return images.find(name)->second; }
    bool has(std::string_view name) const { return images.find(name) != images.end(); }
    std::shared_ptr<const Mask> mask(std::string_view name) {
        auto it = masks.find(name);
        if (it == masks.end()) {
            const Image& im = image(name);
            it = masks.emplace(std::string(name),
                               std::make_shared<const Mask>(Mask::from_alpha(im.rgba.data(), im.width, im.height, 127)))
                     .first;
        }
        return it->second;
    }
};

class ArenaSimulation : public Simulation {
public:
    ArenaSimulation(const Level& level, const std::string& level_path, Sprites sprites, const Rules& rules,
                    std::uint64_t seed, int tick_rate)
        : level_(level), level_path_(level_path), sprites_(std::move(sprites)), rules_(rules),
          world_(WorldDesc{.gravity = {0.0f, 0.0f}, .seed = seed}), dt_(1.0f / static_cast<float>(tick_rate)) {
        // The ship: a triangle pointing along +x.
        const Vec2 ship[] = {{14.0f, 0.0f}, {-10.0f, -9.0f}, {-10.0f, 9.0f}};
        player_ = add(Thing{.name = "player", .kind = Kind::player},
                      EntityDesc{.kind = BodyKind::dynamic, .position = level.player_start, .angle = level.player_angle,
                                 .collider = Collider::polygon(*make_polygon(ship)), .inverse_mass = 0.25f});
        for (const LevelThing& t : level.things) {
            switch (t.kind) {
                case LevelThing::Kind::wall: {
                    const Vec2 half = (t.size - t.position) * 0.5f;
                    add(Thing{.name = t.name, .kind = Kind::wall},
                        EntityDesc{.kind = BodyKind::static_body, .position = t.position + half, .collider = Collider::aabb(half)});
                    break;
                }
                case LevelThing::Kind::crate:
                    add(Thing{.name = t.name, .kind = Kind::crate},
                        EntityDesc{.kind = BodyKind::dynamic, .position = t.position, .angle = t.angle,
                                   .collider = Collider::box(t.size * 0.5f), .inverse_mass = 0.5f});
                    break;
                case LevelThing::Kind::rock_circle:
                    add(Thing{.name = t.name, .kind = Kind::rock},
                        EntityDesc{.kind = BodyKind::dynamic, .position = t.position, .collider = Collider::circle(t.radius),
                                   .inverse_mass = 1.0f / t.mass});
                    break;
                case LevelThing::Kind::rock_polygon:
                    add(Thing{.name = t.name, .kind = Kind::rock},
                        EntityDesc{.kind = BodyKind::dynamic, .position = t.position, .collider = Collider::polygon(t.polygon),
                                   .inverse_mass = 1.0f / t.mass});
                    break;
                case LevelThing::Kind::prop:
                    if (!sprites_.has(t.sprite)) {
                        throw InputError(SourceLocation{level_path, t.line, t.sprite_column},
                                         "no sprite '" + t.sprite + "' (expected a file sprites/" + t.sprite + ".png in the assets)");
                    }
                    add(Thing{.name = t.name, .kind = Kind::prop, .sprite = t.sprite},
                        EntityDesc{.kind = BodyKind::static_body, .position = t.position,
                                   .collider = Collider::mask(sprites_.mask(t.sprite))});
                    break;
                case LevelThing::Kind::blob:
                    if (!sprites_.has("blob")) {
                        throw InputError(SourceLocation{level_path, t.line, t.sprite_column},
                                         "no sprite 'blob' (expected a file sprites/blob.png in the assets)");
                    }
                    add(Thing{.name = t.name, .kind = Kind::blob, .speed = t.speed, .from = t.position, .to = t.size},
                        EntityDesc{.kind = BodyKind::kinematic, .position = t.position,
                                   .collider = Collider::mask(sprites_.mask("blob"))});
                    break;
                case LevelThing::Kind::pickup:
                    add(Thing{.name = t.name, .kind = Kind::pickup},
                        EntityDesc{.kind = BodyKind::trigger, .position = t.position, .collider = Collider::circle(t.radius)});
                    break;
                case LevelThing::Kind::cannon:
                    add(Thing{.name = t.name, .kind = Kind::cannon, .period = t.period, .speed = t.speed},
                        EntityDesc{.kind = BodyKind::static_body, .position = t.position, .angle = t.angle,
                                   .collider = Collider::circle(10.0f)});
                    break;
            }
        }
    }

    void tick(InputFrame input) override {
        drive_player(input);
        fire(input);
        fire_cannons();
        walk_blobs();
        drag();
        world_.step(dt_);
        handle_events();
        age();
        ++ticks_;
    }

    std::int64_t ticks_done() const override { return ticks_; }

    std::uint64_t state_hash() const override {
        Hasher h;
        h.u64(world_.state_hash());
        h.u64(static_cast<std::uint64_t>(ticks_));
        h.u64(static_cast<std::uint64_t>(score_));
        h.u64(static_cast<std::uint64_t>(shots_));
        h.u64(static_cast<std::uint64_t>(balls_));
        h.u64(static_cast<std::uint64_t>(touches_));
        h.u32(static_cast<std::uint32_t>(cooldown_));
        h.u32(events_seen_);
        h.u64(things_.size());
        for (const Thing& t : things_) {
            h.u64(t.serial);
            h.u32(t.alive ? 1u : 0u);
            h.u32(static_cast<std::uint32_t>(t.lifetime));
            h.u32(static_cast<std::uint32_t>(t.bounces));
            h.f32(t.from.x);
            h.f32(t.from.y);
        }
        return h.value();
    }

    const World& world() const override { return world_; }

    std::optional<Vec2> entity_position(std::string_view name) const override {
        for (const Thing& t : things_) {
            if (t.alive && t.name == name) return world_.get(t.id)->position;
        }
        return std::nullopt;
    }

    // The level's things and the player, then bullet_N and ball_N for the first N fired: those
    // fired so far, or any.
    bool entity_named(std::string_view name) const override { return named(name, shots_, balls_); }
    bool entity_name_possible(std::string_view name) const override { return named(name, INT64_MAX, INT64_MAX); }

    std::int64_t count(std::string_view kind) const override {
        std::int64_t n = 0;
        for (const Thing& t : things_) n += t.alive && kind == kKindNames[static_cast<int>(t.kind)] ? 1 : 0;
        return n;
    }

    std::optional<double> variable(std::string_view name) const override {
        if (name == "score") return static_cast<double>(score_);
        if (name == "shots") return static_cast<double>(shots_);
        if (name == "balls") return static_cast<double>(balls_);
        if (name == "fastest") return static_cast<double>(fastest());
        if (name == "touches") return static_cast<double>(touches_);
        return std::nullopt;
    }

    bool event_happened(std::string_view name) const override {
        for (int i = 0; i < static_cast<int>(std::size(kEventNames)); ++i) {
            if (name == kEventNames[i]) return (events_seen_ >> i) & 1u;
        }
        return false;
    }

    std::vector<std::string> kinds() const override { return {std::begin(kKindNames), std::end(kKindNames)}; }
    std::vector<std::string> variables() const override { return {std::begin(kVariableNames), std::end(kVariableNames)}; }
    std::vector<std::string> events() const override { return {std::begin(kEventNames), std::end(kEventNames)}; }

    std::vector<EntityDump> dump() const override {
        std::vector<EntityDump> out;
        out.push_back(EntityDump{"game",
                                 {{"score", std::to_string(score_)},
                                  {"shots", std::to_string(shots_)},
                                  {"balls", std::to_string(balls_)},
                                  {"touches", std::to_string(touches_)},
                                  {"cooldown", std::to_string(cooldown_)}}});
        for (const Thing& t : things_) {
            if (!t.alive || t.kind == Kind::wall || t.kind == Kind::prop) continue;  // they never move
            const EntityDesc& e = *world_.get(t.id);
            EntityDump d{t.name,
                         {{"kind", kKindNames[static_cast<int>(t.kind)]},
                          {"x", shortest_text(e.position.x)},
                          {"y", shortest_text(e.position.y)},
                          {"angle", shortest_text(e.angle)},
                          {"vx", shortest_text(e.velocity.x)},
                          {"vy", shortest_text(e.velocity.y)}}};
            if (t.lifetime >= 0) d.fields.push_back({"lifetime", std::to_string(t.lifetime)});
            if (t.kind == Kind::bullet) d.fields.push_back({"bounces", std::to_string(t.bounces)});
            out.push_back(std::move(d));
        }
        return out;
    }

    Vec2 level_size() const override { return level_.size; }

    void draw(Renderer& renderer, const DrawOptions& options) const override {
        // Sprites go into each renderer's atlas once.
        if (renderer.serial() != renderer_serial_) {
            sprite_ids_.clear();
            for (const auto& [name, image] : sprites_.images) sprite_ids_[name] = renderer.add_sprite(image);
            renderer_serial_ = renderer.serial();
        }
        // Each thing as its sprite, or as its shape in its colour when the assets have no
        // such sprite (a test's own assets folder, say).
        const auto draw = [&](const Shape& shape, std::string_view name, Vec2 centre, float angle, float scale, Color color) {
            const auto it = sprite_ids_.find(name);
            if (it == sprite_ids_.end()) {
                renderer.fill_shape(shape, color);
                return;
            }
            renderer.draw_sprite(it->second, centre, angle, Vec2{scale, scale});
        };
        renderer.fill_rect(Aabb{{0.0f, 0.0f}, level_.size}, kBackground);
        for (const Thing& t : things_) {
            if (!t.alive) continue;
            const Shape shape = world_.shape_of(t.id);
            const EntityDesc& e = *world_.get(t.id);
            switch (t.kind) {
                case Kind::wall: renderer.fill_shape(shape, kWallColor); break;
                case Kind::crate: {
                    const Obb& box = std::get<Obb>(shape);
                    const auto it = sprite_ids_.find("crate");
                    if (it == sprite_ids_.end()) renderer.fill_shape(shape, kCrateColor);
                    else renderer.draw_sprite(it->second, box.center, box.angle(), box.half * (2.0f / 32.0f));
                    break;
                }
                case Kind::rock:
                    if (const Circle* c = std::get_if<Circle>(&shape)) {
                        draw(shape, "boulder", c->center, e.angle, c->radius / 16.0f, kRockColor);
                    } else {
                        renderer.fill_shape(shape, kRockColor);
                        renderer.outline_shape(shape, Color{80, 74, 66, 255}, 2.0f);
                    }
                    break;
                case Kind::pickup: draw(shape, "coin", e.position, 0.0f, std::get<Circle>(shape).radius / 8.0f, kPickupColor); break;
                case Kind::cannon: draw(shape, "cannon", e.position, e.angle, 1.0f, kCannonColor); break;
                case Kind::ball: draw(shape, "ball", e.position, 0.0f, std::get<Circle>(shape).radius / 6.0f, kBallColor); break;
                case Kind::bullet:
                    renderer.draw_line(e.position - e.velocity * (dt_ * 0.5f), e.position, kBulletColor, 2.0f);
                    break;
                case Kind::player: draw(shape, "ship", e.position, e.angle, 1.0f, kPlayerColor); break;
                case Kind::prop:
                case Kind::blob: {
                    // Exactly over the mask's pixels (masks sit on whole pixels).
                    const PlacedMask& m = std::get<PlacedMask>(shape);
                    const Vec2 centre{static_cast<float>(m.x) + static_cast<float>(m.mask->width()) * 0.5f,
                                      static_cast<float>(m.y) + static_cast<float>(m.mask->height()) * 0.5f};
                    renderer.draw_sprite(sprite_ids_.find(t.kind == Kind::blob ? "blob" : t.sprite)->second, centre);
                    break;
                }
            }
        }
        if (options.overlay) draw_overlay(renderer, world_);
        if (options.hud) {
            // The tick just simulated, which is also the frame's number.
            const std::string hud = "SCORE " + std::to_string(score_) + "   TICK " + std::to_string(ticks_ - 1);
            renderer.draw_text(Vec2{8.0f, 8.0f}, hud, kHudColor, 2);
        }
    }

private:
    bool named(std::string_view name, std::int64_t shots, std::int64_t balls) const {
        if (name == "player") return true;
        for (const LevelThing& t : level_.things) {
            if (t.name == name) return true;
        }
        const auto numbered = [&](std::string_view prefix, std::int64_t fired) {
            if (!name.starts_with(prefix)) return false;
            const std::string_view digits = name.substr(prefix.size());
            std::int64_t n = 0;
            const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
            return ec == std::errc{} && end == digits.data() + digits.size() && digits[0] != '0' && n >= 1 && n <= fired;
        };
        return numbered("bullet_", shots) || numbered("ball_", balls);
    }

    std::size_t add(Thing thing, EntityDesc desc) {
        if (world_.entity_count() >= static_cast<std::size_t>(kMaxEntities)) {
            throw InputError(SourceLocation{level_path_, 0, 0},
                             "tick " + std::to_string(ticks_) + ": the world would hold more than " +
                                 std::to_string(kMaxEntities) + " entities (the limit; too many cannons firing too often?)");
        }
        thing.serial = next_serial_++;
        desc.user_data = thing.serial;
        thing.id = world_.create(desc);
        things_.push_back(std::move(thing));
        return things_.size() - 1;
    }

    // The thing an entity's user_data names (things_ stays sorted by serial).
    Thing* thing_of(std::uint64_t serial) {
        const auto it = std::lower_bound(things_.begin(), things_.end(), serial,
                                         [](const Thing& t, std::uint64_t s) { return t.serial < s; });
        return it != things_.end() && it->serial == serial ? &*it : nullptr;
    }

    void drive_player(InputFrame input) {
        const EntityDesc& p = *world_.get(things_[player_].id);
        const float turn = (input.holds(kRight) ? 1.0f : 0.0f) - (input.holds(kLeft) ? 1.0f : 0.0f);
        const float angle = p.angle + turn * rules_.turn_speed * dt_;
        const Vec2 forward{std::cos(angle), std::sin(angle)};
        Vec2 velocity = p.velocity * rules_.coast;
        if (input.holds(kUp)) velocity = forward * rules_.drive_speed;
        else if (input.holds(kDown)) velocity = forward * -rules_.reverse_speed;
        world_.set_angle(things_[player_].id, angle);
        world_.set_angular_velocity(things_[player_].id, 0.0f);
        world_.set_velocity(things_[player_].id, velocity);
    }

    void fire(InputFrame input) {
        if (cooldown_ > 0) --cooldown_;
        if (!input.holds(kFire) || cooldown_ > 0) return;
        const EntityDesc& p = *world_.get(things_[player_].id);
        const Vec2 forward{std::cos(p.angle), std::sin(p.angle)};
        ++shots_;
        // Bullets ricochet off walls (the world reflects them); the game ends them on anything
        // else, or when their bounces are used up.
        add(Thing{.name = "bullet_" + std::to_string(shots_), .kind = Kind::bullet, .lifetime = rules_.bullet_lifetime,
                  .bounces = rules_.bullet_bounces},
            EntityDesc{.kind = BodyKind::bullet, .position = p.position + forward * 15.0f,
                       .velocity = forward * rules_.bullet_speed, .on_hit = BulletResponse::ricochet,
                       .ignore = things_[player_].id});
        cooldown_ = rules_.fire_cooldown;
        events_seen_ |= 1u << kEventFire;
    }

    void fire_cannons() {
        const std::size_t count = things_.size();  // balls added below are not cannons
        for (std::size_t i = 0; i < count; ++i) {
            const Thing& t = things_[i];
            if (t.kind != Kind::cannon || !t.alive || (ticks_ + 1) % t.period != 0) continue;
            const EntityDesc& c = *world_.get(t.id);
            const Vec2 dir{std::cos(c.angle), std::sin(c.angle)};
            const float speed = t.speed;
            const EntityId cannon = t.id;
            ++balls_;
            add(Thing{.name = "ball_" + std::to_string(balls_), .kind = Kind::ball, .lifetime = rules_.ball_lifetime},
                EntityDesc{.kind = BodyKind::dynamic, .position = c.position + dir * (10.0f + rules_.ball_radius + 2.0f),
                           .velocity = dir * speed, .collider = Collider::circle(rules_.ball_radius),
                           .inverse_mass = 2.0f, .restitution = 0.6f, .ignore = cannon});
            events_seen_ |= 1u << kEventCannonFire;
        }
    }

    // Blobs walk to one end of their patrol, then back, at their speed.
    void walk_blobs() {
        for (Thing& t : things_) {
            if (!t.alive || t.kind != Kind::blob) continue;
            const EntityDesc& e = *world_.get(t.id);
            const Vec2 to_go = t.to - e.position;
            const float distance = length(to_go);
            if (distance <= t.speed * dt_) {
                // Arrives this tick: exactly at the end, then turns round.
                world_.set_velocity(t.id, to_go * (1.0f / dt_));
                std::swap(t.from, t.to);
            } else {
                world_.set_velocity(t.id, to_go * (t.speed / distance));
            }
        }
    }

    // The fastest crate or rock (px/s): a crowd has settled when this is near 0.
    float fastest() const {
        float best = 0.0f;
        for (const Thing& t : things_) {
            if (t.alive && (t.kind == Kind::crate || t.kind == Kind::rock)) best = std::max(best, length(world_.get(t.id)->velocity));
        }
        return best;
    }

    // Top-down drag: pushed crates and rocks slow down and stop.
    void drag() {
        for (const Thing& t : things_) {
            if (!t.alive || (t.kind != Kind::crate && t.kind != Kind::rock)) continue;
            const EntityDesc& e = *world_.get(t.id);
            world_.set_velocity(t.id, e.velocity * 0.9f);
            world_.set_angular_velocity(t.id, e.angular_velocity * 0.9f);
        }
    }

    void handle_events() {
        for (const Event& e : world_.events()) {
            Thing* a = thing_of(e.a_user_data);
            Thing* b = thing_of(e.b_user_data);
            if (a == nullptr || b == nullptr) continue;
            switch (e.type) {
                case EventType::bullet_hit:
                    if (!a->alive) break;  // ended by an earlier hit this step
                    events_seen_ |= 1u << kEventBulletHit;
                    if (b->kind == Kind::rock) {
                        score_ += rules_.rock_hit_score;
                        events_seen_ |= 1u << kEventRockHit;
                    }
                    if (b->kind == Kind::wall && a->bounces > 0) {
                        --a->bounces;
                        events_seen_ |= 1u << kEventRicochet;
                    } else if (world_.alive(a->id)) {
                        world_.destroy(a->id);
                        a->alive = false;
                    }
                    break;
                case EventType::trigger_enter:
                    if (a->kind == Kind::pickup && b->kind == Kind::player && a->alive) {
                        score_ += rules_.pickup_score;
                        events_seen_ |= 1u << kEventPickup;
                        world_.destroy(a->id);
                        a->alive = false;
                    }
                    break;
                case EventType::contact_begin: {
                    const auto pair = [&](Kind x, Kind y) { return (a->kind == x && b->kind == y) || (a->kind == y && b->kind == x); };
                    if (pair(Kind::ball, Kind::player)) events_seen_ |= 1u << kEventPlayerHit;
                    if (pair(Kind::blob, Kind::player)) events_seen_ |= 1u << kEventBlobTouch;
                    if (a->kind == Kind::player || b->kind == Kind::player) ++touches_;
                    break;
                }
                default: break;
            }
        }
    }

    void age() {
        for (Thing& t : things_) {
            if (!t.alive) continue;
            if (!world_.alive(t.id)) {  // the world despawned it (a bullet that hit)
                t.alive = false;
                continue;
            }
            if (t.lifetime > 0 && --t.lifetime == 0) {
                world_.destroy(t.id);
                t.alive = false;
            }
        }
        // Forget what is gone, so a long run costs no more per tick than a short one. The
        // player (serial 0, created first) never goes.
        std::erase_if(things_, [](const Thing& t) { return !t.alive; });
    }

    Level level_;
    std::string level_path_;  // for messages
    Sprites sprites_;
    Rules rules_;
    World world_;
    float dt_;
    std::vector<Thing> things_;  // the living, in creation order; user_data is the serial
    std::uint64_t next_serial_ = 0;
    std::size_t player_ = 0;     // always things_[0]
    std::int64_t ticks_ = 0;
    std::int64_t score_ = 0;
    std::int64_t shots_ = 0;
    std::int64_t balls_ = 0;
    std::int64_t touches_ = 0;  // contacts the ship began with anything solid
    int cooldown_ = 0;
    std::uint32_t events_seen_ = 0;
    // The sprites' ids in the renderer that drew last (Renderer::serial says which).
    mutable std::uint64_t renderer_serial_ = 0;
    mutable std::map<std::string, SpriteId, std::less<>> sprite_ids_;
};

}  // namespace

std::string default_assets_dir() {
    if (const char* env = std::getenv("JOSTLE_ASSETS"); env != nullptr && *env != '\0') return env;
    return JOSTLE_SOURCE_ASSETS;
}

ArenaGame::ArenaGame(std::string assets_dir, Rules rules) : assets_dir_(std::move(assets_dir)), rules_(rules) {
    vocabulary_.actions = {"left", "right", "up", "down", "fire"};
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(assets_dir_ + "/levels", ec)) {
        if (entry.path().extension() == ".level") vocabulary_.levels.push_back(entry.path().stem().string());
    }
    // Without them every level would be "unknown (expected one of: )": say what is wrong instead.
    if (ec) {
        throw InputError(SourceLocation{assets_dir_ + "/levels", 0, 0},
                         "cannot list the levels: " + ec.message() +
                             " (expected the assets folder's levels/NAME.level files; --assets or $JOSTLE_ASSETS says where it is)");
    }
    if (vocabulary_.levels.empty()) {
        throw InputError(SourceLocation{assets_dir_ + "/levels", 0, 0},
                         "the assets' levels folder has no levels (expected NAME.level files in it; --assets or "
                         "$JOSTLE_ASSETS says where the assets are)");
    }
    std::sort(vocabulary_.levels.begin(), vocabulary_.levels.end());
}

std::string ArenaGame::level_path(const std::string& level) const { return assets_dir_ + "/levels/" + level + ".level"; }

std::string ArenaGame::asset_named(const std::string& path) const {
    for (const std::string& level : vocabulary_.levels) {
        if (same_file(path, level_path(level))) return "is the level '" + level + "' of the assets";
    }
    for (const std::string& name : sprite_names(assets_dir_)) {
        if (same_file(path, assets_dir_ + "/sprites/" + name + ".png")) return "is the sprite '" + name + "' of the assets";
    }
    // A new file there would be read as a level or sprite too (and change every level-hash).
    const std::filesystem::path p(path);
    const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    std::error_code ec;
    for (const auto& [sub, extension, kind] : {std::tuple{"/levels", ".level", "level"}, std::tuple{"/sprites", ".png", "sprite"}}) {
        if (p.extension() == extension && std::filesystem::equivalent(folder, assets_dir_ + sub, ec)) {
            return "would be a new " + std::string(kind) + " '" + p.stem().string() + "' of the assets";
        }
    }
    return "";
}

std::string ArenaGame::asset_folder(const std::string& dir) const {
    std::error_code ec;
    for (const char* sub : {"levels", "sprites"}) {
        if (std::filesystem::equivalent(dir, assets_dir_ + "/" + sub, ec)) return "is the " + std::string(sub) + " folder of the assets";
    }
    return "";
}

std::string ArenaGame::level_hash(const std::string& level) const {
    // The level and every sprite: masks change the game, pictures change the screenshots.
    Hasher h;
    h.str(read_file(level_path(level)));
    for (const std::string& name : sprite_names(assets_dir_)) {
        h.str(name);
        h.str(read_file(assets_dir_ + "/sprites/" + name + ".png", "the sprite"));
    }
    return hex16(h.value());
}

std::unique_ptr<Simulation> ArenaGame::start(const std::string& level, std::uint64_t seed, int tick_rate) const {
    const std::string path = level_path(level);
    Level parsed = parse_level(read_file(path), path, level);
    Sprites sprites;
    for (const std::string& name : sprite_names(assets_dir_)) {
        const std::string sprite_path = assets_dir_ + "/sprites/" + name + ".png";
        Image image = read_png(sprite_path);
        // A sprite goes into the renderer's atlas and may be a collision mask (props, blobs).
        static_assert(kMaxSpriteSide <= kMaxMaskSide);
        if (image.width > kMaxSpriteSide || image.height > kMaxSpriteSide) {
            throw InputError(SourceLocation{sprite_path, 0, 0},
                             "image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                                 " pixels; a sprite is at most " + std::to_string(kMaxSpriteSide) + " x " +
                                 std::to_string(kMaxSpriteSide));
        }
        sprites.images[name] = std::move(image);
    }
    return std::make_unique<ArenaSimulation>(parsed, path, std::move(sprites), rules_, seed, tick_rate);
}

}  // namespace jostle::game
