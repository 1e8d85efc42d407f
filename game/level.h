// game/level.h: the arena game's level files (assets/levels/NAME.level), line-oriented text:
//
//   jostle-level 1                          the format version: always the first line
//   size 640 480                            the arena in world pixels (y down)
//   player 100 240 0                        x y angle (radians): where the ship starts
//   wall top 0 0 640 8                      NAME x0 y0 x1 y1: a static AABB
//   crate c1 300 200 40 30 0.4              NAME x y width height angle: a pushable OBB
//   rock r1 circle 400 300 18               NAME circle x y radius: a pushable circle
//   rock r2 poly 450 120 -15 -10 15 -12 20 8 -5 16   NAME poly x y, then the vertices
//                                           around (x, y): a pushable convex polygon
//   pickup p1 500 400 10                    NAME x y radius: a trigger worth 10 points
//   cannon k1 620 240 3.1416 90 600         NAME x y angle period_ticks ball_speed
//
// '#' starts a comment; blank lines are ignored. Names are unique. Errors name the file, the
// line and what was expected.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "jostle/collision.h"

namespace jostle::game {

inline constexpr int kLevelFormatVersion = 1;

struct LevelThing {
    enum class Kind { wall, crate, rock_circle, rock_polygon, pickup, cannon };
    Kind kind = Kind::wall;
    std::string name;
    Vec2 position;          // walls: min corner
    Vec2 size;              // walls: max corner; crates: width, height
    float angle = 0.0f;     // crates, cannons
    float radius = 0.0f;    // circle rocks, pickups
    Polygon polygon;        // polygon rocks, around position
    int period = 0;         // cannons: ticks between balls
    float speed = 0.0f;     // cannons: ball speed, px/s
    int line = 0;
};

struct Level {
    std::string name;
    Vec2 size;
    Vec2 player_start;
    float player_angle = 0.0f;
    std::vector<LevelThing> things;  // in file order
};

// Parses level text; `source` names it in errors (InputError with file:line:column).
Level parse_level(std::string_view text, const std::string& source, const std::string& name);

}  // namespace jostle::game
