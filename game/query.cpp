// query.cpp: `jostle query`: parses each JSON line into collision shapes (with messages that
// say what was expected), calls the collision module, and writes the result with a small
// serializer that prints every float in its shortest round-trip form.
#include "query.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <ios>
#include <istream>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <ostream>
#include <stdexcept>
#include <system_error>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "jostle/collision.h"
#include "jostle/core/error.h"
#include "jostle/core/text.h"
#include "jostle/render/png_io.h"

namespace jostle {
namespace {

using Json = nlohmann::json;

constexpr std::string_view kShapeTypes = "aabb, obb, polygon, circle, segment or mask";
constexpr std::string_view kOps = "collide, cast, sweep, closest or lines";
// "at" of a mask: far beyond any useful world, small enough that x + width never overflows.
constexpr double kMaxMaskPosition = 1e9;

// A line that cannot be answered; the message says what was wrong and what was expected.
class BadQuery : public std::runtime_error {
public:
    explicit BadQuery(const std::string& what) : std::runtime_error(what) {}
};

// ---------------------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------------------

// A result object under construction: {"key":value,...} in the order the fields are added.
class ObjectWriter {
public:
    ObjectWriter() : text_("{") {}

    void add_bool(std::string_view key, bool value) {
        add_key(key);
        text_ += value ? "true" : "false";
    }
    void add_number(std::string_view key, float value) {
        add_key(key);
        append_json_number(text_, value);
    }
    void add_int(std::string_view key, int value) {
        add_key(key);
        text_ += std::to_string(value);
    }
    void add_vec(std::string_view key, Vec2 v) {
        add_key(key);
        text_ += '[';
        append_json_number(text_, v.x);
        text_ += ',';
        append_json_number(text_, v.y);
        text_ += ']';
    }
    void add_pixel(std::string_view key, Pixel p) {
        add_key(key);
        text_ += '[' + std::to_string(p.x) + ',' + std::to_string(p.y) + ']';
    }
    void add_string(std::string_view key, std::string_view value) {
        add_key(key);
        append_json_string(text_, value);
    }
    void add_null(std::string_view key) {
        add_key(key);
        text_ += "null";
    }
    std::string finish() {
        text_ += '}';
        return std::move(text_);
    }

private:
    void add_key(std::string_view key) {
        if (text_.size() > 1) text_ += ',';
        append_json_string(text_, key);
        text_ += ':';
    }
    std::string text_;
};

// ---------------------------------------------------------------------------------------
// Messages
// ---------------------------------------------------------------------------------------

// A string from the input, quoted for a message, cut after 40 bytes.
std::string quote_input(std::string_view text) {
    constexpr std::size_t kMaxShown = 40;
    std::string out;
    if (text.size() <= kMaxShown) {
        append_json_string(out, text);
        return out;
    }
    std::size_t cut = kMaxShown;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // whole characters
    append_json_string(out, text.substr(0, cut));
    out.insert(out.size() - 1, "...");
    return out;
}

// Our own key names, quoted. (Built by appending: GCC 12 warns falsely on "\"" + s + "\"".)
std::string quote_key(std::string_view key) {
    std::string out(1, '"');
    out += key;
    out += '"';
    return out;
}

// The shortest text that reads back as `value`; plain digits for everyday sizes (200000 rather
// than 2e+05), an exponent for the rest (1e+19).
std::string format_double(double value) {
    char buffer[64];
    const bool plain = std::fabs(value) >= 1e-4 && std::fabs(value) < 1e15;
    const auto result = plain ? std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed)
                              : std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string format_vec(Vec2 v) {
    std::string out = "[";
    append_json_number(out, v.x);
    out += ',';
    append_json_number(out, v.y);
    return out + ']';
}

// ---------------------------------------------------------------------------------------
// Reading fields
// ---------------------------------------------------------------------------------------

// The fields of one JSON object (a query or a shape), named `what` in messages. Rejects keys
// it does not know: they are almost always typos ("raduis") that would be silently ignored.
class Fields {
public:
    Fields(const Json& object, std::string_view what, std::initializer_list<std::string_view> keys)
        : object_(object), what_(what) {
        for (const auto& item : object.items()) {
            bool known = false;
            for (std::string_view key : keys) known = known || item.key() == key;
            if (known) continue;
            std::string expected;
            for (std::string_view key : keys) {
                if (!expected.empty()) expected += ", ";
                expected += key;
            }
            throw BadQuery("unknown key " + quote_input(item.key()) + " in " + std::string(what) + " (expected " +
                           expected + ")");
        }
    }

    const Json& required(std::string_view key) const {
        const Json* value = optional(key);
        if (value == nullptr) throw BadQuery("missing " + quote_key(key) + " in " + std::string(what_));
        return *value;
    }

    const Json* optional(std::string_view key) const {
        const auto it = object_.find(key);
        return it == object_.end() ? nullptr : &*it;
    }

private:
    const Json& object_;
    std::string_view what_;
};

// A JSON number as a float (an angle: not in pixels, so any float). `name` is the quoted name
// for messages; `expected` completes "<name> must be ..." when the value is not a number.
float to_float(const Json& value, const std::string& name, std::string_view expected) {
    if (!value.is_number()) throw BadQuery(name + " must be " + std::string(expected));
    const double d = value.get<double>();
    if (!std::isfinite(d)) throw BadQuery(name + " must be " + std::string(expected));
    if (std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max())) {
        throw BadQuery(name + " is " + format_double(d) + ", too large for a float (at most about 3.4e+38)");
    }
    return static_cast<float>(d);
}

// What a number in pixels is, for the range it must be in and the message when it is not.
enum class Pixels { coordinate, motion, half_extent, radius };

// A JSON number in pixels: a coordinate, a motion, a half extent or a radius. collision.h
// (LIMITS) promises its precision only within |x|, |y| <= kMaxCoordinate (1e5, as levels are
// held to); beyond it results lose precision, and far beyond it (1e18 and more) squares
// overflow and hits become misses. A query is answered right or refused, so a number past the range is refused
// with the range, like 1e39, which no float holds. `not_a_number` completes "<name> must be
// ..." when the value is not a number.
float to_pixels(const Json& value, const std::string& name, std::string_view not_a_number, Pixels kind) {
    static_assert(kMaxCoordinate == 1e5f, "the messages below say 1e5");
    if (!value.is_number()) throw BadQuery(name + " must be " + std::string(not_a_number));
    const double d = value.get<double>();
    // Compared as the float it becomes (as levels are): 100000.001 is the float 1e5.
    if (std::isfinite(d) && std::fabs(d) <= static_cast<double>(std::numeric_limits<float>::max()) &&
        std::fabs(static_cast<float>(d)) <= kMaxCoordinate) {
        return static_cast<float>(d);
    }
    const char* what = kind == Pixels::coordinate    ? "a coordinate from -1e5 to 1e5"
                       : kind == Pixels::motion      ? "a motion from -1e5 to 1e5 on each axis"
                       : kind == Pixels::half_extent ? "a half extent from 0 to 1e5"
                                                     : "a radius from 0 to 1e5";
    throw BadQuery(name + " is " + format_double(d) + ": expected " + what +
                   " (the collision module's documented range)");
}

// [x, y] as a Vec2.
Vec2 to_vec2(const Json& value, const std::string& name, Pixels kind = Pixels::coordinate) {
    const std::string expected = name + " must be [x, y], an array of 2 numbers";
    if (!value.is_array() || value.size() != 2 || !value[0].is_number() || !value[1].is_number()) {
        throw BadQuery(expected);
    }
    return {to_pixels(value[0], name + "[0]", "a number", kind), to_pixels(value[1], name + "[1]", "a number", kind)};
}

Vec2 field_vec2(const Fields& fields, std::string_view key, Pixels kind = Pixels::coordinate) {
    return to_vec2(fields.required(key), quote_key(key), kind);
}

// An integer in [low, high] (a JSON number with an integer value: 3 and 3.0 both count).
std::optional<int> to_int(const Json& value, double low, double high) {
    if (!value.is_number()) return std::nullopt;
    const double d = value.get<double>();
    if (!(d >= low && d <= high) || d != std::floor(d)) return std::nullopt;
    return static_cast<int>(d);
}

// ---------------------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------------------

// A parsed shape. A mask's pixels live in `mask` (on the heap, so the PlacedMask in `shape`
// keeps pointing at them when a ParsedShape is moved).
struct ParsedShape {
    Shape shape;
    std::unique_ptr<Mask> mask;
};

Aabb parse_aabb(const Json& j) {
    const Fields fields(j, "aabb", {"type", "min", "max"});
    const Aabb box{field_vec2(fields, "min"), field_vec2(fields, "max")};
    if (!(box.min.x <= box.max.x && box.min.y <= box.max.y)) {
        throw BadQuery("\"min\" must be <= \"max\" on both axes (min " + format_vec(box.min) + ", max " +
                       format_vec(box.max) + ")");
    }
    return box;
}

Obb parse_obb(const Json& j) {
    const Fields fields(j, "obb", {"type", "center", "half", "angle"});
    Obb box;
    box.center = field_vec2(fields, "center");
    box.half = field_vec2(fields, "half", Pixels::half_extent);
    if (!(box.half.x >= 0.0f && box.half.y >= 0.0f)) {
        throw BadQuery("\"half\" must be >= 0 on both axes (half extents), got " + format_vec(box.half));
    }
    if (const Json* angle = fields.optional("angle")) {
        box.set_angle(to_float(*angle, "\"angle\"", "a finite number (radians)"));
    }
    return box;
}

Polygon parse_polygon(const Json& j) {
    const Fields fields(j, "polygon", {"type", "points"});
    const Json& points_json = fields.required("points");
    if (!points_json.is_array()) throw BadQuery("\"points\" must be an array of [x, y] points");
    std::vector<Vec2> points;
    points.reserve(points_json.size());
    for (std::size_t i = 0; i < points_json.size(); ++i) {
        points.push_back(to_vec2(points_json[i], "\"points\"[" + std::to_string(i) + "]"));
    }
    std::string error;
    std::optional<Polygon> polygon = make_polygon(points, &error);
    if (!polygon) throw BadQuery(error);  // make_polygon's message names the polygon and the vertex
    return *polygon;
}

Circle parse_circle(const Json& j) {
    const Fields fields(j, "circle", {"type", "center", "radius"});
    Circle circle;
    circle.center = field_vec2(fields, "center");
    circle.radius = to_pixels(fields.required("radius"), "\"radius\"", "a finite number >= 0", Pixels::radius);
    if (!(circle.radius >= 0.0f)) throw BadQuery("\"radius\" must be a finite number >= 0");
    return circle;
}

Segment parse_segment(const Json& j) {
    const Fields fields(j, "segment", {"type", "a", "b"});
    return {field_vec2(fields, "a"), field_vec2(fields, "b")};
}

std::unique_ptr<Mask> mask_from_rows(const Json& rows_json) {
    const std::string expected = "\"rows\" must be a non-empty array of strings of '#' (set) and '.' (clear)";
    if (!rows_json.is_array() || rows_json.empty()) throw BadQuery(expected);
    const std::string limit = std::to_string(kMaxMaskSide);
    if (rows_json.size() > static_cast<std::size_t>(kMaxMaskSide)) {
        throw BadQuery("\"rows\" has " + std::to_string(rows_json.size()) + " rows; a mask is at most " + limit +
                       " x " + limit + " pixels");
    }
    std::vector<std::string_view> rows;
    rows.reserve(rows_json.size());
    for (std::size_t i = 0; i < rows_json.size(); ++i) {
        if (!rows_json[i].is_string()) throw BadQuery(expected);
        const auto& row = rows_json[i].get_ref<const std::string&>();
        // (As "rows":[] is refused: a mask of no pixels in a query is a mistake, not a shape.)
        if (row.empty()) throw BadQuery("\"rows\"[" + std::to_string(i) + "] is empty: a mask row has at least one pixel");
        if (row.size() > static_cast<std::size_t>(kMaxMaskSide)) {
            throw BadQuery("\"rows\"[" + std::to_string(i) + "] has " + std::to_string(row.size()) +
                           " pixels; a mask is at most " + limit + " x " + limit + " pixels");
        }
        rows.push_back(row);
    }
    std::string error;
    std::optional<Mask> mask = Mask::from_rows(rows, &error);
    if (!mask) throw BadQuery("\"rows\": " + error);
    return std::make_unique<Mask>(std::move(*mask));
}

std::unique_ptr<Mask> mask_from_png(const Json& png_json, const Json* threshold_json) {
    if (!png_json.is_string() || png_json.get_ref<const std::string&>().empty()) {
        throw BadQuery("\"png\" must be a file path (a non-empty string)");
    }
    int threshold = 127;
    if (threshold_json != nullptr) {
        const std::optional<int> t = to_int(*threshold_json, 0, 255);
        if (!t) throw BadQuery("\"threshold\" must be an integer from 0 to 255");
        threshold = *t;
    }
    const auto& path = png_json.get_ref<const std::string&>();
    const Image image = read_png(path);  // InputError names the file
    if (image.width > kMaxMaskSide || image.height > kMaxMaskSide) {
        const std::string limit = std::to_string(kMaxMaskSide);
        throw BadQuery(path + ": image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                       " pixels; a mask is at most " + limit + " x " + limit + " pixels");
    }
    return std::make_unique<Mask>(
        Mask::from_alpha(image.rgba.data(), image.width, image.height, static_cast<std::uint8_t>(threshold)));
}

ParsedShape parse_mask(const Json& j) {
    const Fields fields(j, "mask", {"type", "at", "rows", "png", "threshold"});
    const Json& at = fields.required("at");
    const std::optional<int> x = at.is_array() && at.size() == 2 ? to_int(at[0], -kMaxMaskPosition, kMaxMaskPosition)
                                                                  : std::nullopt;
    const std::optional<int> y = at.is_array() && at.size() == 2 ? to_int(at[1], -kMaxMaskPosition, kMaxMaskPosition)
                                                                  : std::nullopt;
    if (!x || !y) {
        throw BadQuery("\"at\" must be [x, y], 2 integers from -1000000000 to 1000000000 (the world pixel of the "
                       "mask's top-left pixel)");
    }
    const Json* rows = fields.optional("rows");
    const Json* png = fields.optional("png");
    const Json* threshold = fields.optional("threshold");
    if (rows != nullptr && png != nullptr) throw BadQuery("a mask takes \"rows\" or \"png\", not both");
    if (rows == nullptr && png == nullptr) throw BadQuery("missing \"rows\" or \"png\" in mask");
    if (rows != nullptr && threshold != nullptr) throw BadQuery("\"threshold\" applies only to a \"png\" mask");

    ParsedShape parsed;
    parsed.mask = rows != nullptr ? mask_from_rows(*rows) : mask_from_png(*png, threshold);
    parsed.shape = PlacedMask{parsed.mask.get(), *x, *y};
    return parsed;
}

// A shape object; `name` is how the query calls it ("a", "shape"), for messages.
ParsedShape parse_shape(const Json& j, std::string_view name) {
    if (!j.is_object()) {
        throw BadQuery(quote_key(name) + " must be a shape object such as {\"type\":\"circle\",\"center\":[0,0],"
                                         "\"radius\":1}");
    }
    const auto type_it = j.find("type");
    if (type_it == j.end()) {
        throw BadQuery("missing \"type\" in " + quote_key(name) + " (expected " + std::string(kShapeTypes) + ")");
    }
    if (!type_it->is_string()) throw BadQuery("\"type\" must be a string: " + std::string(kShapeTypes));
    const auto& type = type_it->get_ref<const std::string&>();
    if (type == "aabb") return {parse_aabb(j), nullptr};
    if (type == "obb") return {parse_obb(j), nullptr};
    if (type == "polygon") return {parse_polygon(j), nullptr};
    if (type == "circle") return {parse_circle(j), nullptr};
    if (type == "segment") return {parse_segment(j), nullptr};
    if (type == "mask") return parse_mask(j);
    throw BadQuery("unknown shape type " + quote_input(type) + " (expected " + std::string(kShapeTypes) + ")");
}

// ---------------------------------------------------------------------------------------
// Ops
// ---------------------------------------------------------------------------------------

std::string op_collide(const Json& q) {
    const Fields fields(q, "collide", {"op", "a", "b"});
    const ParsedShape a = parse_shape(fields.required("a"), "a");
    const ParsedShape b = parse_shape(fields.required("b"), "b");
    const Manifold m = collide(a.shape, b.shape);
    ObjectWriter out;
    out.add_bool("hit", m.hit);
    out.add_number("depth", m.depth);
    out.add_vec("normal", m.normal);
    out.add_vec("mtd", m.mtd());
    if (a.mask && b.mask) {
        const auto& ma = std::get<PlacedMask>(a.shape);
        const auto& mb = std::get<PlacedMask>(b.shape);
        out.add_int("pixels", count_overlap(ma, mb));
        if (const std::optional<Pixel> first = first_overlap(ma, mb)) {
            out.add_pixel("first", *first);
        } else {
            out.add_null("first");
        }
    }
    return out.finish();
}

// A cast's or a sweep's answer: {"hit","t","point","normal"}.
template <class Contact>
std::string contact_json(const Contact& hit) {
    ObjectWriter out;
    out.add_bool("hit", hit.hit);
    out.add_number("t", hit.t);
    out.add_vec("point", hit.point);
    out.add_vec("normal", hit.normal);
    return out.finish();
}

std::string op_cast(const Json& q) {
    const Fields fields(q, "cast", {"op", "from", "to", "shape"});
    const Vec2 from = field_vec2(fields, "from");
    const Vec2 to = field_vec2(fields, "to");
    const ParsedShape shape = parse_shape(fields.required("shape"), "shape");
    return contact_json(cast(from, to, shape.shape));
}

std::string op_sweep(const Json& q) {
    const Fields fields(q, "sweep", {"op", "a", "va", "b", "vb"});
    const ParsedShape a = parse_shape(fields.required("a"), "a");
    const Circle* circle = std::get_if<Circle>(&a.shape);
    if (circle == nullptr) {
        throw BadQuery("\"a\" must be a circle for sweep (the moving circle), got " +
                       std::string(name_of(kind_of(a.shape))));
    }
    const Vec2 va = field_vec2(fields, "va", Pixels::motion);
    const ParsedShape b = parse_shape(fields.required("b"), "b");
    const Vec2 vb = field_vec2(fields, "vb", Pixels::motion);
    return contact_json(sweep(*circle, va, b.shape, vb));
}

std::string op_closest(const Json& q) {
    const Fields fields(q, "closest", {"op", "point", "shape"});
    const Vec2 point = field_vec2(fields, "point");
    const ParsedShape shape = parse_shape(fields.required("shape"), "shape");
    if (shape.mask && shape.mask->count() == 0) {
        throw BadQuery("\"shape\" is a mask with no set pixels: it has no closest point");
    }
    const ClosestPoint closest = closest_point(shape.shape, point);
    ObjectWriter out;
    out.add_vec("point", closest.point);
    out.add_number("distance", closest.distance);
    return out.finish();
}

// Two points [[x, y], [x, y]].
std::pair<Vec2, Vec2> to_point_pair(const Json& value, std::string_view key) {
    const std::string name = quote_key(key);
    if (!value.is_array() || value.size() != 2) {
        throw BadQuery(name + " must be [[x, y], [x, y]], an array of 2 points");
    }
    return {to_vec2(value[0], name + "[0]"), to_vec2(value[1], name + "[1]")};
}

std::string op_lines(const Json& q) {
    const Fields fields(q, "lines", {"op", "a", "b"});
    const auto [a1, a2] = to_point_pair(fields.required("a"), "a");
    const auto [b1, b2] = to_point_pair(fields.required("b"), "b");
    // Two equal points make no line (A = B = 0): intersect() would call it parallel.
    if (a1 == a2) throw BadQuery("\"a\" gives the same point twice: a line needs two different points");
    if (b1 == b2) throw BadQuery("\"b\" gives the same point twice: a line needs two different points");
    const LineIntersection crossing = intersect(line_through(a1, a2), line_through(b1, b2));
    ObjectWriter out;
    switch (crossing.kind) {
        case LineRelation::point:
            out.add_string("kind", "point");
            out.add_vec("point", crossing.point);
            break;
        case LineRelation::parallel:
            out.add_string("kind", "parallel");
            out.add_null("point");
            break;
        case LineRelation::coincident:
            out.add_string("kind", "coincident");
            out.add_null("point");
            break;
    }
    return out.finish();
}

struct Op {
    std::string_view name;
    std::string (*answer)(const Json& query);
};

constexpr Op kOpTable[] = {
    {"collide", op_collide}, {"cast", op_cast}, {"sweep", op_sweep}, {"closest", op_closest}, {"lines", op_lines},
};

std::string answer_query(const Json& query) {
    if (!query.is_object()) {
        throw BadQuery("a query must be a JSON object {\"op\": ...}, got " + std::string(query.type_name()));
    }
    const auto op_it = query.find("op");
    if (op_it == query.end()) throw BadQuery("missing \"op\" (expected " + std::string(kOps) + ")");
    if (!op_it->is_string()) throw BadQuery("\"op\" must be a string: " + std::string(kOps));
    const auto& op = op_it->get_ref<const std::string&>();
    for (const Op& entry : kOpTable) {
        if (entry.name == op) return entry.answer(query);
    }
    throw BadQuery("unknown op " + quote_input(op) + " (expected " + std::string(kOps) + ")");
}

// nlohmann's message without its "[json.exception.parse_error.101] " tag; "at line 1, column
// 5" becomes "at column 5", since the query is a single line.
std::string json_error_message(const Json::exception& e) {
    std::string message = e.what();
    if (!message.empty() && message.front() == '[') {
        const std::size_t end = message.find("] ");
        if (end != std::string::npos) message.erase(0, end + 2);
    }
    const std::size_t line_one = message.find("at line 1, column ");
    if (line_one != std::string::npos) message.erase(line_one + 3, std::strlen("line 1, "));
    return message;
}

// The 1-based column of the line's n-th key (1-based), or 0. The line is valid JSON up to that
// key (the parser has just read it, maybe before its ':'), so a key is a string directly inside
// an object that follows its '{' or a ','.
std::size_t key_column(std::string_view line, int n) {
    std::vector<char> open;  // the brackets around the current position, innermost last
    char before = 0;         // the last character outside strings and blanks
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char ch = line[i];
        if (ch == '"') {
            if (!open.empty() && open.back() == '{' && (before == '{' || before == ',') && --n == 0) return i + 1;
            for (++i; i < line.size() && line[i] != '"'; ++i) {
                if (line[i] == '\\') ++i;
            }
            before = '"';
        } else if (ch == '{' || ch == '[') {
            open.push_back(ch);
            before = ch;
        } else if (ch == '}' || ch == ']') {
            if (!open.empty()) open.pop_back();
            before = ch;
        } else if (ch != ' ' && ch != '\t' && ch != '\n' && ch != '\r') {
            before = ch;
        }
    }
    return 0;
}

// Parses one query line. Refuses a key given twice in one object ({"op":"collide",...,"op":
// "cast"}: JSON leaves it to the reader, and nlohmann keeps the last, so the line would be
// answered as something it does not plainly say) and a NUL byte,
// which the parser would take for the end of the input ("unexpected end of input", or the
// line silently cut short after a complete object); other errors are Json::parse_error.
Json parse_query_json(std::string_view line) {
    const std::size_t nul = line.find('\0');
    // The keys of each object being read, innermost last (objects nest 100,000 deep: no recursion).
    std::vector<std::set<std::string, std::less<>>> keys;
    int keys_read = 0;
    Json query;
    try {
        query = Json::parse(line.begin(), line.end(), [&](int, Json::parse_event_t event, Json& parsed) {
            if (event == Json::parse_event_t::object_start) keys.emplace_back();
            if (event == Json::parse_event_t::object_end) keys.pop_back();
            if (event == Json::parse_event_t::key && (++keys_read, !keys.back().insert(parsed.get_ref<const std::string&>()).second)) {
                throw BadQuery("duplicate key " + quote_input(parsed.get<std::string>()) + " at column " +
                               std::to_string(key_column(line, keys_read)) + " (a key may appear only once in an object)");
            }
            return true;
        });
    } catch (const Json::parse_error& e) {
        // e.byte is the 1-based offset of the last byte read: an error at or after the NUL is
        // the NUL's (the parser reads it as the end of the input).
        if (nul == std::string_view::npos || e.byte <= nul) throw;
    }
    if (nul == std::string_view::npos) return query;
    throw BadQuery("not valid JSON: a NUL byte (0x00) at column " + std::to_string(nul + 1) + " (is this a binary file?)");
}

std::string error_line(std::int64_t line_number, const std::string& message) {
    ObjectWriter out;
    out.add_string("error", "line " + std::to_string(line_number) + ": " + message);
    return out.finish();
}

bool is_blank(std::string_view line) {
    return line.find_first_not_of(" \t\r") == std::string_view::npos;
}

}  // namespace

void append_json_number(std::string& out, float value) {
    if (!std::isfinite(value)) {
        out += "null";
        return;
    }
    if (value == 0.0f) {  // also -0
        out += '0';
        return;
    }
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    out.append(buffer, result.ptr);
}

void append_json_string(std::string& out, std::string_view text) {
    static constexpr char kHex[] = "0123456789abcdef";
    out += '"';
    std::size_t i = 0;
    while (i < text.size()) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x80) {
            const std::size_t length = utf8_sequence_length(text, i);
            if (length == 0) {
                out += "\\ufffd";
                ++i;
            } else {
                out.append(text.substr(i, length));
                i += length;
            }
            continue;
        }
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\b': out += "\\b"; break;
            case '\f': out += "\\f"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20 || c == 0x7f) {
                    out += "\\u00";
                    out += kHex[c >> 4];
                    out += kHex[c & 0xf];
                } else {
                    out += static_cast<char>(c);
                }
        }
        ++i;
    }
    out += '"';
}

std::string run_query_line(std::string_view line, std::int64_t line_number, bool* ok) {
    if (ok != nullptr) *ok = true;
    if (is_blank(line)) return {};
    const auto failed = [&](const std::string& message) {
        if (ok != nullptr) *ok = false;
        return error_line(line_number, message);
    };
    if (line.size() > kMaxQueryLineBytes) {
        return failed("line is longer than 1 MiB (" + std::to_string(kMaxQueryLineBytes) + " bytes)");
    }
    Json query;
    try {
        query = parse_query_json(line);
    } catch (const Json::exception& e) {
        return failed("not valid JSON: " + json_error_message(e));
    } catch (const BadQuery& e) {
        return failed(e.what());
    }
    try {
        return answer_query(query);
    } catch (const BadQuery& e) {
        return failed(e.what());
    } catch (const InputError& e) {
        return failed(e.what());
    } catch (const std::bad_alloc&) {
        return failed("out of memory");
    }
}

int run_query(std::istream& in, std::ostream& out) {
    std::streambuf* input = in.rdbuf();
    if (input == nullptr) return 2;
    bool all_ok = true;
    std::string line;
    for (std::int64_t line_number = 1;; ++line_number) {
        // Reads one line, keeping at most kMaxQueryLineBytes + 1 bytes of it (enough to know
        // it is too long) so a huge line cannot exhaust memory.
        line.clear();
        bool read_any = false;
        int c = 0;
        try {
            while ((c = input->sbumpc()) != std::char_traits<char>::eof()) {
                read_any = true;
                if (c == '\n') break;
                if (line.size() <= kMaxQueryLineBytes) line.push_back(static_cast<char>(c));
            }
        } catch (const std::ios_base::failure& e) {
            // A file stream's read failed (stdin is a folder); the lines answered so far stand.
            // Named as record names its script on standard input.
            if (e.code() == std::errc::is_a_directory) throw InputError("<stdin>: is a folder, expected query lines");
            throw InputError("<stdin>: cannot read: " + e.code().message());
        }
        if (!read_any) break;
        bool ok = true;
        const std::string answer = run_query_line(line, line_number, &ok);
        all_ok = all_ok && ok;
        if (!answer.empty()) {
            out << answer << '\n';
            out.flush();
            if (!out) return 2;
        }
        if (c == std::char_traits<char>::eof()) break;
    }
    return all_ok ? 0 : 2;
}

int query_command(std::span<const std::string_view> args, std::istream& in, std::ostream& out,
                  std::ostream& err) {
    if (!args.empty() && args.front() == "--") args = args.subspan(1);  // the end of the options; query takes no files
    if (!args.empty()) {
        err << "jostle query: unexpected argument '" << args.front()
            << "' (queries are read from stdin)\nRun 'jostle query --help' for usage.\n";
        return 2;
    }
    int status = 0;
    try {
        status = run_query(in, out);
    } catch (const InputError& e) {
        err << "jostle query: " << e.what() << '\n';
        return 2;
    }
    return status;  // (results that could not reach stdout: main says so, exit 2)
}

std::string_view query_help() {
    return R"(usage: jostle query [--help]

Answers collision queries. Reads JSON lines on stdin, one query object per line, and writes
one JSON result per line on stdout, in input order, flushed after each line (so a program
can talk to it through a pipe). Blank lines (only spaces, tabs, \r) are skipped and get no
output line; line numbers in messages still count them.

queries and their results:
  {"op":"collide","a":S,"b":S}
      -> {"hit":true,"depth":d,"normal":[x,y],"mtd":[x,y]}
      normal points from a toward b; mtd = -depth * normal moves a out of b; touching is a
      hit with depth 0. When a and b are both masks, also "pixels" (how many world pixels
      both have set) and "first" (the first such pixel [x,y] in reading order, or null).
  {"op":"cast","from":[x,y],"to":[x,y],"shape":S}
      -> {"hit":true,"t":t,"point":[x,y],"normal":[x,y]}
      the segment from->to first touches the shape at from + t*(to-from); normal is the
      shape's outward normal there ([0,0] when from is inside).
  {"op":"sweep","a":C,"va":[x,y],"b":S,"vb":[x,y]}
      -> {"hit":true,"t":t,"point":[x,y],"normal":[x,y]}
      circle C moving by va and shape S moving by vb first touch at time t in [0,1];
      a must be a circle.
  {"op":"closest","point":[x,y],"shape":S}
      -> {"point":[x,y],"distance":d}
      the point of the shape nearest the given point (distance 0 inside).
  {"op":"lines","a":[[x,y],[x,y]],"b":[[x,y],[x,y]]}
      -> {"kind":"point","point":[x,y]}, or "parallel" / "coincident" with "point":null
      where the infinite lines through the two pairs of points cross (the two points
      of a pair must differ).

shapes S:
  {"type":"aabb","min":[x,y],"max":[x,y]}                 min <= max on both axes
  {"type":"obb","center":[x,y],"half":[hx,hy],"angle":a}  half >= 0; angle in radians,
                                                          from +x toward +y (default 0)
  {"type":"polygon","points":[[x,y],...]}                 convex, 3 to 16 points,
                                                          either winding
  {"type":"circle","center":[x,y],"radius":r}             r >= 0
  {"type":"segment","a":[x,y],"b":[x,y]}
  {"type":"mask","at":[x,y],"rows":["..##",".###"]}       '#' set, '.' clear
  {"type":"mask","at":[x,y],"png":"file.png","threshold":t}
                                                          set where alpha > t (0 to 255,
                                                          default 127); the path is
                                                          relative to the current folder
  A mask's "at" is the world pixel (integers) of its top-left pixel; masks are at most
  4096 x 4096 pixels.

Coordinates are pixels, y pointing down. Every coordinate, half extent, radius and each
axis of va and vb must be within -1e5 .. 1e5 (half extents and radii 0 .. 1e5): the range
in which the collision module promises its precision (kMaxCoordinate); a line with a number
past it is an error, not a less exact answer. An angle may be any float; a mask's "at" is whole pixels
within -1e9 .. 1e9. A number finer than a float (1e-320) rounds to the nearest float. Results
print each float in the shortest form that reads back as the same float (0.5, 2, 1e-05; -0
prints as 0); a result too large for a float prints as null.

errors:
  A line that cannot be answered gets {"error":"line N: ..."} as its output line, saying
  what was wrong and what was expected; the lines after it are still answered. Not valid
  JSON (a NUL byte too), a missing or unknown key (usually a typo), a key given twice in
  one object, a value of the wrong type or range, a bad polygon or mask, an unreadable PNG,
  and a line longer than 1 MiB are errors.
  Standard input that cannot be read (a folder) ends the run with a message on stderr.

exit status: 0 every line was answered, 2 some line was an error, stdin could not be read or
stdout written (or bad usage).

example:
  $ echo '{"op":"collide","a":{"type":"aabb","min":[0,0],"max":[2,2]},"b":{"type":"aabb","min":[1,0],"max":[3,2]}}' | jostle query
  {"hit":true,"depth":1,"normal":[1,0],"mtd":[-1,0]}
)";
}

}  // namespace jostle
