// text_test.cpp: the shared line tokenizer (words, columns, '#' comments), the checks every
// text line passes (length, text not binary, word length, a BOM) and the exact number and hash
// formatting every file format relies on.
#include "jostle/core/text.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <random>

#include "jostle/core/error.h"

namespace jostle {
namespace {

TEST(SplitWords, WordsWithColumnsUntilAComment) {
    const std::vector<Word> words = split_words("  at 5\tscreenshot#note here\r");
    ASSERT_EQ(words.size(), 3u);
    EXPECT_EQ(words[0].text, "at");
    EXPECT_EQ(words[0].column, 3);
    EXPECT_EQ(words[1].text, "5");
    EXPECT_EQ(words[1].column, 6);
    EXPECT_EQ(words[2].text, "screenshot");
    EXPECT_EQ(words[2].column, 8);
    EXPECT_TRUE(split_words("# only a comment").empty());
    EXPECT_TRUE(split_words(" \t\r").empty());
}

TEST(ShortestText, ReadsBackAsTheSameValue) {
    EXPECT_EQ(shortest_text(104.25f), "104.25");
    EXPECT_EQ(shortest_text(0.1f), "0.1");  // the float, not its double expansion
    EXPECT_EQ(shortest_text(0.1), "0.1");
    std::mt19937 rng(5);
    for (int i = 0; i < 10000; ++i) {
        const float v = std::ldexp(static_cast<float>(rng()) / 4294967296.0f - 0.5f, static_cast<int>(rng() % 60) - 30);
        const std::string text = shortest_text(v);
        float back = 0.0f;
        std::from_chars(text.data(), text.data() + text.size(), back);
        ASSERT_EQ(back, v) << text;
    }
}

// The message check_text_line throws for `line` as line 7 of "f.txt", or "ok".
std::string line_error(std::string_view line) {
    try {
        check_text_line(line, "f.txt", 7);
    } catch (const InputError& e) {
        return e.what();
    }
    return "ok";
}

TEST(CheckTextLine, TextOfASaneLengthPasses) {
    EXPECT_EQ(line_error(""), "ok");
    EXPECT_EQ(line_error("0-29 right\tfire  # a comment"), "ok");
    EXPECT_EQ(line_error("wall w 0 0 1 1\r"), "ok");  // a CRLF line end
    EXPECT_EQ(line_error("pickup caf\xc3\xa9 1 2 3 # \xe2\x82\xac \xf0\x9f\x98\x80"), "ok");  // UTF-8
    EXPECT_EQ(line_error(std::string(kMaxLineBytes, ' ')), "ok");
    EXPECT_EQ(line_error(std::string(kMaxWordBytes, 'w')), "ok");
    EXPECT_EQ(line_error("# " + std::string(1000, 'w')), "ok");  // words in a comment are not words
}

TEST(CheckTextLine, BinaryLongAndOddLinesAreRefusedWithTheirColumn) {
    EXPECT_EQ(line_error(std::string(kMaxLineBytes + 1, ' ')),
              "f.txt:7: the line is 65537 bytes long; a line is at most 65536 bytes");
    EXPECT_EQ(line_error("ab " + std::string(kMaxWordBytes + 1, 'w')), "f.txt:7:4: a word of 129 bytes; a word is at most 128 bytes");
    EXPECT_EQ(line_error(std::string("0 le\0ft", 8)), "f.txt:7:5: expected text, got the control character 0x00 (is this a binary file?)");
    EXPECT_EQ(line_error("a\x7f"), "f.txt:7:2: expected text, got the control character 0x7f (is this a binary file?)");
    EXPECT_EQ(line_error("a\rb"), "f.txt:7:2: expected text, got a carriage return (0x0d) inside the line (lines end with LF or CRLF)");
    EXPECT_EQ(line_error("\x89PNG"), "f.txt:7:1: expected text, got the byte 0x89 (not UTF-8: is this a binary file?)");
    EXPECT_EQ(line_error("ab\xc3"), "f.txt:7:3: expected text, got the byte 0xc3 (not UTF-8: is this a binary file?)");     // cut short
    EXPECT_EQ(line_error("\xc0\xaf"), "f.txt:7:1: expected text, got the byte 0xc0 (not UTF-8: is this a binary file?)");   // overlong
    EXPECT_EQ(line_error("\xed\xa0\x80"), "f.txt:7:1: expected text, got the byte 0xed (not UTF-8: is this a binary file?)");  // a surrogate
}

TEST(SkipUtf8Bom, OnlyALeadingMark) {
    EXPECT_EQ(skip_utf8_bom("\xef\xbb\xbfjostle-level 1\n"), "jostle-level 1\n");
    EXPECT_EQ(skip_utf8_bom("jostle-level 1\n"), "jostle-level 1\n");
    EXPECT_EQ(skip_utf8_bom("\xef\xbb"), "\xef\xbb");
    EXPECT_EQ(skip_utf8_bom(""), "");
}

TEST(Hex16, SixteenLowercaseDigitsZeroPadded) {
    EXPECT_EQ(hex16(0), "0000000000000000");
    EXPECT_EQ(hex16(0xabcdef0123456789ull), "abcdef0123456789");
    EXPECT_EQ(hex16(255), "00000000000000ff");
}

}  // namespace
}  // namespace jostle
