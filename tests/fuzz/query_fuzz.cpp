// tests/fuzz/query_fuzz.cpp: fuzzes `jostle query` (game/query.cpp) through run_query, the
// function the command line calls on stdin: the input is the whole stream of JSON lines. Every
// non-blank line must get exactly one answer, every answer must be valid JSON (an object), and
// the exit status must be 0 or 2.
#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "query.h"

using jostle::fuzz::fuzz_fail;

namespace {

bool blank(std::string_view line) { return line.find_first_not_of(" \t\r") == std::string_view::npos; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::istringstream in(text);
    std::ostringstream out;
    const int status = jostle::run_query(in, out);
    if (status != 0 && status != 2) fuzz_fail("run_query returned " + std::to_string(status));
    std::size_t expected = 0;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find('\n', at);
        if (end == std::string::npos) end = text.size();
        if (!blank(std::string_view(text).substr(at, end - at))) ++expected;
        at = end + 1;
    }
    const std::string answers = out.str();
    std::size_t lines = 0;
    for (std::size_t at = 0; at < answers.size();) {
        const std::size_t end = answers.find('\n', at);
        if (end == std::string::npos) fuzz_fail("the last answer lacks its newline");
        const std::string_view line = std::string_view(answers).substr(at, end - at);
        ++lines;
        if (!nlohmann::json::accept(line)) fuzz_fail("answer " + std::to_string(lines) + " is not JSON: " + std::string(line));
        if (line.empty() || line.front() != '{') fuzz_fail("answer " + std::to_string(lines) + " is not an object: " + std::string(line));
        at = end + 1;
    }
    if (lines != expected) {
        fuzz_fail(std::to_string(expected) + " non-blank input lines but " + std::to_string(lines) + " answers");
    }
    return 0;
}
