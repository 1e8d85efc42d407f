// The command line's shared rules for options that take a value (play, record, check, imgdiff).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace jostle::game {

// Reads the value of option `name` (args[i]) from args[i + 1] and moves i past it. Returns ""
// and sets `value`, or the usage error: no value, an empty one, or another option in its
// place (`--trace --quiet` would otherwise write a file named --quiet): "--NAME", or a dash
// and one letter. Other values that begin with '-' ("-1", "-inf", "-" for standard input or
// output where the option allows it) are left to the option's own check.
std::string option_value(std::span<const std::string_view> args, std::size_t& i, std::string_view name,
                         std::string_view& value);

// A whole-number option's value: plain digits (no sign, no spaces) for a number from lo to hi,
// all of `text`; nullopt otherwise.
std::optional<std::uint64_t> parse_whole(std::string_view text, std::uint64_t lo, std::uint64_t hi);

// The usage error for a whole-number option: "NAME: expected a whole number from LO to HI, got
// 'V'", and where V has a sign a number in range would not need ('+3', '-0'), the note that
// such numbers are written without one (as in the file formats).
std::string whole_number_error(std::string_view name, std::uint64_t lo, std::uint64_t hi, std::string_view got);

// Options that take a value may be given once: a second one is a usage error rather than the
// last silently winning. Callers name an option by one spelling (record's -o and --out alike).
class OnceOnly {
public:
    // "" the first time, else "NAME given twice".
    std::string take(std::string_view name);

private:
    std::vector<std::string> seen_;
};

}  // namespace jostle::game
