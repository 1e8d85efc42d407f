// game/check.h: `jostle check`: replays scenarios of the arena game and compares them with
// their goldens (jostle/replay/check.h); --update re-blesses them.
#pragma once

#include <iosfwd>
#include <span>
#include <string_view>

namespace jostle {

std::string_view check_help();

// args: the arguments after "check". Returns 0 when every scenario passes (or was updated),
// 1 on a regression, 2 on bad usage or bad input.
int check_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err);

}  // namespace jostle
