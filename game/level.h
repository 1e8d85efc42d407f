// game/level.h: the arena game's level files (assets/levels/NAME.level), line-oriented text:
//
//   jostle-level 1                          the format version: always the first line
//   size 640 480                            the arena in world pixels (y down)
//   player 100 240 0                        x y angle (radians): where the ship starts,
//                                           inside the size (0 <= x <= width, 0 <= y <= height)
//   wall top 0 0 640 8                      NAME x0 y0 x1 y1: a static AABB
//   crate c1 300 200 40 30 0.4              NAME x y width height angle: a pushable OBB
//   rock r1 circle 400 300 18               NAME circle x y radius: a pushable circle
//   rock r2 poly 450 120 -15 -10 15 -12 20 8 -5 16   NAME poly x y, then the vertices
//                                           around (x, y): a pushable convex polygon
//   rock r3 circle 400 300 18 mass 4        either rock, heavier (mass 1 by default)
//   pickup p1 500 400 10                    NAME x y radius: a trigger worth 10 points
//   cannon k1 620 240 3.1416 90 600         NAME x y angle period_ticks ball_speed
//   prop t1 tree 320 200                    NAME SPRITE x y: a fixed thing that collides by
//                                           the pixels of assets/sprites/SPRITE.png
//                                           (alpha >= 128), centred on (x, y)
//   blob b1 100 400 300 400 40              NAME x0 y0 x1 y1 speed: the blob creature
//                                           (pixel-perfect) patrolling between two points
//
// '#' starts a comment; blank lines are ignored. Names are unique, and neither 'player', 'game'
// nor the game's names for what it fires (bullet_N, ball_N: 'bullet_' or 'ball_' and digits).
// Errors name the file, the line and what was expected. A UTF-8 byte order mark and CRLF line
// ends are accepted.
// Limits: every coordinate, length and speed within +-1e5 (kMaxCoordinate), angles within
// +-1e6, mass <= 1000; at most kMaxLevelThings things; polygons of 3 to 16 vertices; lines
// and words as in jostle/core/text.h (kMaxLineBytes, kMaxWordBytes). A number finer than a
// float (1e-320) rounds to the nearest float (0), as strtof rounds it; a length that must be
// positive is then refused, saying so.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "jostle/collision.h"

namespace jostle::game {

inline constexpr int kLevelFormatVersion = 1;
// Things (walls, crates, rocks, pickups, cannons, props, blobs) in one level.
inline constexpr int kMaxLevelThings = 10000;

struct LevelThing {
    enum class Kind { wall, crate, rock_circle, rock_polygon, pickup, cannon, prop, blob };
    Kind kind = Kind::wall;
    std::string name;
    Vec2 position;          // walls: min corner; blobs: the first end of the patrol
    Vec2 size;              // walls: max corner; crates: width, height; blobs: the other end
    float angle = 0.0f;     // crates, cannons
    float radius = 0.0f;    // circle rocks, pickups
    Polygon polygon;        // polygon rocks, around position
    int period = 0;         // cannons: ticks between balls
    float speed = 0.0f;     // cannons: ball speed; blobs: walking speed (px/s)
    float mass = 1.0f;      // rocks
    std::string sprite;     // props: the picture (and so the mask)
    int line = 0;
    int sprite_column = 1;  // where the sprite was named (the arena checks it exists); a blob's: its first word
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
