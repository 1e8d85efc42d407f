// interrupt.cpp: the signal handler records the first signal; a second one restores the
// default action and raises it again (both async-signal-safe), so an impatient second Ctrl-C
// still ends the process.
#include "jostle/core/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

#include "jostle/core/error.h"

namespace jostle {
namespace {

std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs a lock-free flag");

extern "C" void on_signal(int sig) {
    int expected = 0;
    if (!g_signal.compare_exchange_strong(expected, sig)) {
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
}

struct sigaction g_previous_int, g_previous_term, g_previous_hup;
bool g_installed = false;

std::string signal_name(int sig) {
    if (sig == SIGINT) return "SIGINT";
    if (sig == SIGTERM) return "SIGTERM";
    if (sig == SIGHUP) return "SIGHUP";
    return "signal " + std::to_string(sig);
}

}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error("interrupted by " + signal_name(signal)), signal_(signal) {}

InterruptHandler::InterruptHandler() {
    JOSTLE_ASSERT(!g_installed, "one InterruptHandler at a time");
    g_signal.store(0);
    struct sigaction action;
    std::memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    // No SA_RESTART: a read blocked on a terminal (a script typed on stdin) returns at once.
    action.sa_flags = 0;
    sigaction(SIGINT, &action, &g_previous_int);
    sigaction(SIGTERM, &action, &g_previous_term);
    // The terminal closing (SIGHUP) stops a run as cleanly as Ctrl-C does, unless it is
    // ignored (nohup: the run is to outlive the terminal).
    sigaction(SIGHUP, nullptr, &g_previous_hup);
    if (g_previous_hup.sa_handler != SIG_IGN) sigaction(SIGHUP, &action, nullptr);
    g_installed = true;
}

InterruptHandler::~InterruptHandler() {
    sigaction(SIGINT, &g_previous_int, nullptr);
    sigaction(SIGTERM, &g_previous_term, nullptr);
    sigaction(SIGHUP, &g_previous_hup, nullptr);
    g_installed = false;
    g_signal.store(0);  // a later run in this process starts afresh
}

int interrupt_signal() noexcept { return g_signal.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
    if (const int sig = interrupt_signal(); sig != 0) throw Interrupted(sig);
}

}  // namespace jostle
