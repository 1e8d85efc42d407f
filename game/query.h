// game/query.h: `jostle query`, the collision module as a line protocol: one JSON query per
// input line, one JSON result per output line. query_help() is the protocol's manual; the
// parsing is here so tests can call it without starting a process.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <string_view>

namespace jostle {

// A longer input line is answered with an error (and read no further than this).
inline constexpr std::size_t kMaxQueryLineBytes = std::size_t{1} << 20;

// The text of `jostle query --help`: every op, every shape, the output, errors, exit status.
std::string_view query_help();

// Answers one input line (without its '\n'). Returns the output line without '\n': the result
// object, or {"error":"line N: ..."} with *ok set to false. A blank line (nothing but spaces,
// tabs and '\r') has no answer: returns "" with *ok true. ok may be null.
std::string run_query_line(std::string_view line, std::int64_t line_number, bool* ok);

// Answers every line of `in` until its end, writing each answer and '\n' to `out` and flushing
// after each one (so a program can talk to `jostle query` through a pipe, line by line).
// Returns the exit status: 0 if every line was answered, 2 if some line was an error or the
// output could not be written. Throws InputError ("standard input: cannot read: Is a
// directory") when reading `in` fails, after answering the lines before.
int run_query(std::istream& in, std::ostream& out);

// `jostle query`: the command line entry point; args are the arguments after "query" (there
// are none; `--help` is handled by the dispatcher). Returns the exit status.
int query_command(std::span<const std::string_view> args, std::istream& in, std::ostream& out,
                  std::ostream& err);

// The output's JSON building blocks (exposed for tests).
// A float in the shortest form that reads back as the same float (std::to_chars): 0.5, 2,
// 1e-05, 3.4028235e+38; -0 is written as 0, and NaN or infinity as null.
void append_json_number(std::string& out, float value);
// A quoted JSON string: '"', '\\' and control characters escaped; bytes that are not valid
// UTF-8 become \ufffd, so the output is always valid JSON.
void append_json_string(std::string& out, std::string_view text);

}  // namespace jostle
