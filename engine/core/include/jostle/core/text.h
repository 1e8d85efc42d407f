// jostle/core/text.h: the small text helpers shared by every line-oriented file format
// (scenarios, input scripts, levels, traces): splitting a line into words with columns,
// and exact number and hash formatting.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace jostle {

// A word of a line and its 1-based column, for error messages.
struct Word {
    std::string_view text;
    int column = 0;
};

// The whitespace-separated words of `line` (spaces, tabs, a trailing '\r'); a '#' anywhere
// starts a comment that runs to the end of the line.
std::vector<Word> split_words(std::string_view line);

// The shortest text that reads back as exactly the same value ("104.25", "0.1", "nan").
std::string shortest_text(double v);
std::string shortest_text(float v);

// 16 lowercase hex digits, zero-padded: state hashes and file fingerprints.
std::string hex16(std::uint64_t v);

}  // namespace jostle
