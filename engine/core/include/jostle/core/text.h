// jostle/core/text.h: the small text helpers shared by every line-oriented file format
// (scenarios, input scripts, levels, traces): splitting a line into words with columns,
// the checks every line of those files passes first (length, text, word length), and exact
// number and hash formatting.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace jostle {

// Limits on a line of a text file: a level, a scenario, an input script (README, "Limits").
// A longer line or word is refused with its line and column, before it is read further.
inline constexpr std::size_t kMaxLineBytes = 65536;
inline constexpr std::size_t kMaxWordBytes = 128;

// The whole file at `path` (a level, a scenario, a script). Throws InputError naming the path
// and `what` it should be ("the scenario file") with the reason: it does not exist, it is a
// folder, it cannot be read.
std::string read_text_file(const std::string& path, const std::string& what);

// `text` without a leading UTF-8 byte order mark (EF BB BF): the text formats accept one.
std::string_view skip_utf8_bom(std::string_view text);

// Checks one line of a text file (without its '\n'; a '\r' before it is a CRLF line end and
// is allowed) and throws InputError naming source:line_number:column when it is longer than
// kMaxLineBytes, holds a control character (anything below 0x20 but tab, a '\r' inside the
// line, 0x7f), bytes that are not UTF-8 (binary garbage) or a byte order mark (U+FEFF: only
// the file's first bytes may be one, and skip_utf8_bom takes that), or a word (before any '#'
// comment) longer than kMaxWordBytes.
void check_text_line(std::string_view line, const std::string& source, int line_number);

// Length of the well-formed UTF-8 sequence that starts at s[i] (1 for ASCII), or 0 when it is
// not one: a stray continuation byte, an overlong form, a surrogate, beyond U+10FFFF, cut short.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i);

// A word of a line and its 1-based column, for error messages.
struct Word {
    std::string_view text;
    int column = 0;
};

// The whitespace-separated words of `line` (spaces, tabs, a trailing '\r'); a '#' anywhere
// starts a comment that runs to the end of the line.
std::vector<Word> split_words(std::string_view line);

// All of `text` as a number, in std::from_chars' form: an optional '-', digits with an optional
// '.', an optional exponent ("-12.5", "1e-3"; no '+', no spaces, no hex), or "inf" and "nan",
// which callers refuse or take as they choose. A number too small for the type (1e-320 as a
// float) rounds to the nearest value the type has, as strtof and strtod round it: 0, -0 or a
// denormal; it is in range, only finer than the type. A number too large for the type (1e39
// as a float) and anything that is not a number give nullopt.
std::optional<float> parse_float(std::string_view text);
std::optional<double> parse_double(std::string_view text);

// The shortest text that reads back as exactly the same value ("104.25", "0.1", "nan").
std::string shortest_text(double v);
std::string shortest_text(float v);

// 16 lowercase hex digits, zero-padded: state hashes and file fingerprints.
std::string hex16(std::uint64_t v);

// A count and its noun for messages, plural but for 1: "1 scenario", "0 scenarios",
// "30 ticks" (`noun` is the singular; the plural adds an 's').
std::string counted(std::int64_t n, std::string_view noun);

}  // namespace jostle
