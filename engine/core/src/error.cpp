// Formatting of input errors and the assertion handler.
#include "jostle/core/error.h"

#include <cstdio>
#include <cstdlib>

namespace jostle {

std::string format_location(const SourceLocation& where) {
    std::string out = where.source;
    if (where.line > 0) {
        if (!out.empty()) out += ':';
        out += std::to_string(where.line);
        if (where.column > 0) out += ':' + std::to_string(where.column);
    }
    if (!out.empty()) out += ": ";
    return out;
}

InputError::InputError(const SourceLocation& where, const std::string& what)
    : std::runtime_error(format_location(where) + what) {}

void assertion_failed(const char* expr, const char* file, int line, const char* msg) {
    std::fprintf(stderr, "%s:%d: jostle assertion failed: %s (%s)\n", file, line, expr, msg);
    std::abort();
}

}  // namespace jostle
