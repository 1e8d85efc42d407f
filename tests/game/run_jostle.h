// run_jostle.h: runs the built jostle program (JOSTLE_BINARY), or another program, for the
// end-to-end tests, with stdin from a file and an optional working folder, collecting its exit
// status, stdout and stderr (both pipes polled, so neither can fill up and block the child).
// The interruption tests also have it send a signal (SIGINT unless told) a given time after
// the start; the hostile-input tests give it a file-size limit (a full disk: writes beyond it
// fail with EFBIG).
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern char** environ;

namespace jostle::test {

struct RunResult {
    int status = -1;  // exit status, or -1 if it did not exit normally
    int term_signal = 0;     // the signal that ended it, if one did
    bool signalled = false;  // the signal asked for was sent before the program ended
    std::string out;
    std::string err;
};

// Runs `program` (a path) with `args`. With file_size_limit >= 0 the program runs under that
// RLIMIT_FSIZE with SIGXFSZ ignored, so a write past the limit fails with EFBIG as on a full disk.
inline RunResult run_program(const std::string& program, const std::vector<std::string>& args,
                             const std::string& stdin_path = "/dev/null", const std::string& cwd = "",
                             int signal_after_ms = -1, long long file_size_limit = -1, int signal_number = SIGINT) {
    RunResult result;
    int out_pipe[2];
    int err_pipe[2];
    if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0) {
        ADD_FAILURE() << "pipe failed";
        return result;
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    posix_spawn_file_actions_addopen(&actions, 0, stdin_path.c_str(), O_RDONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
    for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]}) posix_spawn_file_actions_addclose(&actions, fd);

    std::vector<std::string> argv_strings = {program};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& s : argv_strings) argv.push_back(s.data());
    argv.push_back(nullptr);

    // The child inherits the limit and the ignored signal; this process has them only while
    // it spawns (it writes nothing meanwhile).
    rlimit saved_limit{};
    void (*saved_handler)(int) = SIG_DFL;
    if (file_size_limit >= 0) {
        getrlimit(RLIMIT_FSIZE, &saved_limit);
        rlimit limit = saved_limit;
        limit.rlim_cur = static_cast<rlim_t>(file_size_limit);
        saved_handler = signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &limit) != 0) ADD_FAILURE() << "setrlimit(RLIMIT_FSIZE) failed";
    }
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
    if (file_size_limit >= 0) {
        setrlimit(RLIMIT_FSIZE, &saved_limit);
        signal(SIGXFSZ, saved_handler);
    }
    posix_spawn_file_actions_destroy(&actions);
    close(out_pipe[1]);
    close(err_pipe[1]);
    if (spawned != 0) {
        close(out_pipe[0]);
        close(err_pipe[0]);
        ADD_FAILURE() << "cannot start " << program << ": " << std::strerror(spawned);
        return result;
    }
    pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
    std::string* sinks[2] = {&result.out, &result.err};
    int open_count = 2;
    const auto started = std::chrono::steady_clock::now();
    while (open_count > 0) {
        int timeout = -1;
        if (signal_after_ms >= 0 && !result.signalled) {
            const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - started);
            timeout = std::max(0, signal_after_ms - static_cast<int>(elapsed.count()));
            if (timeout == 0) {
                kill(pid, signal_number);
                result.signalled = true;
                timeout = -1;
            }
        }
        const int ready = poll(fds, 2, timeout);
        if (ready < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (ready == 0) continue;
        for (int i = 0; i < 2; ++i) {
            if (fds[i].fd < 0 || fds[i].revents == 0) continue;
            char buffer[4096];
            const ssize_t n = read(fds[i].fd, buffer, sizeof buffer);
            if (n > 0) {
                sinks[i]->append(buffer, static_cast<std::size_t>(n));
            } else if (n == 0 || errno != EINTR) {
                close(fds[i].fd);
                fds[i].fd = -1;
                --open_count;
            }
        }
    }
    for (pollfd& f : fds) {
        if (f.fd >= 0) close(f.fd);
    }
    int wait_status = 0;
    while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
    }
    result.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
    result.term_signal = WIFSIGNALED(wait_status) ? WTERMSIG(wait_status) : 0;
    return result;
}

// Runs the built jostle program.
inline RunResult run_jostle_binary(const std::vector<std::string>& args, const std::string& stdin_path = "/dev/null",
                                   const std::string& cwd = "", int signal_after_ms = -1,
                                   long long file_size_limit = -1, int signal_number = SIGINT) {
    return run_program(JOSTLE_BINARY, args, stdin_path, cwd, signal_after_ms, file_size_limit, signal_number);
}

}  // namespace jostle::test
