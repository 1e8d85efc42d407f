// main.cpp: the `jostle` command line. Each subcommand is one row of kCommands (name, one-line
// summary, help text, entry point); a new subcommand is a new row. Exit status: 0 ok,
// 1 a check failed, 2 bad input or usage.
#include <exception>
#include <iostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "imgdiff.h"
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
};

constexpr Command kCommands[] = {
    {"query", "answer collision queries: JSON lines on stdin, one JSON result per line on stdout",
     jostle::query_help,
     [](std::span<const std::string_view> args) { return jostle::query_command(args, std::cin, std::cout, std::cerr); }},
    {"play", "replay a scenario: fast-forward, or rendering frames, a contact sheet, an animation, a trace",
     jostle::play_help,
     [](std::span<const std::string_view> args) { return jostle::play_command(args, std::cout, std::cerr); }},
    {"record", "write a scenario from an input script, verified by replaying what it wrote",
     jostle::record_help,
     [](std::span<const std::string_view> args) { return jostle::record_command(args, std::cin, std::cout, std::cerr); }},
    {"check", "replay scenarios and compare them with their goldens (trace, expectations, screenshots)",
     jostle::check_help,
     [](std::span<const std::string_view> args) { return jostle::check_command(args, std::cout, std::cerr); }},
    {"imgdiff", "compare two PNG images within a tolerance (exit 0 match, 1 differ), optionally writing a diff picture",
     jostle::imgdiff_help,
     [](std::span<const std::string_view> args) { return jostle::imgdiff_command(args, std::cout, std::cerr); }},
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
           "exit status: 0 ok, 1 a check failed, 2 bad input or usage.\n";
}

int usage_error(const std::string& message) {
    std::cerr << "jostle: " << message << "\nRun 'jostle --help' for usage.\n";
    return 2;
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
            return 0;
        }
        if (rest.size() > 1) return usage_error("help takes at most one command name");
        if (rest.front() == "help") {
            print_usage(std::cout);
            return 0;
        }
        const Command* command = find_command(rest.front());
        if (command == nullptr) {
            return usage_error("unknown command '" + std::string(rest.front()) + "' (expected " +
                               command_names() + ")");
        }
        std::cout << command->help();
        return 0;
    }
    const Command* command = find_command(name);
    if (command == nullptr) {
        const std::string what = name.starts_with('-') ? "unknown option '" : "unknown command '";
        return usage_error(what + std::string(name) + "' (expected " + command_names() + ")");
    }
    if (!rest.empty() && is_help_flag(rest.front())) {
        std::cout << command->help();
        return 0;
    }
    return command->run(rest);
}

}  // namespace

int main(int argc, char** argv) {
    std::ios::sync_with_stdio(false);
    const std::vector<std::string_view> args(argv + (argc > 0 ? 1 : 0), argv + argc);
    try {
        return run(args);
    } catch (const std::exception& e) {
        std::cerr << "jostle: " << e.what() << '\n';
        return 2;
    }
}
