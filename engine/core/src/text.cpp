// text.cpp: words of a line, shortest round-trip numbers, hex hashes.
#include "jostle/core/text.h"

#include <charconv>

namespace jostle {

std::vector<Word> split_words(std::string_view line) {
    std::vector<Word> words;
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    std::size_t i = 0;
    while (i < line.size() && line[i] != '#') {
        if (space(line[i])) {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < line.size() && !space(line[i]) && line[i] != '#') ++i;
        words.push_back(Word{line.substr(start, i - start), static_cast<int>(start) + 1});
    }
    return words;
}

namespace {

template <typename T>
std::string shortest(T v) {
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    return ec == std::errc() ? std::string(buffer, end) : std::string("?");
}

}  // namespace

std::string shortest_text(double v) { return shortest(v); }
std::string shortest_text(float v) { return shortest(v); }

std::string hex16(std::uint64_t v) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out(16, '0');
    for (int i = 15; i >= 0; --i) {
        out[static_cast<std::size_t>(i)] = kDigits[v & 15u];
        v >>= 4;
    }
    return out;
}

}  // namespace jostle
