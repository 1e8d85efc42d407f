// level_test.cpp: the arena's level files (game/level.h): every line kind read into the right
// fields (and the shipped arena.level), and every kind of bad input refused with its exact
// file:line:column message.
#include "level.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "jostle/core/error.h"

namespace jostle::game {
namespace {

// Lines 1-3; the line under test is line 4.
const std::string kHead = "jostle-level 1\nsize 640 480\nplayer 100 240 0\n";

std::string error_of(const std::string& text) {
    try {
        parse_level(text, "l.level", "test");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

// The message for `line` as line 4 of an otherwise good level.
std::string error_of_line(const std::string& line) { return error_of(kHead + line + "\n"); }

TEST(Level, EveryLineKind) {
    const Level level = parse_level(
        "jostle-level 1\n"
        "# a comment line\n"
        "size 320 200.5   # trailing comment\n"
        "\n"
        "player 10 20 1.5\n"
        "wall w 0 0 320 8\n"
        "\tcrate c 50 60 40 30 0.4\n"
        "rock r circle 100 110 16\n"
        "rock p poly 150 120 -14 -10 12 -14 18 6 -4 16 -16 4\n"
        "pickup coin 180 120 8\n"
        "cannon k 300 100 3.6 120 600\n",
        "l.level", "mine");
    EXPECT_EQ(level.name, "mine");
    EXPECT_EQ(level.size.x, 320.0f);
    EXPECT_EQ(level.size.y, 200.5f);
    EXPECT_EQ(level.player_start.x, 10.0f);
    EXPECT_EQ(level.player_start.y, 20.0f);
    EXPECT_EQ(level.player_angle, 1.5f);
    ASSERT_EQ(level.things.size(), 6u);

    const LevelThing& wall = level.things[0];
    EXPECT_EQ(wall.kind, LevelThing::Kind::wall);
    EXPECT_EQ(wall.name, "w");
    EXPECT_EQ(wall.position.x, 0.0f);
    EXPECT_EQ(wall.position.y, 0.0f);
    EXPECT_EQ(wall.size.x, 320.0f);  // walls: the max corner
    EXPECT_EQ(wall.size.y, 8.0f);
    EXPECT_EQ(wall.line, 6);

    const LevelThing& crate = level.things[1];
    EXPECT_EQ(crate.kind, LevelThing::Kind::crate);
    EXPECT_EQ(crate.name, "c");
    EXPECT_EQ(crate.position.x, 50.0f);
    EXPECT_EQ(crate.position.y, 60.0f);
    EXPECT_EQ(crate.size.x, 40.0f);
    EXPECT_EQ(crate.size.y, 30.0f);
    EXPECT_EQ(crate.angle, 0.4f);
    EXPECT_EQ(crate.line, 7);

    const LevelThing& circle = level.things[2];
    EXPECT_EQ(circle.kind, LevelThing::Kind::rock_circle);
    EXPECT_EQ(circle.name, "r");
    EXPECT_EQ(circle.position.x, 100.0f);
    EXPECT_EQ(circle.position.y, 110.0f);
    EXPECT_EQ(circle.radius, 16.0f);

    const LevelThing& poly = level.things[3];
    EXPECT_EQ(poly.kind, LevelThing::Kind::rock_polygon);
    EXPECT_EQ(poly.name, "p");
    EXPECT_EQ(poly.position.x, 150.0f);
    EXPECT_EQ(poly.position.y, 120.0f);
    ASSERT_EQ(poly.polygon.count(), 5);
    bool found = false;  // the vertices are kept around the position (the winding may be reversed)
    for (int i = 0; i < poly.polygon.count(); ++i) found |= poly.polygon.points()[i].x == 18.0f && poly.polygon.points()[i].y == 6.0f;
    EXPECT_TRUE(found);

    const LevelThing& pickup = level.things[4];
    EXPECT_EQ(pickup.kind, LevelThing::Kind::pickup);
    EXPECT_EQ(pickup.name, "coin");
    EXPECT_EQ(pickup.position.x, 180.0f);
    EXPECT_EQ(pickup.radius, 8.0f);

    const LevelThing& cannon = level.things[5];
    EXPECT_EQ(cannon.kind, LevelThing::Kind::cannon);
    EXPECT_EQ(cannon.name, "k");
    EXPECT_EQ(cannon.position.x, 300.0f);
    EXPECT_EQ(cannon.position.y, 100.0f);
    EXPECT_EQ(cannon.angle, 3.6f);
    EXPECT_EQ(cannon.period, 120);
    EXPECT_EQ(cannon.speed, 600.0f);
    EXPECT_EQ(cannon.line, 11);
}

TEST(Level, PlayerAngleIsOptionalAndCrlfIsFine) {
    const Level level = parse_level("jostle-level 1\r\nsize 10 10\r\nplayer 1 2\r\npickup a 5 5 1\r\n", "l.level", "x");
    EXPECT_EQ(level.player_angle, 0.0f);
    EXPECT_EQ(level.player_start.y, 2.0f);
    ASSERT_EQ(level.things.size(), 1u);
    EXPECT_EQ(level.things[0].name, "a");
}

TEST(Level, TheShippedArena) {
    std::ifstream in(std::string(JOSTLE_ASSETS_DIR) + "/levels/arena.level", std::ios::binary);
    ASSERT_TRUE(in);
    std::ostringstream text;
    text << in.rdbuf();
    const Level level = parse_level(text.str(), "arena.level", "arena");
    EXPECT_EQ(level.size.x, 640.0f);
    EXPECT_EQ(level.size.y, 480.0f);
    EXPECT_EQ(level.player_start.x, 100.0f);
    EXPECT_EQ(level.player_start.y, 240.0f);
    int counts[6] = {};
    for (const LevelThing& t : level.things) ++counts[static_cast<int>(t.kind)];
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::wall)], 5);
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::crate)], 2);
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::rock_circle)], 2);
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::rock_polygon)], 1);
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::pickup)], 2);
    EXPECT_EQ(counts[static_cast<int>(LevelThing::Kind::cannon)], 1);
}

// ---------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------

TEST(Level, MassPropsAndBlobs) {
    const Level level = parse_level(kHead +
                                        "rock heavy circle 100 110 16 mass 4\n"
                                        "rock light poly 150 120 -14 -10 12 -14 18 6 mass 0.5\n"
                                        "rock plain circle 10 10 5\n"
                                        "prop t1 tree 320 200\n"
                                        "blob b1 100 400 300 410 40\n",
                                    "l.level", "mine");
    ASSERT_EQ(level.things.size(), 5u);
    EXPECT_EQ(level.things[0].mass, 4.0f);
    EXPECT_EQ(level.things[0].radius, 16.0f);
    EXPECT_EQ(level.things[1].mass, 0.5f);
    EXPECT_EQ(level.things[1].polygon.count(), 3);
    EXPECT_EQ(level.things[2].mass, 1.0f);
    EXPECT_EQ(level.things[3].kind, LevelThing::Kind::prop);
    EXPECT_EQ(level.things[3].sprite, "tree");
    EXPECT_EQ(level.things[3].position.x, 320.0f);
    EXPECT_EQ(level.things[3].position.y, 200.0f);
    const LevelThing& blob = level.things[4];
    EXPECT_EQ(blob.kind, LevelThing::Kind::blob);
    EXPECT_EQ(blob.position.x, 100.0f);
    EXPECT_EQ(blob.size.x, 300.0f);
    EXPECT_EQ(blob.size.y, 410.0f);
    EXPECT_EQ(blob.speed, 40.0f);
}

TEST(LevelErrors, MassPropsAndBlobs) {
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass 0"), "l.level:4:26: expected a positive mass, got '0'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass 2000"), "l.level:4:26: expected a mass of at most 1000, got '2000'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass heavy"), "l.level:4:26: expected a positive mass, got 'heavy'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass"), "l.level:4:25: expected a mass after 'mass'");
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0 0 1 mass"), "l.level:4:33: expected a mass after 'mass'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass 2 mass 3"),
              "l.level:4:28: 'mass' given twice (a rock's mass is given once, at the end)");
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0 0 1 mass 2 mass 3"),
              "l.level:4:36: 'mass' given twice (a rock's mass is given once, at the end)");
    EXPECT_EQ(parse_level(kHead + "rock mass circle 1 2 3 mass 4\n", "l.level", "l").things.at(0).mass, 4.0f);  // a name
    // A misspelt 'mass' is named as such, after a circle and after a polygon's vertices (where
    // it is not "expected a coordinate").
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mas 4"), "l.level:4:21: expected 'mass M' or a number, got 'mas'");
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0 0 1 weight 4"), "l.level:4:29: expected 'mass M' or a number, got 'weight'");
    // Only where a mass may stand: a word in the shape's own place is the shape's error.
    EXPECT_EQ(error_of_line("rock r circle 1 y 3"), "l.level:4:17: expected a coordinate from -1e5 to 1e5, got 'y'");
    EXPECT_EQ(error_of_line("rock r circle mass"), "l.level:4:19: expected 'rock NAME circle X Y RADIUS [mass M]'");
    EXPECT_EQ(error_of_line("rock r box 1 2 mas 4"), "l.level:4:8: expected 'circle' or 'poly', got 'box'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 mass 1e39"), "l.level:4:26: expected a mass of at most 1000, got '1e39'");
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0 0 1 mas"),
              "l.level:4:29: expected 'rock NAME poly X Y, then 3 to 16 vertices as DX DY pairs [mass M]'");
    EXPECT_EQ(error_of_line("prop t tree 1"), "l.level:4:14: expected 'prop NAME SPRITE X Y'");
    EXPECT_EQ(error_of_line("blob b 1 2 3 4 0"), "l.level:4:16: expected a positive speed, got '0'");
    EXPECT_EQ(error_of_line("blob b 1 2 3 4"), "l.level:4:15: expected 'blob NAME X0 Y0 X1 Y1 SPEED'");
}

TEST(LevelErrors, NotALevelFile) {
    EXPECT_EQ(error_of(""), "l.level:1: empty file: expected 'jostle-level 1'");
    EXPECT_EQ(error_of("jostle-level 2\nsize 1 1\nplayer 0 0\n"), "l.level:1:14: format version 2 is not supported (this jostle reads version 1)");
    EXPECT_EQ(error_of("jostle-scenario 1\n"), "l.level:1:1: expected 'jostle-level 1' as the first line");
    EXPECT_EQ(error_of(std::string("# comment\n").append(kHead)), "l.level:1:1: expected 'jostle-level 1' as the first line");
    EXPECT_EQ(error_of("jostle-level\n"), "l.level:1:1: expected 'jostle-level 1' as the first line");
}

TEST(Level, AByteOrderMarkAndCrlfLineEndsAreAccepted) {
    const std::string text = "jostle-level 1\r\nsize 320 200\r\nplayer 10 20 1.5\r\nwall w 0 0 320 8\r\n";
    for (const std::string& variant : {text, "\xef\xbb\xbf" + text}) {
        const Level level = parse_level(variant, "l.level", "mine");
        EXPECT_EQ(level.size.y, 200.0f);
        ASSERT_EQ(level.things.size(), 1u);
        EXPECT_EQ(level.things[0].size.y, 8.0f);
    }
    // Only a leading mark is one; a carriage return inside a line is refused.
    EXPECT_EQ(error_of("jostle-level 1\nsize 1 1\rplayer 0 0\n"),
              "l.level:2:9: expected text, got a carriage return (0x0d) inside the line (lines end with LF or CRLF)");
}

TEST(LevelErrors, TooManyThings) {
    std::string text = kHead;
    for (int i = 0; i < kMaxLevelThings; ++i) text += "pickup p" + std::to_string(i) + " 1 1 1\n";
    EXPECT_EQ(error_of(text), "no error");
    EXPECT_EQ(error_of(text + "  wall w 0 0 1 1\n"),
              "l.level:10004:3: too many things: a level holds at most 10000 walls, crates, rocks, pickups, cannons, props and blobs");
}

TEST(LevelErrors, UnknownLineKind) {
    EXPECT_EQ(error_of_line("tree t 1 2"), "l.level:4:1: unknown line 'tree' (expected size, player, wall, crate, rock, pickup, cannon, prop or blob)");
    EXPECT_EQ(error_of_line("  Wall w 0 0 1 1"),  // the column of the word, not of the line
              "l.level:4:3: unknown line 'Wall' (expected size, player, wall, crate, rock, pickup, cannon, prop or blob)");
}

TEST(LevelErrors, DuplicateAndReservedNames) {
    EXPECT_EQ(error_of(kHead + "wall a 0 0 10 10\npickup a 5 5 2\n"), "l.level:5:8: the name 'a' is already taken");
    EXPECT_EQ(error_of(kHead + "rock r circle 1 1 1\nrock r poly 0 0 0 0 1 0 0 1\n"), "l.level:5:6: the name 'r' is already taken");
    EXPECT_EQ(error_of_line("crate player 1 2 3 4 0"), "l.level:4:7: the name 'player' is reserved: the game names its ship player");
    EXPECT_EQ(error_of_line("cannon game 1 2 0 10 100"), "l.level:4:8: the name 'game' is reserved: a trace's dumps name the game's own state game");
    // The game's names for the bullets and balls it fires (bullet_N, ball_N): a thing named so
    // would be dumped beside the bullet of that name, and `expect bullet_1 gone` would find it.
    EXPECT_EQ(error_of_line("rock bullet_1 circle 200 240 10"),
              "l.level:4:6: the name 'bullet_1' is reserved: the game names its bullets bullet_N");
    EXPECT_EQ(error_of_line("cannon ball_12 1 2 0 10 100"),
              "l.level:4:8: the name 'ball_12' is reserved: the game names its cannon balls ball_N");
    EXPECT_EQ(error_of_line("wall  bullet_0 0 0 10 10"),  // never fired, but the game's all the same
              "l.level:4:7: the name 'bullet_0' is reserved: the game names its bullets bullet_N");
    EXPECT_EQ(error_of_line("pickup ball_007 5 5 2"), "l.level:4:8: the name 'ball_007' is reserved: the game names its cannon balls ball_N");
    // Only "bullet_" or "ball_" and digits: anything else is the level's to use.
    for (const char* name : {"bullet", "bullet_", "ball_", "bullet_x", "ball_1a", "bullets_1", "Bullet_1", "my_ball_1", "bullet_1_spare",
                             "ball_-1", "ball_+1", "ball"}) {
        EXPECT_EQ(error_of_line(std::string("pickup ") + name + " 5 5 2"), "no error") << name;
    }
}

TEST(LevelErrors, PolygonRocks) {
    // A dart: the vertex (0, 0) points inwards.
    EXPECT_EQ(error_of_line("rock r poly 100 100 -10 -10 10 -10 0 0 10 10 -10 10"),
              "l.level:4:21: polygon is not convex at vertex 2");
    EXPECT_EQ(error_of_line("rock r poly 100 100 0 0 1 1 2 2"),
              "l.level:4:21: polygon has zero area (all vertices on one line)");
    EXPECT_EQ(error_of_line("rock r poly 100 100 0 0 5 0 0 0"),
              "l.level:4:21: polygon vertices 0 and 2 are the same point");
    std::string seventeen = "rock r poly 0 0";
    for (int i = 0; i < 17; ++i) seventeen.append(" ").append(std::to_string(i)).append(" ").append(std::to_string(i * i));
    // Too many vertices is said at the first one too many, before any number is read.
    EXPECT_EQ(error_of_line(seventeen), "l.level:4:105: a polygon has at most 16 vertices, got 17");
    const std::string form = "expected 'rock NAME poly X Y, then 3 to 16 vertices as DX DY pairs [mass M]'";
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0"), "l.level:4:24: " + form);        // two vertices
    EXPECT_EQ(error_of_line("rock r poly 1 2 0 0 1 0 0 1 5"), "l.level:4:29: " + form);  // a lone coordinate
    EXPECT_EQ(error_of_line("rock r square 1 2 3"), "l.level:4:8: expected 'circle' or 'poly', got 'square'");
}

TEST(LevelErrors, WallCornersOutOfOrder) {
    EXPECT_EQ(error_of_line("wall w 10 0 10 8"), "l.level:4:8: expected X0 < X1 and Y0 < Y1");
    EXPECT_EQ(error_of_line("wall w 20 0 10 8"), "l.level:4:8: expected X0 < X1 and Y0 < Y1");
    EXPECT_EQ(error_of_line("wall w 0 8 10 8"), "l.level:4:8: expected X0 < X1 and Y0 < Y1");
}

TEST(LevelErrors, MissingSizeOrPlayerAndRepeats) {
    EXPECT_EQ(error_of("jostle-level 1\nplayer 1 2\n"), "l.level:2: the level has no 'size WIDTH HEIGHT' line");
    EXPECT_EQ(error_of("jostle-level 1\nsize 10 10\nwall w 0 0 1 1\n"), "l.level:3: the level has no 'player X Y' line");
    EXPECT_EQ(error_of("jostle-level 1\n"), "l.level:1: the level has no 'size WIDTH HEIGHT' line");
    EXPECT_EQ(error_of_line("size 10 10"), "l.level:4:1: 'size' given twice");
    EXPECT_EQ(error_of_line("player 1 1"), "l.level:4:1: 'player' given twice");
    EXPECT_EQ(error_of_line("\tsize 10 10"), "l.level:4:2: 'size' given twice");
}

TEST(LevelErrors, PlayerStartOutsideTheLevel) {
    const auto x = [](int line, int column, const std::string& width, const std::string& got) {
        return "l.level:" + std::to_string(line) + ":" + std::to_string(column) + ": expected the player's X inside the level, from 0 to " +
               width + " (its width), got '" + got + "'";
    };
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480\nplayer 1000 1000 0\n"), x(3, 8, "640", "1000"));
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480\nplayer 640.5 10\n"), x(3, 8, "640", "640.5"));
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480\nplayer -1 10\n"), x(3, 8, "640", "-1"));
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480\nplayer 100  -0.5\n"),
              "l.level:3:13: expected the player's Y inside the level, from 0 to 480 (its height), got '-0.5'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480.5\nplayer 10 481\n"),
              "l.level:3:11: expected the player's Y inside the level, from 0 to 480.5 (its height), got '481'");
    // The player line before the size line: said at the player line, once the size is known.
    EXPECT_EQ(error_of("jostle-level 1\nplayer 700 10\n# the arena\nsize 640 480\nwall w 0 0 1 1\n"), x(2, 8, "640", "700"));
    // The edges are inside.
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480\nplayer 0 0\n"), "no error");
    EXPECT_EQ(error_of("jostle-level 1\nplayer 640 480\nsize 640 480\n"), "no error");
}

TEST(LevelErrors, WrongWordCounts) {
    EXPECT_EQ(error_of("jostle-level 1\nsize 640\n"), "l.level:2:9: expected 'size WIDTH HEIGHT'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 480 1\n"), "l.level:2:14: expected 'size WIDTH HEIGHT'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 1 1\nplayer 1 2 3 4\n"), "l.level:3:14: expected 'player X Y [ANGLE]'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 1 1\nplayer 1\n"), "l.level:3:9: expected 'player X Y [ANGLE]'");
    EXPECT_EQ(error_of_line("wall w 0 0 10"), "l.level:4:14: expected 'wall NAME X0 Y0 X1 Y1'");
    EXPECT_EQ(error_of_line("wall"), "l.level:4:5: expected 'wall NAME X0 Y0 X1 Y1'");
    EXPECT_EQ(error_of_line("crate c 1 2 3 4"), "l.level:4:16: expected 'crate NAME X Y WIDTH HEIGHT ANGLE'");
    EXPECT_EQ(error_of_line("rock r"), "l.level:4:7: expected 'rock NAME circle|poly ...'");
    EXPECT_EQ(error_of_line("rock r circle 1 2"), "l.level:4:18: expected 'rock NAME circle X Y RADIUS [mass M]'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 3 4"), "l.level:4:21: expected 'rock NAME circle X Y RADIUS [mass M]'");
    EXPECT_EQ(error_of_line("pickup p 1 2"), "l.level:4:13: expected 'pickup NAME X Y RADIUS'");
    EXPECT_EQ(error_of_line("cannon k 1 2 3 4"), "l.level:4:17: expected 'cannon NAME X Y ANGLE PERIOD_TICKS BALL_SPEED'");
}

TEST(LevelErrors, NumbersTooBigNotFiniteOrNotPositive) {
    // Coordinates and lengths: within kMaxCoordinate (1e5); other numbers (angles, speeds): 1e6.
    const auto number = [](int column, const std::string& got) {
        return "l.level:4:" + std::to_string(column) + ": expected a coordinate from -1e5 to 1e5, got '" + got + "'";
    };
    EXPECT_EQ(error_of_line("wall w 0 0 1000001 8"), number(12, "1000001"));
    EXPECT_EQ(error_of_line("wall w 0 0 1e7 8"), number(12, "1e7"));
    EXPECT_EQ(error_of_line("wall w -1e7 0 1 8"), number(8, "-1e7"));
    EXPECT_EQ(error_of_line("wall w 0 0 1e39 8"), number(12, "1e39"));
    EXPECT_EQ(error_of_line("pickup p nan 1 2"), number(10, "nan"));
    EXPECT_EQ(error_of_line("pickup p 1 inf 2"), number(12, "inf"));
    // A length is said as one: a positive radius, of at most 1e5.
    EXPECT_EQ(error_of_line("pickup p 1 2 x"), "l.level:4:14: expected a positive radius, got 'x'");
    EXPECT_EQ(error_of_line("pickup p 1 2 2e5"), "l.level:4:14: expected a radius of at most 1e5, got '2e5'");
    EXPECT_EQ(error_of_line("crate c 1 2 inf 4 0"), "l.level:4:13: expected a width of at most 1e5, got 'inf'");
    EXPECT_EQ(error_of_line("pickup p 1 2 1e39"), "l.level:4:14: expected a radius of at most 1e5, got '1e39'");
    EXPECT_EQ(error_of_line("pickup p 1 2 -1e39"), "l.level:4:14: expected a positive radius, got '-1e39'");
    EXPECT_EQ(error_of_line("wall w 0 0 100001 8"), number(12, "100001"));
    EXPECT_EQ(error_of_line("rock r poly 0 0 0 0 1e5 0 0 100000.01"), number(29, "100000.01"));
    EXPECT_EQ(error_of_line("crate c 1 2 3 4 0.5rad"), "l.level:4:17: expected a number from -1e6 to 1e6, got '0.5rad'");
    EXPECT_EQ(error_of_line("cannon k 1 2 2e6 10 600"), "l.level:4:14: expected a number from -1e6 to 1e6, got '2e6'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 1e5 1e5\nplayer 1e5 0 -1e6\nwall w -1e5 -1e5 1e5 1e5\n"), "no error");  // the limits themselves are fine
    EXPECT_EQ(error_of("jostle-level 1\nsize 0 480\nplayer 0 0\n"), "l.level:2:6: expected a positive width, got '0'");
    EXPECT_EQ(error_of("jostle-level 1\nsize 640 -1\nplayer 0 0\n"), "l.level:2:10: expected a positive height, got '-1'");
    EXPECT_EQ(error_of_line("pickup p 1 2 0"), "l.level:4:14: expected a positive radius, got '0'");
    EXPECT_EQ(error_of_line("rock r circle 1 2 -3"), "l.level:4:19: expected a positive radius, got '-3'");
    EXPECT_EQ(error_of_line("crate c 1 2 0 4 0"), "l.level:4:13: expected a positive width, got '0'");
    EXPECT_EQ(error_of_line("cannon k 1 2 0 0 600"), "l.level:4:16: expected a period in ticks (1 .. 100000), got '0'");
    EXPECT_EQ(error_of_line("cannon k 1 2 0 1.5 600"), "l.level:4:16: expected a period in ticks (1 .. 100000), got '1.5'");
    EXPECT_EQ(error_of_line("cannon k 1 2 0 100001 600"), "l.level:4:16: expected a period in ticks (1 .. 100000), got '100001'");
    EXPECT_EQ(error_of_line("cannon k 1 2 0 10 0"), "l.level:4:19: expected a positive ball speed, got '0'");
}

TEST(Level, NumbersFinerThanAFloatRoundToTheNearestFloat) {
    // 1e-320 is within -1e5 .. 1e5; a float has nothing that small, so it rounds to 0 (or to a
    // denormal, as strtof gives), like any other number rounds to its nearest float.
    const Level level = parse_level(kHead + "wall w 1e-320 -1e-320 1e-40 8\ncrate c 1 2 3 4 -1e-330\n", "l.level", "test");
    ASSERT_EQ(level.things.size(), 2u);
    EXPECT_EQ(level.things[0].position.x, 0.0f);
    EXPECT_EQ(level.things[0].position.y, 0.0f);
    EXPECT_TRUE(std::signbit(level.things[0].position.y));
    EXPECT_EQ(level.things[0].size.x, static_cast<float>(1e-40));  // a denormal
    EXPECT_EQ(level.things[1].angle, 0.0f);
    // Too large is still refused; a length that must be positive says why 1e-320 is not.
    EXPECT_EQ(error_of_line("wall w 0 0 1e39 8"), "l.level:4:12: expected a coordinate from -1e5 to 1e5, got '1e39'");
    EXPECT_EQ(error_of_line("pickup p 1 2 1e-320"),
              "l.level:4:14: expected a positive radius, got '1e-320' (too small for a float: it rounds to 0)");
    EXPECT_EQ(error_of_line("pickup p 1 2 0.0e5"), "l.level:4:14: expected a positive radius, got '0.0e5'");
    EXPECT_EQ(error_of_line("pickup p 1 2 1e-40"), "no error");
}

}  // namespace
}  // namespace jostle::game
