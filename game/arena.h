// game/arena.h: the demo game, a top-down arena. The player's ship turns (left, right),
// drives (up, down) and fires bullets (fire); crates and rocks get pushed around; pickups
// (triggers) score; cannons fire fast balls. Every rule lives here, not in the engine; the
// replay module reaches it through the Game and Simulation interfaces.
//
// Bullets ricochet off walls (twice); anything else ends them. Blob creatures patrol.
// Kinds: player, wall, crate, rock, pickup, cannon, bullet, ball, prop, blob.
// Variables: score (10 per pickup, 1 per bullet hit on a rock), shots, balls, fastest (the
// speed of the fastest crate or rock, px/s: a settled crowd has it near 0), touches (contacts
// the ship has begun with anything solid: a near miss leaves it at 0).
// Events: fire, bullet_hit, rock_hit, pickup, cannon_fire, player_hit (a ball hit the ship),
// ricochet, blob_touch (the ship touched a blob).
// Pictures come from assets/sprites (tools/make-sprites); props and blobs collide by them.
#pragma once

#include <memory>
#include <string>

#include "jostle/replay/simulation.h"

namespace jostle::game {

// The game's tuning, in one place (tests tweak it to prove that `check` notices).
struct Rules {
    float turn_speed = 3.0f;        // rad/s
    float drive_speed = 150.0f;     // px/s forward
    float reverse_speed = 75.0f;    // px/s backward
    float coast = 0.85f;            // velocity kept per tick with neither up nor down held
    float bullet_speed = 900.0f;    // px/s
    int fire_cooldown = 8;          // ticks between shots
    int bullet_lifetime = 90;       // ticks
    int bullet_bounces = 2;         // ricochets off walls before a bullet ends
    float ball_radius = 5.0f;
    int ball_lifetime = 240;        // ticks
    int pickup_score = 10;
    int rock_hit_score = 1;
};

// Entities alive in one arena at once (the level's things, the ship, bullets, cannon balls).
// A run that would go beyond it (cannons firing faster than their balls expire) stops with an
// InputError naming the level and the tick.
inline constexpr int kMaxEntities = 20000;

// The arena game, reading levels from `assets_dir`/levels/NAME.level (InputError when that
// folder cannot be listed: a wrong --assets).
class ArenaGame : public Game {
public:
    explicit ArenaGame(std::string assets_dir, Rules rules = {});
    const ScenarioVocabulary& vocabulary() const override { return vocabulary_; }
    std::string level_hash(const std::string& level) const override;
    std::unique_ptr<Simulation> start(const std::string& level, std::uint64_t seed, int tick_rate) const override;

    const std::string& assets_dir() const { return assets_dir_; }
    std::string level_path(const std::string& level) const;
    // What `path` is among the files the game reads: "is the level 'arena' of the assets", "is
    // the sprite 'ship' of the assets" (same_file: by any path or link), "would be a new level
    // 'x' of the assets" (NAME.level in the levels folder; NAME.png in the sprites folder), or ""
    // when none. Commands refuse an output that names one, before they run.
    std::string asset_named(const std::string& path) const;
    // What folder `dir` is among those the game reads: "is the sprites folder of the assets"
    // (by any path or link), the same for levels, or "". An output folder there (frames, a
    // report's images) would add sprites or mix files into the levels: commands refuse it.
    std::string asset_folder(const std::string& dir) const;

private:
    std::string assets_dir_;
    Rules rules_;
    ScenarioVocabulary vocabulary_;
};

// The action bits, in the order of vocabulary().actions.
enum Action : int { kLeft = 0, kRight, kUp, kDown, kFire, kActionCount };

// Where the assets are: $JOSTLE_ASSETS when set, else the source tree's assets/ (compiled in).
std::string default_assets_dir();

}  // namespace jostle::game
