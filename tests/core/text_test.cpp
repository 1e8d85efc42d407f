// text_test.cpp: the shared line tokenizer (words, columns, '#' comments) and the exact
// number and hash formatting every file format relies on.
#include "jostle/core/text.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <random>

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

TEST(Hex16, SixteenLowercaseDigitsZeroPadded) {
    EXPECT_EQ(hex16(0), "0000000000000000");
    EXPECT_EQ(hex16(0xabcdef0123456789ull), "abcdef0123456789");
    EXPECT_EQ(hex16(255), "00000000000000ff");
}

}  // namespace
}  // namespace jostle
