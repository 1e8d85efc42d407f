// tests/fuzz/level_fuzz.cpp: fuzzes the arena game's level parser (game/level.cpp), the function
// the game calls on assets/levels/NAME.level. Bad input must be an InputError naming the file; a
// level that parses must hold what level.h promises: finite numbers within the parser's 1e6
// limit, unique names, walls with min < max, valid polygons.
#include <cmath>
#include <cstring>
#include <set>
#include <string>

#include "fuzz_support.h"
#include "jostle/core/error.h"
#include "level.h"

namespace {

using jostle::fuzz::fuzz_fail;

bool sane(float v) { return std::isfinite(v) && std::fabs(v) <= 1e6f; }
bool sane(jostle::Vec2 v) { return sane(v.x) && sane(v.y); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    jostle::game::Level level;
    try {
        level = jostle::game::parse_level(text, "fuzz.level", "fuzz");
    } catch (const jostle::InputError& e) {
        if (std::strncmp(e.what(), "fuzz.level", 10) != 0) fuzz_fail(std::string("error without its source: ") + e.what());
        return 0;
    }
    if (!sane(level.size) || !(level.size.x > 0 && level.size.y > 0) || !sane(level.player_start) ||
        !sane(level.player_angle)) {
        fuzz_fail("the level's size or player start is not a sane number:\n" + text);
    }
    std::set<std::string> names;
    for (const jostle::game::LevelThing& t : level.things) {
        if (!names.insert(t.name).second) fuzz_fail("name '" + t.name + "' used twice:\n" + text);
        if (!sane(t.position) || !sane(t.size) || !sane(t.angle) || !sane(t.radius) || !sane(t.speed) ||
            !std::isfinite(t.mass) || !(t.mass > 0.0f)) {
            fuzz_fail("thing '" + t.name + "' has a number out of range:\n" + text);
        }
        if (t.kind == jostle::game::LevelThing::Kind::wall && !(t.position.x < t.size.x && t.position.y < t.size.y)) {
            fuzz_fail("wall '" + t.name + "' has min >= max:\n" + text);
        }
        if (t.kind == jostle::game::LevelThing::Kind::rock_polygon && t.polygon.count() < 3) {
            fuzz_fail("polygon rock '" + t.name + "' has no polygon:\n" + text);
        }
    }
    return 0;
}
