// query_test.cpp: `jostle query` in process (run_query_line and run_query: every op, every
// shape type, the number format, each error message) and end to end (the built jostle binary
// with stdin from tests/data, checking every output line and the exit status).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ios>
#include <streambuf>
#include <system_error>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "game/run_jostle.h"
#include "query.h"

namespace jostle {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using Json = nlohmann::json;

const std::string kData = JOSTLE_TEST_DATA;

// The answer to a line that must succeed.
std::string answer(const std::string& line) {
    bool ok = false;
    std::string out = run_query_line(line, 1, &ok);
    EXPECT_TRUE(ok) << line << "\n -> " << out;
    return out;
}

// The answer to a line that must succeed, parsed.
Json answer_json(const std::string& line) { return Json::parse(answer(line)); }

// The message of a line that must fail; checks the answer is exactly {"error": "..."}.
std::string error_of(const std::string& line, std::int64_t line_number = 1) {
    bool ok = true;
    const std::string out = run_query_line(line, line_number, &ok);
    EXPECT_FALSE(ok) << line << "\n -> " << out;
    const Json j = Json::parse(out);  // always valid JSON
    EXPECT_TRUE(j.is_object() && j.size() == 1 && j.contains("error") && j["error"].is_string()) << out;
    return j.value("error", std::string());
}

std::string collide(const std::string& a, const std::string& b) {
    return R"({"op":"collide","a":)" + a + R"(,"b":)" + b + "}";
}
std::string closest(const std::string& point, const std::string& shape) {
    return R"({"op":"closest","point":)" + point + R"(,"shape":)" + shape + "}";
}
std::string circle_at(const std::string& center, const std::string& radius) {
    return R"({"type":"circle","center":)" + center + R"(,"radius":)" + radius + "}";
}

const std::string kBox02 = R"({"type":"aabb","min":[0,0],"max":[2,2]})";
const std::string kUnitCircle = R"({"type":"circle","center":[0,0],"radius":1})";

// ---------------------------------------------------------------------------------------
// Output format
// ---------------------------------------------------------------------------------------

std::string number(float v) {
    std::string out;
    append_json_number(out, v);
    return out;
}

TEST(QueryOutput, FloatsPrintShortestRoundTrip) {
    EXPECT_EQ(number(0.5f), "0.5");
    EXPECT_EQ(number(2.0f), "2");
    EXPECT_EQ(number(-1.5f), "-1.5");
    EXPECT_EQ(number(0.1f), "0.1");
    EXPECT_EQ(number(1.0f / 3.0f), "0.33333334");
    EXPECT_EQ(number(1e-5f), "1e-05");
    EXPECT_EQ(number(123456789.0f), "123456792");
    EXPECT_EQ(number(std::numeric_limits<float>::max()), "3.4028235e+38");
    EXPECT_EQ(number(std::numeric_limits<float>::denorm_min()), "1e-45");
}

TEST(QueryOutput, NegativeZeroPrintsAsZeroAndNonFiniteAsNull) {
    EXPECT_EQ(number(-0.0f), "0");
    EXPECT_EQ(number(0.0f), "0");
    EXPECT_EQ(number(std::numeric_limits<float>::quiet_NaN()), "null");
    EXPECT_EQ(number(std::numeric_limits<float>::infinity()), "null");
    EXPECT_EQ(number(-std::numeric_limits<float>::infinity()), "null");
}

TEST(QueryOutput, EveryShortestFormReadsBackAsTheSameFloat) {
    std::uint32_t state = 12345;
    for (int i = 0; i < 10000; ++i) {
        state = state * 1664525u + 1013904223u;
        float v = 0.0f;
        std::memcpy(&v, &state, sizeof v);
        if (!std::isfinite(v)) continue;
        const std::string text = number(v);
        EXPECT_EQ(std::strtof(text.c_str(), nullptr), v == 0.0f ? 0.0f : v) << text;
    }
}

std::string quoted(std::string_view s) {
    std::string out;
    append_json_string(out, s);
    return out;
}

TEST(QueryOutput, StringsAreEscapedAndAlwaysValidUtf8) {
    EXPECT_EQ(quoted("plain"), R"("plain")");
    EXPECT_EQ(quoted("a\"b\\c"), R"("a\"b\\c")");
    EXPECT_EQ(quoted("\n\t\r\b\f"), R"("\n\t\r\b\f")");
    EXPECT_EQ(quoted(std::string_view("\x01\x1f\x7f\0", 4)), R"("\u0001\u001f\u007f\u0000")");
    EXPECT_EQ(quoted("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "\"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\"");
    EXPECT_EQ(quoted("\xff"), R"("\ufffd")");
    EXPECT_EQ(quoted("a\xe2\x82"), R"("a\ufffd\ufffd")");          // cut-off sequence
    EXPECT_EQ(quoted("\xc0\xaf"), R"("\ufffd\ufffd")");            // overlong '/'
    EXPECT_EQ(quoted("\xed\xa0\x80"), R"("\ufffd\ufffd\ufffd")");  // a surrogate
    EXPECT_EQ(quoted("\xf4\x90\x80\x80"), R"("\ufffd\ufffd\ufffd\ufffd")");  // above U+10FFFF
}

// ---------------------------------------------------------------------------------------
// collide, for each shape type
// ---------------------------------------------------------------------------------------

TEST(QueryCollide, AabbsOverlappingByOne) {
    EXPECT_EQ(answer(collide(kBox02, R"({"type":"aabb","min":[1,0],"max":[3,2]})")),
              R"({"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0]})");
}

TEST(QueryCollide, AabbsApartMiss) {
    EXPECT_EQ(answer(collide(kBox02, R"({"type":"aabb","min":[5,0],"max":[6,2]})")),
              R"({"hit":false,"depth":0,"normal":[0,0],"mtd":[0,0]})");
}

TEST(QueryCollide, TouchingAabbsHitWithDepthZero) {
    // mtd = -0 * normal prints as 0, not -0.
    EXPECT_EQ(answer(collide(kBox02, R"({"type":"aabb","min":[2,0],"max":[4,2]})")),
              R"({"hit":true,"depth":0,"normal":[1,0],"mtd":[0,0]})");
}

TEST(QueryCollide, Circles) {
    EXPECT_EQ(answer(collide(kUnitCircle, circle_at("[1.5,0]", "1"))),
              R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
    EXPECT_EQ(answer(collide(kUnitCircle, circle_at("[0,3]", "1"))),
              R"({"hit":false,"depth":0,"normal":[0,0],"mtd":[0,0]})");
}

TEST(QueryCollide, ObbAtAngleZeroAgainstAabb) {
    EXPECT_EQ(answer(collide(R"({"type":"obb","center":[0,0],"half":[1,1],"angle":0})",
                             R"({"type":"aabb","min":[0.5,-1],"max":[3,1]})")),
              R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
}

TEST(QueryCollide, ObbAngleDefaultsToZero) {
    EXPECT_EQ(answer(collide(R"({"type":"obb","center":[0,0],"half":[1,1]})",
                             R"({"type":"aabb","min":[0.5,-1],"max":[3,1]})")),
              R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
}

TEST(QueryCollide, RotatedObbAgainstCircle) {
    // A 2x2 square turned 45 degrees reaches x = sqrt(2); the circle starts at x = 1.
    const Json j = answer_json(collide(R"({"type":"obb","center":[0,0],"half":[1,1],"angle":0.7853981634})",
                                       circle_at("[2,0]", "1")));
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["depth"].get<double>(), std::sqrt(2.0) - 1.0, 1e-5);
    EXPECT_NEAR(j["normal"][0].get<double>(), 1.0, 1e-5);
    EXPECT_NEAR(j["normal"][1].get<double>(), 0.0, 1e-5);
}

TEST(QueryCollide, PolygonAgainstCircle) {
    EXPECT_EQ(answer(collide(R"({"type":"polygon","points":[[0,0],[2,0],[2,2],[0,2]]})",
                             circle_at("[3,1]", "1.5"))),
              R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
}

TEST(QueryCollide, PolygonInEitherWindingAgainstPolygon) {
    // Counter-clockwise on screen (negative cross) is accepted too.
    EXPECT_EQ(answer(collide(R"({"type":"polygon","points":[[0,0],[0,2],[2,2],[2,0]]})",
                             R"({"type":"polygon","points":[[1.5,0],[4,0],[4,2],[1.5,2]]})")),
              R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
}

TEST(QueryCollide, SegmentAgainstCircle) {
    EXPECT_EQ(answer(collide(R"({"type":"segment","a":[0,0],"b":[4,0]})", circle_at("[2,1]", "2"))),
              R"({"hit":true,"depth":1,"normal":[0,1],"mtd":[0,-1]})");
}

TEST(QueryCollide, MasksAddPixelsAndFirst) {
    // A: 3 pixels in a row at y = 0; B: a column at x = 2, y = -1..1. They share pixel (2, 0).
    // Moving A left by 1 frees it; up or down takes 2, right takes 3.
    EXPECT_EQ(answer(collide(R"({"type":"mask","at":[0,0],"rows":["###"]})",
                             R"({"type":"mask","at":[2,-1],"rows":["#","#","#"]})")),
              R"({"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0],"pixels":1,"first":[2,0]})");
}

TEST(QueryCollide, MasksApartHaveNoFirstPixel) {
    EXPECT_EQ(answer(collide(R"({"type":"mask","at":[0,0],"rows":["##"]})",
                             R"({"type":"mask","at":[0,1],"rows":["##"]})")),
              R"({"hit":false,"depth":0,"normal":[0,0],"mtd":[0,0],"pixels":0,"first":null})");
}

TEST(QueryCollide, MaskFromPngUsesTheAlphaThreshold) {
    // mask_4x4.png: alpha 255 at (1,1)-(2,2), alpha 100 at (3,0). Placed at (10,10).
    const std::string png = R"({"type":"mask","at":[10,10],"png":")" + kData + R"(/mask_4x4.png"})";
    const std::string png50 =
        R"({"type":"mask","at":[10,10],"png":")" + kData + R"(/mask_4x4.png","threshold":50})";
    const std::string column = R"({"type":"mask","at":[12,11],"rows":["#","#","#"]})";
    EXPECT_EQ(answer(collide(png, column)),
              R"({"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0],"pixels":2,"first":[12,11]})");

    const std::string corner = R"({"type":"mask","at":[13,10],"rows":["#"]})";
    EXPECT_EQ(answer(collide(png, corner)),
              R"({"hit":false,"depth":0,"normal":[0,0],"mtd":[0,0],"pixels":0,"first":null})");
    const Json j = answer_json(collide(png50, corner));
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_EQ(j["pixels"], 1);
    EXPECT_EQ(j["first"], Json::parse("[13,10]"));
    EXPECT_EQ(j["depth"], 1);
}

TEST(QueryCollide, MaskAgainstAnotherShapeHasNoPixelCount) {
    // The pixel (1,0) has its centre (1.5, 0.5) on the box's corner: closed shapes meet.
    const Json j = answer_json(collide(R"({"type":"mask","at":[0,0],"rows":["##","##"]})",
                                       R"({"type":"aabb","min":[1.5,0.5],"max":[5,5]})"));
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_FALSE(j.contains("pixels"));
    EXPECT_FALSE(j.contains("first"));
    EXPECT_EQ(answer_json(collide(R"({"type":"mask","at":[0,0],"rows":["##","##"]})",
                                  R"({"type":"aabb","min":[1.6,0.5],"max":[5,5]})"))["hit"],
              false);
}

TEST(QueryCollide, KeysComeInTheDocumentedOrder) {
    const std::string out = answer(collide(kUnitCircle, kUnitCircle));
    EXPECT_THAT(out, StartsWith(R"({"hit":true,"depth":)"));
    EXPECT_LT(out.find("\"depth\""), out.find("\"normal\""));
    EXPECT_LT(out.find("\"normal\""), out.find("\"mtd\""));
}

// ---------------------------------------------------------------------------------------
// cast, sweep, closest, lines
// ---------------------------------------------------------------------------------------

TEST(QueryCast, SegmentAgainstAabb) {
    EXPECT_EQ(answer(R"({"op":"cast","from":[-2,1],"to":[2,1],"shape":)" + kBox02 + "}"),
              R"({"hit":true,"t":0.5,"point":[0,1],"normal":[-1,0]})");
}

TEST(QueryCast, SegmentAgainstCircle) {
    EXPECT_EQ(answer(R"({"op":"cast","from":[-3,0],"to":[1,0],"shape":)" + kUnitCircle + "}"),
              R"({"hit":true,"t":0.5,"point":[-1,0],"normal":[-1,0]})");
}

TEST(QueryCast, StartingInsideReportsTZeroAndNoNormal) {
    EXPECT_EQ(answer(R"({"op":"cast","from":[1,1],"to":[5,1],"shape":)" + kBox02 + "}"),
              R"({"hit":true,"t":0,"point":[1,1],"normal":[0,0]})");
}

TEST(QueryCast, Miss) {
    const Json j = answer_json(R"({"op":"cast","from":[-3,5],"to":[1,5],"shape":)" + kUnitCircle + "}");
    EXPECT_FALSE(j["hit"].get<bool>());
    EXPECT_EQ(j.size(), 4u);
}

TEST(QueryCast, AgainstSegmentObbPolygonAndMask) {
    Json j = answer_json(R"({"op":"cast","from":[0,-1],"to":[0,1],"shape":{"type":"segment","a":[-1,0],"b":[1,0]}})");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_EQ(j["t"], 0.5);
    EXPECT_EQ(j["point"], Json::parse("[0,0]"));

    j = answer_json(
        R"({"op":"cast","from":[-4,0],"to":[4,0],"shape":{"type":"obb","center":[0,0],"half":[1,1],"angle":0}})");
    EXPECT_EQ(j["t"], 0.375);
    EXPECT_EQ(j["point"], Json::parse("[-1,0]"));
    EXPECT_EQ(j["normal"], Json::parse("[-1,0]"));

    j = answer_json(
        R"({"op":"cast","from":[1,-4],"to":[1,4],"shape":{"type":"polygon","points":[[0,0],[2,0],[2,2],[0,2]]}})");
    EXPECT_EQ(j["t"], 0.5);
    EXPECT_EQ(j["point"], Json::parse("[1,0]"));
    EXPECT_EQ(j["normal"], Json::parse("[0,-1]"));

    // The set pixel (1, 0) of the mask at (5, 5) is the square [6,7] x [5,6].
    j = answer_json(R"({"op":"cast","from":[0,5.5],"to":[10,5.5],"shape":{"type":"mask","at":[5,5],"rows":[".#"]}})");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 0.6, 1e-6);
    EXPECT_EQ(j["point"][0], 6);
    EXPECT_EQ(j["normal"], Json::parse("[-1,0]"));
}

TEST(QuerySweep, CircleAgainstStillCircle) {
    // Centres 5 apart, radii 1 + 1: contact after moving 3 of 4.
    EXPECT_EQ(answer(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[4,0],"b":)" + circle_at("[5,0]", "1") +
                     R"(,"vb":[0,0]})"),
              R"({"hit":true,"t":0.75,"point":[4,0],"normal":[1,0]})");
}

TEST(QuerySweep, BothMoving) {
    // Relative speed 4; at t = 0.75 the circles are at 1.5 and 3.5, touching at 2.5.
    EXPECT_EQ(answer(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[2,0],"b":)" + circle_at("[5,0]", "1") +
                     R"(,"vb":[-2,0]})"),
              R"({"hit":true,"t":0.75,"point":[2.5,0],"normal":[1,0]})");
}

TEST(QuerySweep, CircleAgainstAabbAndMiss) {
    Json j = answer_json(R"({"op":"sweep","a":)" + kUnitCircle +
                         R"(,"va":[10,0],"b":{"type":"aabb","min":[5,-1],"max":[7,1]},"vb":[0,0]})");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 0.4, 1e-6);
    EXPECT_NEAR(j["point"][0].get<double>(), 5.0, 1e-5);
    EXPECT_NEAR(j["point"][1].get<double>(), 0.0, 1e-5);
    EXPECT_EQ(j["normal"], Json::parse("[1,0]"));

    j = answer_json(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[10,0],"b":)" + circle_at("[5,5]", "1") +
                    R"(,"vb":[0,0]})");
    EXPECT_FALSE(j["hit"].get<bool>());
}

TEST(QuerySweep, ANotACircleIsAnError) {
    EXPECT_EQ(error_of(R"({"op":"sweep","a":)" + kBox02 + R"(,"va":[1,0],"b":)" + kUnitCircle + R"(,"vb":[0,0]})"),
              R"(line 1: "a" must be a circle for sweep (the moving circle), got aabb)");
}

TEST(QueryClosest, EachShapeType) {
    EXPECT_EQ(answer(closest("[5,1]", kBox02)), R"({"point":[2,1],"distance":3})");
    EXPECT_EQ(answer(closest("[1,1]", kBox02)), R"({"point":[1,1],"distance":0})");
    EXPECT_EQ(answer(closest("[3,0]", R"({"type":"obb","center":[0,0],"half":[1,2],"angle":0})")),
              R"({"point":[1,0],"distance":2})");
    EXPECT_EQ(answer(closest("[3,1]", R"({"type":"polygon","points":[[0,0],[2,0],[2,2],[0,2]]})")),
              R"({"point":[2,1],"distance":1})");
    EXPECT_EQ(answer(closest("[2,3]", R"({"type":"segment","a":[0,0],"b":[4,0]})")),
              R"({"point":[2,0],"distance":3})");
    EXPECT_EQ(answer(closest("[5,3.5]", R"({"type":"mask","at":[2,3],"rows":["#"]})")),
              R"({"point":[3,3.5],"distance":2})");
    const Json j = answer_json(closest("[3,4]", kUnitCircle));
    EXPECT_NEAR(j["point"][0].get<double>(), 0.6, 1e-6);
    EXPECT_NEAR(j["point"][1].get<double>(), 0.8, 1e-6);
    EXPECT_NEAR(j["distance"].get<double>(), 4.0, 1e-5);
}

TEST(QueryClosest, EmptyMaskHasNoClosestPoint) {
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":["..."]})")),
              R"(line 1: "shape" is a mask with no set pixels: it has no closest point)");
}

TEST(QueryLines, PointParallelCoincident) {
    EXPECT_EQ(answer(R"({"op":"lines","a":[[0,0],[2,2]],"b":[[0,2],[2,0]]})"), R"({"kind":"point","point":[1,1]})");
    EXPECT_EQ(answer(R"({"op":"lines","a":[[0,0],[1,0]],"b":[[0,1],[1,1]]})"), R"({"kind":"parallel","point":null})");
    EXPECT_EQ(answer(R"({"op":"lines","a":[[0,0],[1,0]],"b":[[2,0],[3,0]]})"), R"({"kind":"coincident","point":null})");
    // Points 1e-23 apart still make lines that cross (y = x and y = 1).
    EXPECT_EQ(answer(R"({"op":"lines","a":[[0,0],[1e-23,1e-23]],"b":[[0,1],[1e-23,1]]})"), R"({"kind":"point","point":[1,1]})");
}

TEST(QueryErrors, AMaskOfNoPixelsIsAnError) {
    const std::string circle = R"("b":{"type":"circle","center":[0,0],"radius":1}})";
    EXPECT_EQ(error_of(R"({"op":"collide","a":{"type":"mask","at":[0,0],"rows":[]},)" + circle),
              R"(line 1: "rows" must be a non-empty array of strings of '#' (set) and '.' (clear))");
    EXPECT_EQ(error_of(R"({"op":"collide","a":{"type":"mask","at":[0,0],"rows":[""]},)" + circle),
              R"(line 1: "rows"[0] is empty: a mask row has at least one pixel)");
    EXPECT_EQ(error_of(R"({"op":"collide","a":{"type":"mask","at":[0,0],"rows":["#",""]},)" + circle),
              R"(line 1: "rows"[1] is empty: a mask row has at least one pixel)");
}

TEST(QueryLines, TwoEqualPointsAreNoLine) {
    // (The collision module calls a line with A = B = 0 parallel to everything; a query with
    // such a line is a mistake, so it is an error.)
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[1,1],[1,1]],"b":[[0,1],[1,2]]})"),
              R"(line 1: "a" gives the same point twice: a line needs two different points)");
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[0,1],[1,2]],"b":[[-0.0,5],[0,5]]})"),
              R"(line 1: "b" gives the same point twice: a line needs two different points)");
}

// ---------------------------------------------------------------------------------------
// Errors: each message, exactly
// ---------------------------------------------------------------------------------------

TEST(QueryErrors, NotJson) {
    const std::string message = error_of("{x", 2);
    EXPECT_THAT(message, StartsWith("line 2: not valid JSON: "));
    EXPECT_THAT(message, HasSubstr("column 2"));
    EXPECT_THAT(error_of("[1,2", 7), StartsWith("line 7: not valid JSON: "));
    EXPECT_THAT(error_of(R"({"op":"lines",})"), StartsWith("line 1: not valid JSON: "));
}

TEST(QueryErrors, ANulByteIsSaidWithItsColumn) {
    using namespace std::string_literals;
    const auto nul_at = [](int column) {
        return "line 1: not valid JSON: a NUL byte (0x00) at column " + std::to_string(column) + " (is this a binary file?)";
    };
    // Where a value or a key should be (the parser took it for the end of the input).
    EXPECT_EQ(error_of("{\"op\":\"lines\",\0}"s), nul_at(15));
    EXPECT_EQ(error_of("\0"s), nul_at(1));
    // After a whole query: not answered as if the line ended there.
    const std::string lines = R"({"op":"lines","a":[[0,0],[1,1]],"b":[[0,1],[1,0]]})";
    EXPECT_EQ(answer(lines), R"({"kind":"point","point":[0.5,0.5]})");
    EXPECT_EQ(error_of(lines + "\0"s), nul_at(static_cast<int>(lines.size()) + 1));
    EXPECT_EQ(error_of(lines + " \0{\"op\":1}"s), nul_at(static_cast<int>(lines.size()) + 2));
    // Inside a string.
    EXPECT_EQ(error_of("{\"op\":\"li\0nes\"}"s), nul_at(10));
    // An error before the NUL is that error.
    const std::string before = error_of("{x\0"s);
    EXPECT_THAT(before, StartsWith("line 1: not valid JSON: parse error at column 2: syntax error"));
}

TEST(QueryErrors, AKeyGivenTwiceInAnObjectIsRefused) {
    // The message names the second key's column (1-based, in bytes like the parser's own).
    const auto message = [](const std::string& key, std::size_t column) {
        return "duplicate key \"" + key + "\" at column " + std::to_string(column) + " (a key may appear only once in an object)";
    };
    const std::string cast_too = R"({"op":"collide","a":{"type":"aabb","min":[0,0],"max":[2,2]},"b":{"type":"aabb","min":[1,0],"max":[3,2]},"op":"cast"})";
    EXPECT_EQ(error_of(cast_too), "line 1: " + message("op", cast_too.rfind("\"op\"") + 1));
    const std::string radius = R"({"op":"closest","point":[0,0],"shape":{"type":"circle","center":[0,0],"radius":1,"radius":-2}})";
    EXPECT_EQ(error_of(radius, 4), "line 4: " + message("radius", radius.rfind("\"radius\"") + 1));
    EXPECT_EQ(error_of(R"({"op":"lines","op":"lines","a":[[0,0],[1,1]],"b":[[0,1],[1,0]]})"), "line 1: " + message("op", 15));
    // Strings that look like keys (a value with a colon and escaped quotes in it, spaces before
    // the colon) are not counted; an escaped spelling of a key is that key.
    const std::string tricky = R"({"op":"lines", "a" :[[0,0],[1,1]],"b":[[0,1],[1,0]],"x":{"s":"\":\" :"}, "o\u0070" : 1})";
    EXPECT_EQ(error_of(tricky), "line 1: " + message("op", tricky.find("\"o\\u0070\"") + 1));
    // The parser stops at the repeated key, before its ':' (which may be missing); keys in arrays
    // of objects and values in arrays are counted right.
    EXPECT_EQ(error_of(R"({"op":"lines","op"})"), "line 1: " + message("op", 15));
    EXPECT_EQ(error_of(R"({"op":"lines","op" "x":1})"), "line 1: " + message("op", 15));
    const std::string nested = R"({"a":[{"x":1},"y",{"y":2,"y":3}]})";
    EXPECT_EQ(error_of(nested), "line 1: " + message("y", nested.rfind("\"y\"") + 1));
    // The same key in different objects, or as a value, is no duplicate.
    EXPECT_EQ(answer(collide(circle_at("[0,0]", "1"), circle_at("[1.5,0]", "1"))), R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})");
    EXPECT_THAT(error_of(R"({"op":"lines","a":[[0,0],[1,1]],"b":[[0,1],[1,0]],"x":{"op":1,"y":{"op":"op"}}})"),
                StartsWith("line 1: unknown key \"x\""));
}

TEST(QueryErrors, NotJsonWithBadUtf8StillAnswersValidJson) {
    // The parser quotes the bad bytes; the answer replaces them and stays valid JSON.
    EXPECT_THAT(error_of("{\"op\":\"\xff\"}"), StartsWith("line 1: not valid JSON: "));
}

TEST(QueryErrors, NumbersJsonCannotHoldOrFloatCannotHold) {
    EXPECT_EQ(error_of(closest("[1e400,0]", kUnitCircle)), "line 1: not valid JSON: number overflow parsing '1e400'");
    // Beyond a float is beyond the collision module's range too: the message gives the range.
    EXPECT_EQ(error_of(closest("[1e39,0]", kUnitCircle)),
              R"(line 1: "point"[0] is 1e+39: expected a coordinate from -1e5 to 1e5 (the collision module's documented range))");
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,-1e39]", "1"))),
              R"(line 1: "center"[1] is -1e+39: expected a coordinate from -1e5 to 1e5 (the collision module's documented range))");
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", "1e39"))),
              R"(line 1: "radius" is 1e+39: expected a radius from 0 to 1e5 (the collision module's documented range))");
    // An angle is not in pixels: any float, but not beyond one.
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"obb","center":[0,0],"half":[1,1],"angle":1e39})")),
              R"(line 1: "angle" is 1e+39, too large for a float (at most about 3.4e+38))");
    // JSON has no NaN or Infinity literals.
    EXPECT_THAT(error_of(closest("[NaN,0]", kUnitCircle)), StartsWith("line 1: not valid JSON: "));
    EXPECT_THAT(error_of(closest("[Infinity,0]", kUnitCircle)), StartsWith("line 1: not valid JSON: "));
    // Finer than a float: rounds to one, like any number.
    EXPECT_EQ(answer(closest("[3,-1e-320]", circle_at("[1e-50,0]", "1"))), R"({"point":[1,0],"distance":2})");
}

TEST(QueryErrors, PixelsPastTheCollisionModulesRangeAreRefused) {
    // collision.h, LIMITS: exact within |x|, |y| <= 1e5 (kMaxCoordinate). Far past it squares
    // overflow and hits became misses: this cast through a unit circle answered "hit":false, and
    // the same sweep with va [1e20,0] passed the box. Now both are refused, saying the range.
    const std::string range = " (the collision module's documented range)";
    EXPECT_EQ(error_of(R"({"op":"cast","from":[-1e19,0],"to":[1e19,0],"shape":)" + kUnitCircle + "}"),
              R"(line 1: "from"[0] is -1e+19: expected a coordinate from -1e5 to 1e5)" + range);
    const std::string box10 = R"({"type":"aabb","min":[11,-5],"max":[12,5]})";
    EXPECT_EQ(error_of(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[1e20,0],"b":)" + box10 + R"(,"vb":[0,0]})"),
              R"(line 1: "va"[0] is 1e+20: expected a motion from -1e5 to 1e5 on each axis)" + range);
    EXPECT_EQ(error_of(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[0,0],"b":)" + box10 + R"(,"vb":[0,-100000.5]})"),
              R"(line 1: "vb"[1] is -100000.5: expected a motion from -1e5 to 1e5 on each axis)" + range);
    // Every coordinate, extent and radius of every shape and op.
    const auto coordinate = [&](const std::string& name, const std::string& value) {
        return "line 1: " + name + " is " + value + ": expected a coordinate from -1e5 to 1e5" + range;
    };
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"aabb","min":[-200000,0],"max":[1,1]})")), coordinate(R"("min"[0])", "-200000"));
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"aabb","min":[0,0],"max":[1,1e6]})")), coordinate(R"("max"[1])", "1000000"));
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"obb","center":[0,100001],"half":[1,1]})")),
              coordinate(R"("center"[1])", "100001"));
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"obb","center":[0,0],"half":[1,3e5]})")),
              R"(line 1: "half"[1] is 300000: expected a half extent from 0 to 1e5)" + range);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[1,0],[0,1e18]]})")),
              coordinate(R"("points"[2][1])", "1e+18"));
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"segment","a":[0,0],"b":[-1e10,0]})")), coordinate(R"("b"[0])", "-10000000000"));
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", "100000.5"))),
              R"(line 1: "radius" is 100000.5: expected a radius from 0 to 1e5)" + range);
    EXPECT_EQ(error_of(closest("[1e18,0]", kBox02)), coordinate(R"("point"[0])", "1e+18"));
    EXPECT_EQ(error_of(R"({"op":"cast","from":[0,0],"to":[0,3.4028234e38],"shape":)" + kUnitCircle + "}"),
              coordinate(R"("to"[1])", "3.4028234e+38"));
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[0,0],[1,1]],"b":[[0,1],[2e5,2]]})"), coordinate(R"("b"[1][0])", "200000"));
    // A negative radius or half extent within the range keeps its own message.
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", "-1"))), R"(line 1: "radius" must be a finite number >= 0)");
}

TEST(QueryErrors, AtTheRangesEndsAnswersAreRight) {
    // The reviewer's cast, at the range's ends: through the unit circle, t = (1e5 - 1) / 2e5.
    Json j = answer_json(R"({"op":"cast","from":[-1e5,0],"to":[1e5,0],"shape":)" + kUnitCircle + "}");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 0.499995, 1e-7);
    EXPECT_EQ(j["normal"], Json::parse("[-1,0]"));
    // Corner to corner: the circle is met 1 px before the middle of a 2e5 * sqrt 2 path.
    j = answer_json(R"({"op":"cast","from":[-1e5,-1e5],"to":[1e5,1e5],"shape":)" + kUnitCircle + "}");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 0.5 - 1.0 / (2e5 * std::sqrt(2.0)), 1e-7);
    // The sweep: the ball's right side meets the box 10 px away after 10 px of its 1e5.
    j = answer_json(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[1e5,0],"b":{"type":"aabb","min":[11,-5],"max":[12,5]},"vb":[0,0]})");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 1e-4, 1e-9);
    EXPECT_EQ(j["normal"], Json::parse("[1,0]"));
    // Both moving at the most, toward each other: closing 2e5 px, 10 px to go.
    j = answer_json(R"({"op":"sweep","a":)" + kUnitCircle + R"(,"va":[1e5,0],"b":)" + circle_at("[12,0]", "1") +
                    R"(,"vb":[-1e5,0]})");
    EXPECT_TRUE(j["hit"].get<bool>());
    EXPECT_NEAR(j["t"].get<double>(), 5e-5, 1e-9);
    // A shape at the far corner, as large as allowed.
    EXPECT_EQ(answer(collide(circle_at("[-1e5,-1e5]", "1e5"), circle_at("[1e5,-1e5]", "1e5"))),
              R"({"hit":true,"depth":0,"normal":[1,0],"mtd":[0,0]})");
    EXPECT_EQ(answer(closest("[1e5,1e5]", R"({"type":"obb","center":[-1e5,1e5],"half":[1e5,1],"angle":0})")),
              R"({"point":[0,1e+05],"distance":1e+05})");  // results print shortest
}

TEST(QueryErrors, Radius) {
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", "-1")), 3), R"(line 3: "radius" must be a finite number >= 0)");
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", R"("1")"))), R"(line 1: "radius" must be a finite number >= 0)");
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[0,0]", "null"))), R"(line 1: "radius" must be a finite number >= 0)");
    EXPECT_EQ(answer(closest("[3,0]", circle_at("[0,0]", "0"))), R"({"point":[0,0],"distance":3})");
}

TEST(QueryErrors, UnknownShapeTypeAndOp) {
    EXPECT_EQ(error_of(collide(R"({"type":"cirlce","center":[0,0],"radius":1})", kUnitCircle), 4),
              R"(line 4: unknown shape type "cirlce" (expected aabb, obb, polygon, circle, segment or mask))");
    EXPECT_EQ(error_of(R"({"op":"colide","a":1})", 5),
              R"(line 5: unknown op "colide" (expected collide, cast, sweep, closest or lines))");
    // A long name is cut; quotes in it are escaped.
    EXPECT_EQ(error_of(R"({"op":"a\"bcdefghijklmnopqrstuvwxyz0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"})"),
              R"(line 1: unknown op "a\"bcdefghijklmnopqrstuvwxyz0123456789ABC..." (expected collide, cast, sweep, closest or lines))");
}

TEST(QueryErrors, OpAndQueryShape) {
    EXPECT_EQ(error_of("[1,2]"), R"(line 1: a query must be a JSON object {"op": ...}, got array)");
    EXPECT_EQ(error_of("42"), R"(line 1: a query must be a JSON object {"op": ...}, got number)");
    EXPECT_EQ(error_of("{}"), R"(line 1: missing "op" (expected collide, cast, sweep, closest or lines))");
    EXPECT_EQ(error_of(R"({"op":1})"), R"(line 1: "op" must be a string: collide, cast, sweep, closest or lines)");
}

TEST(QueryErrors, MissingAndUnknownKeys) {
    EXPECT_EQ(error_of(R"({"op":"collide","a":)" + kBox02 + "}"), R"(line 1: missing "b" in collide)");
    EXPECT_EQ(error_of(R"({"op":"cast","from":[0,0],"shape":)" + kBox02 + "}"), R"(line 1: missing "to" in cast)");
    EXPECT_EQ(error_of(R"({"op":"closest","shape":)" + kBox02 + "}"), R"(line 1: missing "point" in closest)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"circle","center":[0,0]})")), R"(line 1: missing "radius" in circle)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"circle","center":[0,0],"raduis":1})")),
              R"(line 1: unknown key "raduis" in circle (expected type, center, radius))");
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[0,0],[1,1]],"b":[[0,1],[1,0]],"c":0})"),
              R"(line 1: unknown key "c" in lines (expected op, a, b))");
}

TEST(QueryErrors, ShapeObject) {
    EXPECT_EQ(error_of(closest("[0,0]", "[1,2]")),
              R"(line 1: "shape" must be a shape object such as {"type":"circle","center":[0,0],"radius":1})");
    EXPECT_EQ(error_of(collide(R"({"center":[0,0],"radius":1})", kUnitCircle)),
              R"(line 1: missing "type" in "a" (expected aabb, obb, polygon, circle, segment or mask))");
    EXPECT_EQ(error_of(collide(kUnitCircle, R"({"type":7})")),
              R"(line 1: "type" must be a string: aabb, obb, polygon, circle, segment or mask)");
}

TEST(QueryErrors, Vectors) {
    const std::string expected = R"(line 1: "center" must be [x, y], an array of 2 numbers)";
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[1]", "1"))), expected);
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[1,2,3]", "1"))), expected);
    EXPECT_EQ(error_of(closest("[0,0]", circle_at(R"([1,"2"])", "1"))), expected);
    EXPECT_EQ(error_of(closest("[0,0]", circle_at(R"({"x":1,"y":2})", "1"))), expected);
    EXPECT_EQ(error_of(closest("[0,0]", circle_at("[true,false]", "1"))), expected);
    EXPECT_EQ(error_of(closest("7", kUnitCircle)), R"(line 1: "point" must be [x, y], an array of 2 numbers)");
}

TEST(QueryErrors, AabbAndObb) {
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"aabb","min":[3,0],"max":[1,2]})")),
              R"(line 1: "min" must be <= "max" on both axes (min [3,0], max [1,2]))");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"aabb","min":[0,2.5],"max":[1,2]})")),
              R"(line 1: "min" must be <= "max" on both axes (min [0,2.5], max [1,2]))");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"obb","center":[0,0],"half":[-1,1],"angle":0})")),
              R"(line 1: "half" must be >= 0 on both axes (half extents), got [-1,1])");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"obb","center":[0,0],"half":[1,1],"angle":"45deg"})")),
              R"(line 1: "angle" must be a finite number (radians))");
}

TEST(QueryErrors, Polygon) {
    // make_polygon's messages, passed on as they are.
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[1,0],[2,0]]})")),
              "line 1: polygon has zero area (all vertices on one line)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[4,0],[1,1],[0,4]]})")),
              "line 1: polygon is not convex at vertex 2");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[4,0],[4,0],[0,4]]})")),
              "line 1: polygon vertices 1 and 2 are the same point");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[4,0]]})")),
              "line 1: a polygon needs 3 to 16 vertices, got 2");
    std::string many = R"({"type":"polygon","points":[)";
    for (int i = 0; i < 17; ++i) {
        const double a = 2.0 * 3.14159265358979 * i / 17.0;
        if (i > 0) many += ',';
        many += '[';
        many += std::to_string(100.0 * std::cos(a));
        many += ',';
        many += std::to_string(100.0 * std::sin(a));
        many += ']';
    }
    EXPECT_EQ(error_of(closest("[0,0]", many + "]}")), "line 1: a polygon needs 3 to 16 vertices, got 17");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":{"0":[0,0]}})")),
              R"(line 1: "points" must be an array of [x, y] points)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"polygon","points":[[0,0],[1],[0,1]]})")),
              R"(line 1: "points"[1] must be [x, y], an array of 2 numbers)");
}

TEST(QueryErrors, MaskRowsAndPlacement) {
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":["##","#x"]})")),
              R"(line 1: "rows": row 2, column 2: expected '#' or '.', got 'x')");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":["##","#"]})")),
              R"(line 1: "rows": row 2 has 1 pixels, expected 2 like row 1)");
    const std::string rows_expected =
        R"(line 1: "rows" must be a non-empty array of strings of '#' (set) and '.' (clear))";
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":[]})")), rows_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":"##"})")), rows_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":[1]})")), rows_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":[")" + std::string(4097, '#') + R"("]})")),
              R"(line 1: "rows"[0] has 4097 pixels; a mask is at most 4096 x 4096 pixels)");
    std::string tall = R"({"type":"mask","at":[0,0],"rows":[)";
    for (int i = 0; i < 4097; ++i) tall += i > 0 ? R"(,"#")" : R"("#")";
    EXPECT_EQ(error_of(closest("[0,0]", tall + "]}")),
              R"(line 1: "rows" has 4097 rows; a mask is at most 4096 x 4096 pixels)");

    const std::string at_expected =
        R"(line 1: "at" must be [x, y], 2 integers from -1000000000 to 1000000000 (the world pixel of the mask's top-left pixel))";
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0.5,0],"rows":["#"]})")), at_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,2000000000],"rows":["#"]})")), at_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0],"rows":["#"]})")), at_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":["0","0"],"rows":["#"]})")), at_expected);
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","rows":["#"]})")), R"(line 1: missing "at" in mask)");
    // 3.0 is an integer value.
    EXPECT_EQ(answer(closest("[0,0]", R"({"type":"mask","at":[3.0,-1],"rows":["#"]})")),
              R"({"point":[3,0],"distance":3})");
}

TEST(QueryErrors, MaskSources) {
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0]})")),
              R"(line 1: missing "rows" or "png" in mask)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":["#"],"png":"a.png"})")),
              R"(line 1: a mask takes "rows" or "png", not both)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"rows":["#"],"threshold":3})")),
              R"(line 1: "threshold" applies only to a "png" mask)");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"png":""})")),
              R"(line 1: "png" must be a file path (a non-empty string))");
    EXPECT_EQ(error_of(closest("[0,0]", R"({"type":"mask","at":[0,0],"png":7})")),
              R"(line 1: "png" must be a file path (a non-empty string))");
    const std::string mask_png = R"({"type":"mask","at":[0,0],"png":")" + kData + R"(/mask_4x4.png","threshold":)";
    EXPECT_EQ(error_of(closest("[0,0]", mask_png + "256}")), R"(line 1: "threshold" must be an integer from 0 to 255)");
    EXPECT_EQ(error_of(closest("[0,0]", mask_png + "-1}")), R"(line 1: "threshold" must be an integer from 0 to 255)");
    EXPECT_EQ(error_of(closest("[0,0]", mask_png + "1.5}")), R"(line 1: "threshold" must be an integer from 0 to 255)");
    // threshold 255: nothing is set.
    EXPECT_EQ(error_of(closest("[0,0]", mask_png + "255}")),
              R"(line 1: "shape" is a mask with no set pixels: it has no closest point)");
}

TEST(QueryErrors, PngFiles) {
    const auto png_mask = [](const std::string& file) {
        return closest("[0,0]", R"({"type":"mask","at":[0,0],"png":")" + kData + "/" + file + R"("})");
    };
    EXPECT_EQ(error_of(png_mask("missing.png")), "line 1: " + kData + "/missing.png: cannot open: No such file or directory");
    EXPECT_EQ(error_of(png_mask("not_png.png")), "line 1: " + kData + "/not_png.png: not a PNG file (no PNG signature)");
    EXPECT_EQ(error_of(png_mask("corrupt_crc.png")), "line 1: " + kData + "/corrupt_crc.png: corrupt PNG: IDAT: CRC error");
    EXPECT_EQ(error_of(png_mask("truncated.png")),
              "line 1: " + kData + "/truncated.png: corrupt PNG: unexpected end of file (truncated)");
    EXPECT_EQ(error_of(png_mask("too_wide.png")),
              "line 1: " + kData +
                  "/too_wide.png: image is 20000 x 1 pixels; the limit is 16384 x 16384 and 67108864 pixels in total");
    EXPECT_EQ(error_of(png_mask("wide_5000x1.png")),
              "line 1: " + kData + "/wide_5000x1.png: image is 5000 x 1 pixels; a mask is at most 4096 x 4096 pixels");
}

TEST(QueryErrors, LinesOp) {
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[0,0]],"b":[[0,1],[1,1]]})"),
              R"(line 1: "a" must be [[x, y], [x, y]], an array of 2 points)");
    EXPECT_EQ(error_of(R"({"op":"lines","a":[[0,0],[1,0]],"b":[[0,1],[1]]})"),
              R"(line 1: "b"[1] must be [x, y], an array of 2 numbers)");
}

TEST(QueryErrors, LineLongerThanOneMiB) {
    std::string line = R"({"op":"lines","a":[[0,0],[1,0]],"b":[[0,1],[1,1]]})";
    line += std::string(kMaxQueryLineBytes - line.size(), ' ');
    EXPECT_EQ(answer(line), R"({"kind":"parallel","point":null})");  // exactly 1 MiB is fine
    line += ' ';
    EXPECT_EQ(error_of(line, 9), "line 9: line is longer than 1 MiB (1048576 bytes)");
}

TEST(QueryErrors, BlankLinesHaveNoAnswer) {
    for (const char* blank : {"", " ", "\t \r", "\r"}) {
        bool ok = false;
        EXPECT_EQ(run_query_line(blank, 1, &ok), "");
        EXPECT_TRUE(ok);
    }
    EXPECT_EQ(run_query_line("", 1, nullptr), "");
}

TEST(QueryErrors, DeepNestingIsJustAWrongType) {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_EQ(error_of(closest(deep, kUnitCircle)), R"(line 1: "point" must be [x, y], an array of 2 numbers)");
}

// ---------------------------------------------------------------------------------------
// run_query: a stream of lines
// ---------------------------------------------------------------------------------------

TEST(QueryStream, AnswersEachLineSkipsBlankOnesAndGoesOnAfterAnError) {
    std::istringstream in(
        "{\"op\":\"lines\",\"a\":[[0,0],[2,2]],\"b\":[[0,2],[2,0]]}\r\n"
        "\n"
        "   \n"
        "{\"op\":\"colide\"}\n"
        "{\"op\":\"lines\",\"a\":[[0,0],[1,0]],\"b\":[[2,0],[3,0]]}");  // no final newline
    std::ostringstream out;
    EXPECT_EQ(run_query(in, out), 2);
    EXPECT_EQ(out.str(),
              "{\"kind\":\"point\",\"point\":[1,1]}\n"
              "{\"error\":\"line 4: unknown op \\\"colide\\\" (expected collide, cast, sweep, closest or lines)\"}\n"
              "{\"kind\":\"coincident\",\"point\":null}\n");
}

TEST(QueryStream, AllGoodIsZero) {
    std::istringstream in("{\"op\":\"closest\",\"point\":[5,1],\"shape\":" + kBox02 + "}\n\n");
    std::ostringstream out;
    EXPECT_EQ(run_query(in, out), 0);
    EXPECT_EQ(out.str(), "{\"point\":[2,1],\"distance\":3}\n");
}

TEST(QueryStream, EmptyInputIsZeroWithNoOutput) {
    std::istringstream in("");
    std::ostringstream out;
    EXPECT_EQ(run_query(in, out), 0);
    EXPECT_EQ(out.str(), "");
}

TEST(QueryStream, AHugeLineIsAnErrorAndTheNextLineIsAnswered) {
    std::string text = "[" + std::string(3 * kMaxQueryLineBytes, '1') + "]\n";
    text += "{\"op\":\"lines\",\"a\":[[0,0],[1,0]],\"b\":[[0,1],[1,1]]}\n";
    std::istringstream in(text);
    std::ostringstream out;
    EXPECT_EQ(run_query(in, out), 2);
    EXPECT_EQ(out.str(),
              "{\"error\":\"line 1: line is longer than 1 MiB (1048576 bytes)\"}\n"
              "{\"kind\":\"parallel\",\"point\":null}\n");
}

// Gives `text`, then fails the way a file stream does when read() fails (an ios_base::failure
// carrying errno).
class FailingBuffer : public std::streambuf {
public:
    FailingBuffer(std::string text, int error) : text_(std::move(text)), error_(error) {
        setg(text_.data(), text_.data(), text_.data() + text_.size());
    }

protected:
    int_type underflow() override {
        throw std::ios_base::failure("basic_filebuf::underflow error reading the file",
                                     std::error_code(error_, std::generic_category()));
    }

private:
    std::string text_;
    int error_;
};

TEST(QueryStream, AnUnreadableStdinSaysSoAfterTheLinesBeforeIt) {
    // Was "jostle: basic_filebuf::underflow error reading the file: Is a directory" from main().
    FailingBuffer buffer("{\"op\":\"lines\",\"a\":[[0,0],[1,0]],\"b\":[[0,1],[1,1]]}\n{\"op\"", EIO);
    std::istream in(&buffer);
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(query_command({}, in, out, err), 2);
    EXPECT_EQ(out.str(), "{\"kind\":\"parallel\",\"point\":null}\n");
    EXPECT_EQ(err.str(), "jostle query: <stdin>: cannot read: Input/output error\n");

    std::ifstream folder(kData);  // opening a folder works; reading it fails
    std::ostringstream out2;
    std::ostringstream err2;
    EXPECT_EQ(query_command({}, folder, out2, err2), 2);
    EXPECT_EQ(out2.str(), "");
    EXPECT_EQ(err2.str(), "jostle query: <stdin>: is a folder, expected query lines\n");
}

TEST(QueryStream, ExtraArgumentsAreAUsageError) {
    std::istringstream in("");
    std::ostringstream out;
    std::ostringstream err;
    const std::string_view args[] = {"--bogus"};
    EXPECT_EQ(query_command(args, in, out, err), 2);
    EXPECT_EQ(out.str(), "");
    EXPECT_THAT(err.str(), StartsWith("jostle query: unexpected argument '--bogus'"));
}

// ---------------------------------------------------------------------------------------
// End to end: the jostle binary
// ---------------------------------------------------------------------------------------

using test::RunResult;

// The binary, run in the test data folder by default.
RunResult run_jostle(const std::vector<std::string>& args, const std::string& stdin_path = "/dev/null",
                     const std::string& cwd = kData) {
    return test::run_jostle_binary(args, stdin_path, cwd);
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

TEST(JostleBinary, GoodQueriesFromAFile) {
    // Run in the data folder: the mask's "png" path is relative to the current folder.
    const RunResult r = run_jostle({"query"}, kData + "/queries_good.jsonl");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out.back(), '\n');
    const std::vector<std::string> expected = {
        R"({"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0]})",
        R"({"hit":true,"depth":0.5,"normal":[1,0],"mtd":[-0.5,0]})",
        // (the blank line 3 has no answer)
        R"({"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0],"pixels":2,"first":[12,11]})",
        R"({"hit":true,"t":0.5,"point":[0,1],"normal":[-1,0]})",
        R"({"hit":true,"t":0.75,"point":[4,0],"normal":[1,0]})",
        R"({"point":[2,1],"distance":3})",
        R"({"kind":"point","point":[1,1]})",
    };
    EXPECT_EQ(lines_of(r.out), expected);
}

TEST(JostleBinary, BadLinesInTheMiddleAreAnsweredAndExitIsTwo) {
    const RunResult r = run_jostle({"query"}, kData + "/queries_mixed.jsonl");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "");
    const std::vector<std::string> lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 5u) << r.out;
    EXPECT_EQ(lines[0], R"({"point":[2,0],"distance":3})");
    EXPECT_EQ(lines[1],
              R"x({"error":"line 2: unknown shape type \"cirlce\" (expected aabb, obb, polygon, circle, segment or mask)"})x");
    EXPECT_EQ(lines[2], R"({"error":"line 3: corrupt_crc.png: corrupt PNG: IDAT: CRC error"})");
    EXPECT_THAT(lines[3], StartsWith(R"({"error":"line 4: not valid JSON: )"));
    EXPECT_EQ(lines[4], R"({"kind":"parallel","point":null})");
}

TEST(JostleBinary, EmptyInput) {
    const RunResult r = run_jostle({"query"});
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
}

TEST(JostleBinary, Help) {
    for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"}, {"-h"}, {"help"}}) {
        const RunResult r = run_jostle(args);
        EXPECT_EQ(r.status, 0);
        EXPECT_THAT(r.out, StartsWith("usage: jostle <command> [arguments]\n"));
        EXPECT_THAT(r.out, HasSubstr("\n  query     answer collision queries"));
        EXPECT_EQ(r.err, "");
    }
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"query", "--help"}, {"query", "-h"}, {"help", "query"}}) {
        const RunResult r = run_jostle(args);
        EXPECT_EQ(r.status, 0);
        EXPECT_EQ(r.out, query_help());
        EXPECT_EQ(r.err, "");
    }
    EXPECT_THAT(std::string(query_help()), HasSubstr("Blank lines"));
}

TEST(JostleBinary, UsageErrorsExitTwo) {
    RunResult r = run_jostle({});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_THAT(r.err, StartsWith("usage: jostle <command>"));

    r = run_jostle({"frobnicate"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "jostle: unknown command 'frobnicate' (expected query, play, record, check, imgdiff, help)\nRun 'jostle --help' for usage.\n");

    r = run_jostle({"--frobnicate"});
    EXPECT_EQ(r.status, 2);
    EXPECT_THAT(r.err, StartsWith("jostle: unknown option '--frobnicate'"));

    r = run_jostle({"help", "frobnicate"});
    EXPECT_EQ(r.status, 2);
    EXPECT_THAT(r.err, StartsWith("jostle: unknown command 'frobnicate'"));

    r = run_jostle({"query", "input.jsonl"});
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_THAT(r.err, StartsWith("jostle query: unexpected argument 'input.jsonl'"));
}

}  // namespace
}  // namespace jostle
