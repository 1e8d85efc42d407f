// game/play.h: `jostle play SCENARIO`: replays a scenario of the arena game, fast-forward or
// rendering frames, a contact sheet, an animation and a trace; prints a summary.
#pragma once

#include <iosfwd>
#include <span>
#include <string_view>

namespace jostle {

std::string_view play_help();

// args: the arguments after "play". Returns 0 when the run's expectations pass, 1 when one
// fails, 2 on bad usage or bad input (the scenario, the level, an unwritable output).
int play_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err);

}  // namespace jostle
