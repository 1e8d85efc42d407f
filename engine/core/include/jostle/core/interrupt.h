// jostle/core/interrupt.h: Ctrl-C, SIGTERM and SIGHUP (the terminal closing) as a request to
// stop at the next safe point.
//
// While an InterruptHandler is alive, SIGINT, SIGTERM and SIGHUP only record the signal; a second
// signal kills the process at once (the default action), for when stopping takes too long.
// Long loops call throw_if_interrupted() at points where stopping leaves nothing half done
// (between ticks, between files); it throws Interrupted, and unwinding removes every unfinished
// temporary file (AtomicFile), so each output file is either complete or absent. The program
// then exits with 128 + the signal number, as a shell does.
#pragma once

#include <stdexcept>

namespace jostle {

// Thrown by throw_if_interrupted. Not an InputError: the input was fine.
class Interrupted : public std::runtime_error {
public:
    explicit Interrupted(int signal);
    int signal() const noexcept { return signal_; }
    int exit_status() const noexcept { return 128 + signal_; }

private:
    int signal_;
};

// Installs the handlers for SIGINT, SIGTERM and SIGHUP; the destructor restores the previous ones.
// One at a time (they are process-wide).
class InterruptHandler {
public:
    InterruptHandler();
    ~InterruptHandler();
    InterruptHandler(const InterruptHandler&) = delete;
    InterruptHandler& operator=(const InterruptHandler&) = delete;
};

// The signal received since the handler was installed, or 0. Safe from any thread.
int interrupt_signal() noexcept;

// Throws Interrupted when a signal has been received.
void throw_if_interrupted();

}  // namespace jostle
