// main.cpp: the `jostle` command line. Each subcommand is one row of kCommands (name, one-line
// summary, help text, entry point, whether Ctrl-C stops it cleanly); a new subcommand is a new
// row. Exit status: 0 ok, 1 a check failed, 2 bad input or usage (or standard output could not be
// written), 128 + N stopped by signal N.
#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <span>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "imgdiff.h"
#include "jostle/core/interrupt.h"
#include "check.h"
#include "play.h"
#include "record.h"
#include "query.h"

namespace {

struct Command {
    std::string_view name;
    std::string_view summary;       // one line in `jostle --help`
    std::string_view (*help)();     // the text of `jostle <name> --help`
    int (*run)(std::span<const std::string_view> args);  // args after the name; returns the exit status
    // Long runs that write files take SIGINT and SIGTERM as a request to stop between ticks
    // (jostle/core/interrupt.h). Commands that block reading stdin keep the default: they die.
    bool stops_cleanly;
};

constexpr Command kCommands[] = {
    {"query", "answer collision queries: JSON lines on stdin, one JSON result per line on stdout",
     jostle::query_help,
     [](std::span<const std::string_view> args) { return jostle::query_command(args, std::cin, std::cout, std::cerr); },
     false},
    {"play", "replay a scenario: fast-forward, or rendering frames, a contact sheet, an animation, a trace",
     jostle::play_help,
     [](std::span<const std::string_view> args) { return jostle::play_command(args, std::cout, std::cerr); },
     true},
    {"record", "write a scenario from an input script, verified by replaying what it wrote",
     jostle::record_help,
     [](std::span<const std::string_view> args) { return jostle::record_command(args, std::cin, std::cout, std::cerr); },
     true},
    {"check", "replay scenarios and compare them with their goldens (trace, expectations, screenshots)",
     jostle::check_help,
     [](std::span<const std::string_view> args) { return jostle::check_command(args, std::cout, std::cerr); },
     true},
    {"imgdiff", "compare two PNG images within a tolerance (exit 0 match, 1 differ), optionally writing a diff picture",
     jostle::imgdiff_help,
     [](std::span<const std::string_view> args) { return jostle::imgdiff_command(args, std::cout, std::cerr); },
     false},
};

const Command* find_command(std::string_view name) {
    for (const Command& command : kCommands) {
        if (command.name == name) return &command;
    }
    return nullptr;
}

bool is_help_flag(std::string_view arg) { return arg == "--help" || arg == "-h"; }

std::string command_names() {
    std::string names;
    for (const Command& command : kCommands) {
        names += command.name;
        names += ", ";
    }
    return names + "help";
}

void print_usage(std::ostream& out) {
    out << "usage: jostle <command> [arguments]\n"
           "\n"
           "jostle: a small, exact 2D game engine and its demo game.\n"
           "\n"
           "commands:\n";
    for (const Command& command : kCommands) {
        out << "  " << command.name << std::string(10 - command.name.size(), ' ') << command.summary << '\n';
    }
    out << "  help      show this text, or a command's help: jostle help <command>\n"
           "\n"
           "Run 'jostle <command> --help' for a command's arguments.\n"
           "exit status: 0 ok, 1 a check failed, 2 bad input or usage (or standard output could not be\n"
           "written), 128 + N stopped by signal N\n"
           "(130 Ctrl-C; play, record and check then leave only complete files).\n";
}

int usage_error(const std::string& message) {
    std::cerr << "jostle: " << message << "\nRun 'jostle --help' for usage.\n";
    return 2;
}

// std::cout's buffer, passed through, keeping why a write to it first failed (errno then):
// stdout on a full disk or closed fails during the run (a large write goes straight to the
// descriptor), and checked_stdout says why at the end.
class FailureRecordingBuffer : public std::streambuf {
public:
    explicit FailureRecordingBuffer(std::streambuf* to) : to_(to) {}
    int first_errno() const { return first_errno_; }
    std::streambuf* to() const { return to_; }

protected:
    int_type overflow(int_type c) override {
        if (traits_type::eq_int_type(c, traits_type::eof())) return sync() == 0 ? traits_type::not_eof(c) : traits_type::eof();
        const bool ok = passed([&] { return !traits_type::eq_int_type(to_->sputc(traits_type::to_char_type(c)), traits_type::eof()); });
        return ok ? c : traits_type::eof();
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        std::streamsize written = 0;
        passed([&] { return (written = to_->sputn(s, n)) == n; });
        return written;
    }
    int sync() override { return passed([&] { return to_->pubsync() == 0; }) ? 0 : -1; }

private:
    // Runs a write; on failure keeps the errno it left (the first failure's), else errno is
    // left as it was.
    template <class Write>
    bool passed(Write&& write) {
        const int saved = errno;
        errno = 0;
        const bool ok = write();
        if (!ok && first_errno_ == 0) first_errno_ = errno;
        if (ok || errno == 0) errno = saved;
        return ok;
    }

    std::streambuf* to_;
    int first_errno_ = 0;
};

FailureRecordingBuffer* g_stdout_failures = nullptr;  // main's, while it runs

// A command's status once what it printed has reached standard output: output that could not
// be written (a full disk, a closed descriptor) is an error, exit status 2 (a failed check
// keeps its 1), said even when the command had failed already (query's answers to bad lines
// go to stdout). Files the command wrote are kept: they are complete.
int checked_stdout(std::string_view name, int status) {
    std::cout.flush();
    if (std::cout) return status;
    const int e = g_stdout_failures != nullptr ? g_stdout_failures->first_errno() : 0;
    std::cerr << "jostle " << name << ": standard output: cannot write"
              << (e != 0 ? ": " + std::string(std::strerror(e)) : std::string()) << '\n';
    return status == 0 ? 2 : status;
}

int run(std::span<const std::string_view> args) {
    if (args.empty()) {
        print_usage(std::cerr);
        return 2;
    }
    const std::string_view name = args.front();
    const auto rest = args.subspan(1);
    if (is_help_flag(name) || name == "help") {
        if (rest.empty()) {
            print_usage(std::cout);
            return checked_stdout("help", 0);
        }
        if (rest.size() > 1) return usage_error("help takes at most one command name");
        if (rest.front() == "help") {
            print_usage(std::cout);
            return checked_stdout("help", 0);
        }
        const Command* command = find_command(rest.front());
        if (command == nullptr) {
            return usage_error("unknown command '" + std::string(rest.front()) + "' (expected " +
                               command_names() + ")");
        }
        std::cout << command->help();
        return checked_stdout("help", 0);
    }
    const Command* command = find_command(name);
    if (command == nullptr) {
        const std::string what = name.starts_with('-') ? "unknown option '" : "unknown command '";
        return usage_error(what + std::string(name) + "' (expected " + command_names() + ")");
    }
    if (!rest.empty() && is_help_flag(rest.front())) {
        std::cout << command->help();
        return checked_stdout(name, 0);
    }
    if (!command->stops_cleanly) return checked_stdout(name, command->run(rest));
    const jostle::InterruptHandler handler;
    const int status = command->run(rest);
    // A signal that came while the last files were renamed into place (held back then) still
    // says the run was interrupted, though everything it wrote is complete.
    if (const int sig = jostle::interrupt_signal(); sig != 0) throw jostle::Interrupted(sig);
    return checked_stdout(name, status);
}

}  // namespace

int main(int argc, char** argv) {
    std::ios::sync_with_stdio(false);
    const std::vector<std::string_view> args(argv + (argc > 0 ? 1 : 0), argv + argc);
    FailureRecordingBuffer stdout_failures(std::cout.rdbuf());
    std::cout.rdbuf(&stdout_failures);
    g_stdout_failures = &stdout_failures;
    // std::cout is flushed once more at exit, after main's locals are gone: it gets its own
    // buffer back first, whichever way main returns.
    struct Restore {
        std::streambuf* buffer;
        ~Restore() {
            std::cout.rdbuf(buffer);
            g_stdout_failures = nullptr;
        }
    } restore{stdout_failures.to()};
    try {
        return run(args);
    } catch (const jostle::Interrupted& e) {
        std::cerr << "jostle: " << e.what() << ": stopped; files it finished are complete, unfinished ones were removed\n";
        return e.exit_status();
    } catch (const std::exception& e) {
        std::cerr << "jostle: " << e.what() << '\n';
        return 2;
    }
}
