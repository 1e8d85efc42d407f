// game/imgdiff.h: `jostle imgdiff A.png B.png`: compares two images with a tolerance and can
// write a diff picture. Here rather than in main.cpp so tests can call it in-process.
#pragma once

#include <iosfwd>
#include <span>
#include <string_view>

namespace jostle {

std::string_view imgdiff_help();

// args: the arguments after "imgdiff". Returns 0 when the images match within the tolerance,
// 1 when they do not, 2 on bad usage or unreadable images.
int imgdiff_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err);

}  // namespace jostle
