// text.cpp: words of a line, the checks every text line passes, shortest round-trip
// numbers, hex hashes.
#include "jostle/core/text.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <type_traits>

#include "jostle/core/error.h"

namespace jostle {
namespace {

// parse_float and parse_double. std::from_chars reads the number, and is the judge of its form;
// it reports a value beyond the type's range both ways, too large and too small (what rounds to
// 0), as out of range. The second is a value like any other, rounded: strtof/strtod give it,
// correctly rounded (jostle never calls setlocale, so they read '.' as the C locale does).
template <class T>
std::optional<T> parse_real(std::string_view text) {
    T value{};
    const char* const last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(text.data(), last, value);
    if (text.empty() || end != last) return std::nullopt;
    if (ec == std::errc()) return value;
    if (ec != std::errc::result_out_of_range) return std::nullopt;
    const std::string copy(text);  // strto* read up to a NUL
    char* stop = nullptr;
    T rounded{};
    if constexpr (std::is_same_v<T, float>) {
        rounded = std::strtof(copy.c_str(), &stop);
    } else {
        rounded = std::strtod(copy.c_str(), &stop);
    }
    if (stop != copy.c_str() + copy.size() || std::isinf(rounded)) return std::nullopt;  // too large
    return rounded;
}

}  // namespace

std::optional<float> parse_float(std::string_view text) { return parse_real<float>(text); }
std::optional<double> parse_double(std::string_view text) { return parse_real<double>(text); }

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

std::string read_text_file(const std::string& path, const std::string& what) {
    const auto fail = [&](const std::string& why) { throw InputError(SourceLocation{path, 0, 0}, why); };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        const int e = errno;
        fail("cannot open " + what + ": " + std::strerror(e));
    }
    struct stat info {};
    if (::fstat(fd, &info) == 0 && S_ISDIR(info.st_mode)) {
        ::close(fd);
        fail("is a folder, expected " + what);
    }
    std::string text;
    char buffer[65536];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n > 0) {
            text.append(buffer, static_cast<std::size_t>(n));
        } else if (n == 0) {
            break;
        } else if (errno != EINTR) {
            const int e = errno;
            ::close(fd);
            fail("cannot read " + what + ": " + std::strerror(e));
        }
    }
    ::close(fd);
    return text;
}

std::string_view skip_utf8_bom(std::string_view text) {
    return text.starts_with("\xef\xbb\xbf") ? text.substr(3) : text;
}

std::size_t utf8_sequence_length(std::string_view line, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(line[k]); };
    const unsigned char lead = byte(i);
    if (lead < 0x80) return 1;
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;  // the allowed range of the second byte
    if (lead >= 0xC2 && lead <= 0xDF) {
        length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
        length = 3;
        if (lead == 0xE0) low = 0xA0;   // no overlong forms
        if (lead == 0xED) high = 0x9F;  // no surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
        length = 4;
        if (lead == 0xF0) low = 0x90;
        if (lead == 0xF4) high = 0x8F;  // nothing above U+10FFFF
    } else {
        return 0;
    }
    if (i + length > line.size() || byte(i + 1) < low || byte(i + 1) > high) return 0;
    for (std::size_t k = 2; k < length; ++k) {
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    }
    return length;
}

namespace {

std::string hex_byte(unsigned char c) {
    char buffer[8];
    std::snprintf(buffer, sizeof buffer, "0x%02x", c);
    return buffer;
}

}  // namespace

void check_text_line(std::string_view line, const std::string& source, int line_number) {
    const auto fail = [&](std::size_t column, const std::string& what) {
        throw InputError(SourceLocation{source, line_number, static_cast<int>(column)}, what);
    };
    if (line.size() > kMaxLineBytes) {
        fail(0, "the line is " + std::to_string(line.size()) + " bytes long; a line is at most " +
                    std::to_string(kMaxLineBytes) + " bytes");
    }
    if (line.ends_with('\r')) line.remove_suffix(1);  // a CRLF line end
    for (std::size_t i = 0; i < line.size();) {
        const auto c = static_cast<unsigned char>(line[i]);
        if (c == '\r') fail(i + 1, "expected text, got a carriage return (0x0d) inside the line (lines end with LF or CRLF)");
        if ((c < 0x20 && c != '\t') || c == 0x7f) {
            fail(i + 1, "expected text, got the control character " + hex_byte(c) + " (is this a binary file?)");
        }
        const std::size_t length = utf8_sequence_length(line, i);
        if (length == 0) fail(i + 1, "expected text, got the byte " + hex_byte(c) + " (not UTF-8: is this a binary file?)");
        // U+FEFF (EF BB BF) is invisible: in a word it would make "wait" an unknown step that
        // reads as "wait". skip_utf8_bom takes the one at the start of the file.
        if (line.substr(i, 3) == "\xef\xbb\xbf") {
            fail(i + 1, "expected text, got a byte order mark (U+FEFF): it is only allowed at the start of the file");
        }
        i += length;
    }
    for (const Word& word : split_words(line)) {
        if (word.text.size() > kMaxWordBytes) {
            fail(static_cast<std::size_t>(word.column), "a word of " + std::to_string(word.text.size()) +
                                                            " bytes; a word is at most " + std::to_string(kMaxWordBytes) + " bytes");
        }
    }
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

std::string counted(std::int64_t n, std::string_view noun) {
    return std::to_string(n) + " " + std::string(noun) + (n == 1 ? "" : "s");
}

}  // namespace jostle
