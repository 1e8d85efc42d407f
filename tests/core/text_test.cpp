// text_test.cpp: the shared line tokenizer (words, columns, '#' comments), the checks every
// text line passes (length, text not binary, word length, a BOM), the number parser every text
// format shares and the exact number and hash formatting every file format relies on.
#include "jostle/core/text.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
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

TEST(ParseNumber, WholeWordsInFromCharsForm) {
    EXPECT_EQ(parse_float("-12.5"), -12.5f);
    EXPECT_EQ(parse_double("1e-3"), 1e-3);
    EXPECT_EQ(parse_float("3.4028235e38"), std::numeric_limits<float>::max());
    for (const char* bad : {"", "+1", " 1", "1 ", "1x", "0x10", "--1", "e5", "1e"}) {
        EXPECT_FALSE(parse_float(bad)) << bad;
        EXPECT_FALSE(parse_double(bad)) << bad;
    }
    // inf and nan are numbers to from_chars; the callers refuse them with their own message.
    EXPECT_TRUE(std::isnan(*parse_float("nan")));
    EXPECT_TRUE(std::isinf(*parse_double("-inf")));
}

TEST(ParseNumber, TooSmallRoundsToTheNearestValueTooLargeIsRefused) {
    // Finer than the type: rounded as strtof/strtod round it (0, -0 or a denormal), not refused.
    EXPECT_EQ(parse_float("1e-320"), 0.0f);
    EXPECT_TRUE(std::signbit(*parse_float("-1e-320")));
    EXPECT_EQ(parse_float("1e-50"), 0.0f);
    EXPECT_EQ(parse_float("1e-40"), std::strtof("1e-40", nullptr));  // a denormal, as from_chars gives it
    EXPECT_EQ(parse_float("1e-45"), std::numeric_limits<float>::denorm_min());  // nearest is the least denormal
    EXPECT_EQ(parse_float("7.1e-46"), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(parse_float("7e-46"), 0.0f);  // just under half the least denormal
    EXPECT_EQ(parse_double("1e-320"), std::strtod("1e-320", nullptr));
    EXPECT_EQ(parse_double("1e-330"), 0.0);
    EXPECT_EQ(parse_double("-1e-400"), 0.0);
    EXPECT_EQ(parse_float("0.0000000000000000000000000000000000000000000000000001"), 0.0f);
    // Beyond the type's largest value: refused, both signs.
    for (const char* big : {"1e39", "-1e39", "3.5e38"}) EXPECT_FALSE(parse_float(big)) << big;
    for (const char* big : {"1e309", "-1e400"}) EXPECT_FALSE(parse_double(big)) << big;
    EXPECT_EQ(parse_double("1e39"), 1e39);
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

TEST(CheckTextLine, AByteOrderMarkAfterTheStartOfTheFileIsSaidAtItsColumn) {
    // U+FEFF is invisible: "\xef\xbb\xbfwait" would be an unknown step that reads as "wait".
    const std::string message = ": expected text, got a byte order mark (U+FEFF): it is only allowed at the start of the file";
    EXPECT_EQ(line_error("\xef\xbb\xbfwait 10"), "f.txt:7:1" + message);
    EXPECT_EQ(line_error("hold left\xef\xbb\xbf 3"), "f.txt:7:10" + message);
    EXPECT_EQ(line_error("wait 1 # \xef\xbb\xbf"), "f.txt:7:10" + message);  // in a comment too
    EXPECT_EQ(line_error("\xef\xbb"), "f.txt:7:1: expected text, got the byte 0xef (not UTF-8: is this a binary file?)");
    EXPECT_EQ(line_error("\xef\xbb\xbe \xef\xbf\xbf"), "ok");  // its neighbours U+FEFE and U+FFFF are text
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

TEST(Counted, PluralButForOne) {
    EXPECT_EQ(counted(1, "scenario"), "1 scenario");
    EXPECT_EQ(counted(0, "scenario"), "0 scenarios");
    EXPECT_EQ(counted(2, "tick"), "2 ticks");
    EXPECT_EQ(counted(-1, "tick"), "-1 ticks");
    EXPECT_EQ(counted(2280, "frame"), "2280 frames");
}

}  // namespace
}  // namespace jostle
