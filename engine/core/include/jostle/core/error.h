// Errors and assertions. Bad input from a file or the command line is an InputError
// carrying where it came from ("level.json:12:5: ..."); a broken engine invariant is an
// assertion failure (JOSTLE_ASSERT), which stays on in every build type.
#pragma once

#include <stdexcept>
#include <string>

namespace jostle {

// Where a piece of input came from: a file name (or "<stdin>", "line 3"), line, column.
// Line and column are 1-based; 0 means "not known" and is left out of the message.
struct SourceLocation {
    std::string source;
    int line = 0;
    int column = 0;
};

// "source:line:column: " with the unknown parts left out.
std::string format_location(const SourceLocation& where);

// Bad input: the message already names where, so callers print what() as it is.
class InputError : public std::runtime_error {
public:
    InputError(const SourceLocation& where, const std::string& what);
    explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

[[noreturn]] void assertion_failed(const char* expr, const char* file, int line, const char* msg);

}  // namespace jostle

#define JOSTLE_ASSERT(expr, msg) \
    ((expr) ? static_cast<void>(0) : ::jostle::assertion_failed(#expr, __FILE__, __LINE__, (msg)))

// Checked in Debug builds only: invariants a hot path relies on instead of re-checking them.
#ifdef NDEBUG
#define JOSTLE_DEBUG_ASSERT(expr, msg) static_cast<void>(0)
#else
#define JOSTLE_DEBUG_ASSERT(expr, msg) JOSTLE_ASSERT(expr, msg)
#endif
