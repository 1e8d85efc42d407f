// level.cpp: parsing the arena's level files (format in level.h).
#include "level.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string_view>
#include <tuple>
#include <utility>

#include "jostle/core/error.h"
#include "jostle/core/text.h"

namespace jostle::game {
namespace {

class LineReader {
public:
    LineReader(const std::string& source, int line, const std::vector<Word>& words)
        : source_(source), line_(line), words_(words) {}

    [[noreturn]] void fail(int column, const std::string& what) const {
        throw InputError(SourceLocation{source_, line_, column}, what);
    }
    void expect_words(std::size_t min, std::size_t max, const char* form) const {
        if (words_.size() < min || words_.size() > max) {
            const Word& at = words_.size() > max ? words_[max] : words_.back();
            fail(words_.size() > max ? at.column : at.column + static_cast<int>(at.text.size()),
                 std::string("expected '") + form + "'");
        }
    }
    // A coordinate or a length: |v| <= kMaxCoordinate (the collision module's precision limit).
    float coordinate(std::size_t i) const { return number(i, kMaxCoordinate, "a coordinate from -1e5 to 1e5"); }
    // Anything else (an angle): |v| <= 1e6.
    float number(std::size_t i, float limit = 1e6f, const char* what = "a number from -1e6 to 1e6") const {
        const Word& w = words_[i];
        // A number finer than a float (1e-320) is rounded to one (0 or a denormal), like any other.
        const std::optional<float> value = parse_float(w.text);
        if (!value || !std::isfinite(*value) || std::fabs(*value) > limit) {
            fail(w.column, std::string("expected ") + what + ", got '" + std::string(w.text) + "'");
        }
        return *value;
    }
    // A positive length or speed (a radius, a width, px/s): 0 < v <= limit (kMaxCoordinate: a
    // length is a coordinate), said as one ("expected a positive width", not "a coordinate").
    float positive(std::size_t i, const char* what, float limit = kMaxCoordinate, const char* limit_text = "1e5") const {
        // Read as a double too, so that 1e39 (beyond a float) is too large, not "not positive".
        const std::optional<float> parsed = parse_float(words_[i].text);
        const std::optional<double> wide = parsed ? std::optional<double>(*parsed) : parse_double(words_[i].text);
        const float v = parsed ? *parsed : std::numeric_limits<float>::quiet_NaN();
        if (wide && *wide > limit) {
            fail(words_[i].column, std::string("expected a ") + what + " of at most " + limit_text + ", got '" +
                                       std::string(words_[i].text) + "'");
        }
        if (!(v > 0.0f)) {
            const std::string_view text = words_[i].text;
            // 1e-320 is positive, but a float has nothing that small: say why it is refused.
            const std::string_view digits = text.substr(0, text.find_first_of("eE"));
            const bool rounded_to_zero = v == 0.0f && digits.find_first_of("123456789") != std::string_view::npos;
            fail(words_[i].column, std::string("expected a positive ") + what + ", got '" + std::string(text) + "'" +
                                       (rounded_to_zero ? " (too small for a float: it rounds to 0)" : ""));
        }
        return v;
    }
    int whole(std::size_t i, int min, int max, const char* what) const {
        const Word& w = words_[i];
        int value = 0;
        const auto [end, ec] = std::from_chars(w.text.data(), w.text.data() + w.text.size(), value);
        if (ec != std::errc() || end != w.text.data() + w.text.size() || value < min || value > max) {
            fail(w.column, std::string("expected ") + what + " (" + std::to_string(min) + " .. " + std::to_string(max) +
                               "), got '" + std::string(w.text) + "'");
        }
        return value;
    }
    const Word& word(std::size_t i) const { return words_[i]; }
    std::size_t size() const { return words_.size(); }

private:
    const std::string& source_;
    int line_;
    const std::vector<Word>& words_;
};

// The game's own names for what it spawns, bullet_N and ball_N (arena.cpp): "bullet_" or
// "ball_" and digits. A thing named so would share its name with a bullet or a ball in the
// dumps and in expectations; so would player (the ship) and game (the dumps' game state).
// Returns why the name is reserved, or nullptr.
const char* reserved_for(std::string_view name) {
    if (name == "player") return "the game names its ship player";
    if (name == "game") return "a trace's dumps name the game's own state game";
    for (const auto& [prefix, what] : {std::pair<std::string_view, const char*>{"bullet_", "the game names its bullets bullet_N"},
                                       std::pair<std::string_view, const char*>{"ball_", "the game names its cannon balls ball_N"}}) {
        if (name.size() > prefix.size() && name.starts_with(prefix) &&
            name.find_first_not_of("0123456789", prefix.size()) == std::string_view::npos) {
            return what;
        }
    }
    return nullptr;
}

}  // namespace

Level parse_level(std::string_view text, const std::string& source, const std::string& name) {
    Level level;
    level.name = name;
    bool have_size = false, have_player = false;
    // The player's X and Y as written, with their line and columns: a start outside the level
    // is refused as soon as both the size and the player are known, at the coordinate that is
    // outside.
    struct Written {
        std::string text;
        int line = 0, column = 0;
    };
    Written player_x, player_y;
    const auto check_player_start = [&]() {
        if (!have_size || !have_player) return;
        for (const auto& [value, limit, written, axis, side] :
             {std::tuple{level.player_start.x, level.size.x, &player_x, "X", "width"},
              std::tuple{level.player_start.y, level.size.y, &player_y, "Y", "height"}}) {
            if (!(value >= 0.0f && value <= limit)) {
                throw InputError(SourceLocation{source, written->line, written->column},
                                 std::string("expected the player's ") + axis + " inside the level, from 0 to " +
                                     shortest_text(limit) + " (its " + side + "), got '" + written->text + "'");
            }
        }
    };
    std::set<std::string, std::less<>> names;
    int line_number = 0;
    std::size_t at = 0;
    text = skip_utf8_bom(text);
    if (text.empty()) throw InputError(SourceLocation{source, 1, 0}, "empty file: expected 'jostle-level 1'");
    while (at < text.size()) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        ++line_number;
        check_text_line(line, source, line_number);
        std::vector<Word> words = split_words(line);
        if (line_number == 1) {
            if (words.size() == 2 && words[0].text == "jostle-level" && words[1].text != "1") {
                throw InputError(SourceLocation{source, 1, words[1].column},
                                 "format version " + std::string(words[1].text) + " is not supported (this jostle reads version 1)");
            }
            if (words.size() != 2 || words[0].text != "jostle-level" || words[1].text != "1") {
                throw InputError(SourceLocation{source, 1, 1}, "expected 'jostle-level 1' as the first line");
            }
            continue;
        }
        if (words.empty()) continue;
        const LineReader r(source, line_number, words);
        const std::string_view head = words[0].text;
        if (head == "size") {
            r.expect_words(3, 3, "size WIDTH HEIGHT");
            if (have_size) r.fail(words[0].column, "'size' given twice");
            level.size = {r.positive(1, "width"), r.positive(2, "height")};
            have_size = true;
            check_player_start();
            continue;
        }
        if (head == "player") {
            r.expect_words(3, 4, "player X Y [ANGLE]");
            if (have_player) r.fail(words[0].column, "'player' given twice");
            level.player_start = {r.coordinate(1), r.coordinate(2)};
            if (words.size() == 4) level.player_angle = r.number(3);
            have_player = true;
            player_x = {std::string(words[1].text), line_number, words[1].column};
            player_y = {std::string(words[2].text), line_number, words[2].column};
            check_player_start();
            continue;
        }
        if (level.things.size() >= static_cast<std::size_t>(kMaxLevelThings)) {
            r.fail(words[0].column, "too many things: a level holds at most " + std::to_string(kMaxLevelThings) +
                                        " walls, crates, rocks, pickups, cannons, props and blobs");
        }
        LevelThing thing;
        thing.line = line_number;
        auto take_name = [&]() {
            if (r.size() < 2) r.expect_words(2, 2, "KIND NAME ...");
            thing.name = std::string(r.word(1).text);
            if (const char* what = reserved_for(thing.name)) {
                r.fail(r.word(1).column, "the name '" + thing.name + "' is reserved: " + what);
            }
            if (!names.insert(thing.name).second) r.fail(r.word(1).column, "the name '" + thing.name + "' is already taken");
        };
        if (head == "wall") {
            r.expect_words(6, 6, "wall NAME X0 Y0 X1 Y1");
            take_name();
            thing.kind = LevelThing::Kind::wall;
            thing.position = {r.coordinate(2), r.coordinate(3)};
            thing.size = {r.coordinate(4), r.coordinate(5)};
            if (thing.size.x <= thing.position.x || thing.size.y <= thing.position.y) {
                r.fail(r.word(2).column, "expected X0 < X1 and Y0 < Y1");
            }
        } else if (head == "crate") {
            r.expect_words(7, 7, "crate NAME X Y WIDTH HEIGHT ANGLE");
            take_name();
            thing.kind = LevelThing::Kind::crate;
            thing.position = {r.coordinate(2), r.coordinate(3)};
            thing.size = {r.positive(4, "width"), r.positive(5, "height")};
            thing.angle = r.number(6);
        } else if (head == "rock") {
            if (r.size() < 3) r.expect_words(3, 3, "rock NAME circle|poly ...");
            take_name();
            const std::string_view shape = r.word(2).text;
            if (shape != "circle" && shape != "poly") {
                r.fail(r.word(2).column, "expected 'circle' or 'poly', got '" + std::string(shape) + "'");
            }
            // A count of words the shape takes (without a mass): circle X Y RADIUS, poly X Y and pairs.
            const auto shape_words = [&](std::size_t n) { return shape == "circle" ? n == 6 : n >= 11 && (n - 5) % 2 == 0; };
            const Word& second_last = r.word(r.size() - 2);
            if (r.size() >= 5 && second_last.text == "mass") {
                thing.mass = r.positive(r.size() - 1, "mass", 1000.0f, "1000");
                const int mass_column = second_last.column;
                words.resize(words.size() - 2);  // the shape's words are checked as if it were not there
                // (After 'rock NAME SHAPE': a rock may be named mass.)
                if (std::any_of(words.begin() + 3, words.end(), [](const Word& w) { return w.text == "mass"; })) {
                    r.fail(mass_column, "'mass' given twice (a rock's mass is given once, at the end)");
                }
            } else if (shape_words(r.size() - 2) && std::isalpha(static_cast<unsigned char>(second_last.text[0])) != 0 &&
                       !parse_float(second_last.text) && parse_float(r.word(r.size() - 1).text)) {
                // "mas 3", "weight 3" where a mass may stand: a misspelt mass, not a coordinate.
                r.fail(second_last.column, "expected 'mass M' or a number, got '" + std::string(second_last.text) + "'");
            } else if (const Word& last = r.word(r.size() - 1); shape_words(r.size() - 1) && last.text == "mass") {
                r.fail(last.column + static_cast<int>(last.text.size()), "expected a mass after 'mass'");
            }
            if (r.word(2).text == "circle") {
                r.expect_words(6, 6, "rock NAME circle X Y RADIUS [mass M]");
                thing.kind = LevelThing::Kind::rock_circle;
                thing.position = {r.coordinate(3), r.coordinate(4)};
                thing.radius = r.positive(5, "radius");
            } else if (r.word(2).text == "poly") {
                if (r.size() < 11 || (r.size() - 5) % 2 != 0) {
                    r.expect_words(11, 11, "rock NAME poly X Y, then 3 to 16 vertices as DX DY pairs [mass M]");
                }
                const std::size_t max_words = 5 + 2 * static_cast<std::size_t>(kMaxPolygonVertices);
                if (r.size() > max_words) {
                    r.fail(r.word(max_words).column, "a polygon has at most " + std::to_string(kMaxPolygonVertices) +
                                                         " vertices, got " + std::to_string((r.size() - 5) / 2));
                }
                thing.kind = LevelThing::Kind::rock_polygon;
                thing.position = {r.coordinate(3), r.coordinate(4)};
                std::vector<Vec2> points;
                for (std::size_t i = 5; i + 1 < r.size(); i += 2) points.push_back({r.coordinate(i), r.coordinate(i + 1)});
                std::string error;
                const std::optional<Polygon> polygon = make_polygon(points, &error);
                if (!polygon) r.fail(r.word(5).column, error);  // "polygon is not convex at vertex 2", ...
                thing.polygon = *polygon;
            }
        } else if (head == "pickup") {
            r.expect_words(5, 5, "pickup NAME X Y RADIUS");
            take_name();
            thing.kind = LevelThing::Kind::pickup;
            thing.position = {r.coordinate(2), r.coordinate(3)};
            thing.radius = r.positive(4, "radius");
        } else if (head == "cannon") {
            r.expect_words(7, 7, "cannon NAME X Y ANGLE PERIOD_TICKS BALL_SPEED");
            take_name();
            thing.kind = LevelThing::Kind::cannon;
            thing.position = {r.coordinate(2), r.coordinate(3)};
            thing.angle = r.number(4);
            thing.period = r.whole(5, 1, 100000, "a period in ticks");
            thing.speed = r.positive(6, "ball speed");
        } else if (head == "prop") {
            r.expect_words(5, 5, "prop NAME SPRITE X Y");
            take_name();
            thing.kind = LevelThing::Kind::prop;
            thing.sprite = std::string(r.word(2).text);
            thing.sprite_column = r.word(2).column;
            thing.position = {r.coordinate(3), r.coordinate(4)};
        } else if (head == "blob") {
            r.expect_words(7, 7, "blob NAME X0 Y0 X1 Y1 SPEED");
            take_name();
            thing.kind = LevelThing::Kind::blob;
            thing.sprite_column = r.word(0).column;  // the sprite is blob's own: the line names it
            thing.position = {r.coordinate(2), r.coordinate(3)};
            thing.size = {r.coordinate(4), r.coordinate(5)};
            thing.speed = r.positive(6, "speed");
        } else {
            r.fail(words[0].column, "unknown line '" + std::string(head) +
                          "' (expected size, player, wall, crate, rock, pickup, cannon, prop or blob)");
        }
        level.things.push_back(std::move(thing));
    }
    if (!have_size) throw InputError(SourceLocation{source, line_number, 0}, "the level has no 'size WIDTH HEIGHT' line");
    if (!have_player) throw InputError(SourceLocation{source, line_number, 0}, "the level has no 'player X Y' line");
    return level;
}

}  // namespace jostle::game
