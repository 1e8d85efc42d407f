// jostle/replay/simulation.h: what replay needs from a game. The game (game/) implements
// these two interfaces; engine/replay plays, records and checks scenarios through them and
// never knows the game's rules.
//
//   Game        the game's vocabulary (actions, levels) and a factory for runs
//   Simulation  one run of one level: tick(input) advances one fixed step; the rest reads
//
// Doom's rule: the tick reads its input from one place, the InputFrame passed to tick(), so a
// recorded log, live input and a bot are the same to the game.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jostle/render/renderer.h"
#include "jostle/replay/scenario.h"
#include "jostle/world.h"

namespace jostle {

// One field of an entity's readable state: "x" = "104.25".
struct StateField {
    std::string name;
    std::string value;
};

// One entity's readable state, for traces and divergence reports.
struct EntityDump {
    std::string name;  // unique within the run, stable across runs ("player", "rock_3", "bullet_17"); never contains '#' or spaces
    std::vector<StateField> fields;
};

struct DrawOptions {
    bool overlay = false;  // the debug overlay over the game's own drawing
    bool hud = true;       // score, tick
};

class Simulation {
public:
    virtual ~Simulation() = default;

    // One fixed step: the game's rules read `input`, then the world steps.
    virtual void tick(InputFrame input) = 0;
    // Ticks done so far.
    virtual std::int64_t ticks_done() const = 0;
    // A hash of everything that affects the future: the world's state hash and the game's
    // own variables.
    virtual std::uint64_t state_hash() const = 0;
    virtual const World& world() const = 0;

    // For expectations. An entity's position (nullopt when no live entity has that name);
    // the number of live entities of a kind; a game variable (nullopt when the game has no
    // such variable); whether the game reported the named event so far.
    virtual std::optional<Vec2> entity_position(std::string_view name) const = 0;
    // Whether an entity of that name has lived at some time in the run so far (false for a
    // name no entity has had: a misspelt expectation), and whether one ever can in this run
    // (false for a name the game never gives: refused before the first tick).
    virtual bool entity_named(std::string_view name) const = 0;
    virtual bool entity_name_possible(std::string_view name) const = 0;
    virtual std::int64_t count(std::string_view kind) const = 0;
    virtual std::optional<double> variable(std::string_view name) const = 0;
    virtual bool event_happened(std::string_view name) const = 0;
    // The names the game knows, for "did you mean" in errors: entity kinds, variables, events.
    virtual std::vector<std::string> kinds() const = 0;
    virtual std::vector<std::string> variables() const = 0;
    virtual std::vector<std::string> events() const = 0;

    // Every live entity's state (and the game's variables as an entity named "game"), in a
    // stable order.
    virtual std::vector<EntityDump> dump() const = 0;

    // The size of the level in world pixels (the default frame size).
    virtual Vec2 level_size() const = 0;
    // Draws the current state into a frame begun on `renderer` (begin_frame is the caller's).
    // The game adds its sprites to a renderer the first time it sees it. Drawing never
    // changes the run: a run with rendering and one without give the same state hashes.
    virtual void draw(Renderer& renderer, const DrawOptions& options) const = 0;
};

class Game {
public:
    virtual ~Game() = default;
    virtual const ScenarioVocabulary& vocabulary() const = 0;
    // A fingerprint of the level's file and every asset it uses (16 hex digits).
    virtual std::string level_hash(const std::string& level) const = 0;
    // Starts a run. Throws InputError when the level's files are bad.
    virtual std::unique_ptr<Simulation> start(const std::string& level, std::uint64_t seed, int tick_rate) const = 0;
};

}  // namespace jostle
