// game/record.h: `jostle record`: writes a scenario of the arena game from an input script,
// then reads it back and replays it to prove the file reproduces the run.
#pragma once

#include <iosfwd>
#include <span>
#include <string_view>

namespace jostle {

std::string_view record_help();

// args: the arguments after "record"; `in` is read when there is no --script. Returns 0 when
// the scenario was written and verified, 1 when the read-back replay differs (nothing is
// written), 2 on bad usage or bad input.
int record_command(std::span<const std::string_view> args, std::istream& in, std::ostream& out, std::ostream& err);

}  // namespace jostle
