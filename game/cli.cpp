// The command line's shared option rules (cli.h).
#include "cli.h"

#include <algorithm>
#include <charconv>

namespace jostle::game {

namespace {

// "--anything", or a dash and one letter ("-o", "-h"): the shapes options take. Anything else
// that begins with '-' ("-", "-1", "-.5", "-inf") is a value, for the option's own check.
bool looks_like_option(std::string_view v) {
    if (v.size() > 2 && v.starts_with("--")) return true;
    if (v == "--") return true;
    return v.size() == 2 && v[0] == '-' && ((v[1] >= 'a' && v[1] <= 'z') || (v[1] >= 'A' && v[1] <= 'Z'));
}

}  // namespace

std::optional<std::uint64_t> parse_whole(std::string_view text, std::uint64_t lo, std::uint64_t hi) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);  // no sign accepted
    if (ec != std::errc{} || end != text.data() + text.size() || v < lo || v > hi) return std::nullopt;
    return v;
}

std::string whole_number_error(std::string_view name, std::uint64_t lo, std::uint64_t hi, std::string_view got) {
    std::string out = std::string(name) + ": expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                      ", got '" + std::string(got) + "'";
    // '+3' or '-0' where 3 or 0 would do; not '+x', '+999' past the range, or '-5'.
    const bool sign = got.starts_with('+') || (got.starts_with('-') && got.find_first_not_of('0', 1) == std::string_view::npos);
    if (sign && parse_whole(got.substr(1), lo, hi)) out += " (a number here is written without a sign)";
    return out;
}

std::string option_value(std::span<const std::string_view> args, std::size_t& i, std::string_view name,
                         std::string_view& value) {
    if (i + 1 >= args.size() || args[i + 1].empty()) return std::string(name) + " needs a value";
    const std::string_view v = args[i + 1];
    if (looks_like_option(v)) {
        return std::string(name) + " needs a value, got the option '" + std::string(v) +
               "' (a path that begins with '-' is written ./" + std::string(v) + ")";
    }
    value = v;
    ++i;
    return "";
}

std::string OnceOnly::take(std::string_view name) {
    if (std::find(seen_.begin(), seen_.end(), name) != seen_.end()) return std::string(name) + " given twice";
    seen_.emplace_back(name);
    return "";
}

}  // namespace jostle::game
