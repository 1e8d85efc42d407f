// interrupt_test.cpp: Ctrl-C and SIGTERM as a request to stop (jostle/core/interrupt.h): the
// handler records the signal instead of dying, throw_if_interrupted turns it into Interrupted
// with the shell's exit status, a second signal kills at once, and the previous handlers come
// back when the handler goes.
#include "jostle/core/interrupt.h"

#include <csignal>
#include <cstdlib>

#include <gtest/gtest.h>

namespace jostle {
namespace {

TEST(Interrupt, NothingHappensWithoutASignal) {
    const InterruptHandler handler;
    EXPECT_EQ(interrupt_signal(), 0);
    EXPECT_NO_THROW(throw_if_interrupted());
}

TEST(Interrupt, SigintIsRecordedAndThrownAsInterrupted) {
    const InterruptHandler handler;
    std::raise(SIGINT);  // would end the test binary without the handler
    EXPECT_EQ(interrupt_signal(), SIGINT);
    try {
        throw_if_interrupted();
        FAIL() << "expected Interrupted";
    } catch (const Interrupted& e) {
        EXPECT_EQ(e.signal(), SIGINT);
        EXPECT_EQ(e.exit_status(), 130);
        EXPECT_STREQ(e.what(), "interrupted by SIGINT");
    }
    EXPECT_THROW(throw_if_interrupted(), Interrupted) << "the request stays until the handler goes";
}

TEST(Interrupt, SigtermToo) {
    const InterruptHandler handler;
    std::raise(SIGTERM);
    EXPECT_EQ(interrupt_signal(), SIGTERM);
    try {
        throw_if_interrupted();
        FAIL() << "expected Interrupted";
    } catch (const Interrupted& e) {
        EXPECT_EQ(e.exit_status(), 143);
        EXPECT_STREQ(e.what(), "interrupted by SIGTERM");
    }
}

TEST(Interrupt, TheFirstSignalIsTheOneReported) {
    const InterruptHandler handler;
    std::raise(SIGTERM);
    EXPECT_EQ(interrupt_signal(), SIGTERM);
    // A second signal would kill (tested below); the flag keeps the first.
}

TEST(InterruptDeathTest, ASecondSignalKillsAtOnce) {
    EXPECT_EXIT(
        {
            const InterruptHandler handler;
            std::raise(SIGINT);
            std::raise(SIGINT);
            std::_Exit(0);  // not reached
        },
        ::testing::KilledBySignal(SIGINT), "");
}

std::sig_atomic_t g_previous_handler_calls = 0;
extern "C" void count_signal(int) { g_previous_handler_calls = g_previous_handler_calls + 1; }

TEST(Interrupt, ThePreviousHandlersComeBackAndTheFlagIsCleared) {
    const auto old_int = std::signal(SIGINT, count_signal);
    const auto old_term = std::signal(SIGTERM, count_signal);
    {
        const InterruptHandler handler;
        std::raise(SIGINT);
        EXPECT_EQ(g_previous_handler_calls, 0);
    }
    EXPECT_EQ(interrupt_signal(), 0) << "a later handler starts afresh";
    std::raise(SIGINT);
    std::raise(SIGTERM);
    EXPECT_EQ(g_previous_handler_calls, 2);
    std::signal(SIGINT, old_int);
    std::signal(SIGTERM, old_term);
}

}  // namespace
}  // namespace jostle
