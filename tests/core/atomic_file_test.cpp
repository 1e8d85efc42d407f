// atomic_file_test.cpp: AtomicFile leaves either the old file or the whole new one, and
// nothing else: no temporary files, no half-written target.
#include "jostle/core/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <vector>

#include "jostle/core/error.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;
using ::testing::StartsWith;
using test::read_text;

class AtomicFileTest : public ::testing::Test {
protected:
    std::vector<std::string> files() const { return test::file_names(folder_.path()); }
    std::string path(const char* name) const { return folder_.file(name); }
    const test::TempFolder folder_{"jostle_atomic"};
};

TEST_F(AtomicFileTest, CommitReplacesTheTargetWhole) {
    write_file_atomic(path("a.txt"), "old contents");
    {
        AtomicFile file(path("a.txt"));
        file.write("new");
        // Until commit the target is the old file, and the new bytes sit in a temporary file.
        EXPECT_EQ(read_text(path("a.txt")), "old contents");
        EXPECT_EQ(files().size(), 2u);
        EXPECT_THAT(file.temp_path(), StartsWith(path("a.txt") + "."));
        file.commit();
    }
    EXPECT_EQ(read_text(path("a.txt")), "new");
    EXPECT_EQ(files(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFileTest, AReplacedFileKeepsItsPermissions) {
    // Whatever the umask says, a private file stays private and a shared one shared (set-id
    // bits are not carried over to new contents).
    const mode_t umask_before = ::umask(022);
    struct RestoreUmask {
        mode_t mask;
        ~RestoreUmask() { ::umask(mask); }
    } restore{umask_before};
    for (const mode_t mode : {mode_t{0600}, mode_t{0640}, mode_t{0664}, mode_t{0755}}) {
        SCOPED_TRACE(mode);
        write_file_atomic(path("p.txt"), "old");
        ASSERT_EQ(::chmod(path("p.txt").c_str(), mode), 0);
        write_file_atomic(path("p.txt"), "new");
        struct stat st{};
        ASSERT_EQ(::stat(path("p.txt").c_str(), &st), 0);
        EXPECT_EQ(st.st_mode & 07777, mode);
        EXPECT_EQ(read_text(path("p.txt")), "new");
    }
    // A new file takes the umask's default.
    write_file_atomic(path("fresh.txt"), "x");
    struct stat st{};
    ASSERT_EQ(::stat(path("fresh.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode_t{0644});
    write_file_atomic(path("setid.txt"), "old");
    ASSERT_EQ(::chmod(path("setid.txt").c_str(), 04755), 0);
    write_file_atomic(path("setid.txt"), "new");
    ASSERT_EQ(::stat(path("setid.txt").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode_t{0755});
}

TEST_F(AtomicFileTest, WithoutCommitNothingChanges) {
    write_file_atomic(path("a.txt"), "old");
    {
        AtomicFile file(path("a.txt"));
        file.write("half of the ne");
    }
    {
        AtomicFile file(path("b.txt"));
        file.write("never committed");
    }
    EXPECT_EQ(read_text(path("a.txt")), "old");
    EXPECT_EQ(files(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFileTest, SeekPatchesBytesWrittenEarlier) {
    AtomicFile file(path("h.bin"));
    file.write("count=??;data");
    EXPECT_EQ(file.tell(), 13);
    file.seek(6);
    file.write("42");
    file.seek(13);
    file.write(";end");
    file.commit();
    EXPECT_EQ(read_text(path("h.bin")), "count=42;data;end");
}

TEST_F(AtomicFileTest, ErrorsNameTheTargetAndLeaveNothingBehind) {
    const std::string missing = (folder_.path() / "no_such_folder" / "a.txt").string();
    try {
        write_file_atomic(missing, "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(missing + ": cannot write: cannot create a file in "));
    }
    // A folder is refused before anything is written.
    fs::create_directories(folder_.path() / "taken" / "inside");
    try {
        write_file_atomic(path("taken"), "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path("taken") + ": cannot write: it is a folder");
    }
    EXPECT_EQ(files(), std::vector<std::string>{"taken"});
}

// A named pipe stays a pipe: the bytes go through it (the rename would have put a regular
// file in its place, as it did to /dev/null before), and a file patched after it is written
// says why a pipe cannot take it.
TEST_F(AtomicFileTest, APipeIsWrittenInPlaceNotReplaced) {
    const std::string fifo = path("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto reader = std::async(std::launch::async, [&] {
        std::ifstream in(fifo, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    });
    {
        AtomicFile file(fifo);
        EXPECT_TRUE(file.in_place());
        EXPECT_EQ(file.temp_path(), "");
        file.write("through the pipe");
        file.commit();
    }
    EXPECT_EQ(reader.get(), "through the pipe");
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_EQ(files(), std::vector<std::string>{"pipe"});

    auto drain = std::async(std::launch::async, [&] {
        std::ifstream in(fifo, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    });
    try {
        AtomicFile file(fifo);
        file.write("header");
        (void)file.tell();
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), fifo + ": cannot write: a pipe cannot take this file (its header is patched once "
                                                "the rest is written): give a file path");
    }
    drain.get();
    EXPECT_TRUE(fs::is_fifo(fifo));
}

// A link to such a name (out.scn -> /dev/stdout, made by the user), a link to that link, and a
// name in a linked folder (d -> /dev/fd, then d/N) are that descriptor too: followed to the
// file behind it, they were replaced by name, losing what `>>` had kept there.
TEST_F(AtomicFileTest, ALinkToADescriptorNameIsThatDescriptor) {
    const int fd = ::open(path("log.txt").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, "kept\n", 5), 5);
    fs::create_symlink("/dev/fd/" + std::to_string(fd), path("out.scn"));
    fs::create_symlink("out.scn", path("again.scn"));
    fs::create_directory_symlink("/dev/fd", path("d"));
    fs::create_directory_symlink("/proc/thread-self/fd", path("t"));  // spelt out: /proc/<pid>/task/<tid>/fd
    for (const std::string& name : {path("out.scn"), path("again.scn"), path("d") + "/" + std::to_string(fd), path("t") + "/" + std::to_string(fd)}) {
        AtomicFile file(name);
        EXPECT_TRUE(file.in_place()) << name;
        file.write(fs::path(name).filename().string() + "\n");
        file.commit();
        EXPECT_TRUE(same_file(name, "/dev/fd/" + std::to_string(fd))) << name;
    }
    ::close(fd);
    EXPECT_EQ(read_text(path("log.txt")), "kept\nout.scn\nagain.scn\n" + std::to_string(fd) + "\n" + std::to_string(fd) + "\n");
    EXPECT_TRUE(fs::is_symlink(path("out.scn")));
    // A link to a plain file is still replaced through the link, and a loop of links is no
    // descriptor (it is replaced, as a dangling link is).
    fs::create_symlink("log.txt", path("plain.scn"));
    write_file_atomic(path("plain.scn"), "replaced\n");
    EXPECT_EQ(read_text(path("log.txt")), "replaced\n");
    EXPECT_TRUE(fs::is_symlink(path("plain.scn")));
    fs::create_symlink("loop_b", path("loop_a"));
    fs::create_symlink("loop_a", path("loop_b"));
    {
        AtomicFile file(path("loop_a"));
        EXPECT_FALSE(file.in_place());
        file.write("x");
        file.commit();
    }
    EXPECT_EQ(read_text(path("loop_a")), "x");
}

// A path that stands for a descriptor of this process (/dev/stdout is /dev/fd/1) goes through
// that descriptor, at its offset and with its O_APPEND, in order with the other writes to it:
// opened again, it started at offset 0 of the file behind it and overwrote what was there
// (stdout redirected to a file lost the trace's start to the summary, and `>>` its old lines).
TEST_F(AtomicFileTest, ADescriptorOfThisProcessIsWrittenThroughNotOpenedAgain) {
    const int fd = ::open(path("out.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::write(fd, "before;", 7), 7);
    for (const std::string& name : {"/dev/fd/" + std::to_string(fd), "/proc/self/fd/" + std::to_string(fd)}) {
        AtomicFile file(name);
        EXPECT_TRUE(file.in_place());
        file.write(name + ";");
        file.commit();
    }
    ASSERT_EQ(::write(fd, "after", 5), 5);
    EXPECT_EQ(read_text(path("out.txt")), "before;/dev/fd/" + std::to_string(fd) + ";/proc/self/fd/" + std::to_string(fd) + ";after");
    // A header patched at the end leaves the descriptor after the last byte, not after the patch.
    {
        AtomicFile file("/dev/fd/" + std::to_string(fd));
        const std::int64_t start = file.tell();
        file.write("n=?;data");
        file.seek(start + 2);
        file.write("2");
        file.commit();
    }
    ASSERT_EQ(::write(fd, ";end", 4), 4);
    EXPECT_THAT(read_text(path("out.txt")), ::testing::EndsWith("aftern=2;data;end"));
    ::close(fd);
    EXPECT_EQ(files(), std::vector<std::string>{"out.txt"});

    // Opened to append (`>>`): the old bytes stay; a file that must be patched says why it cannot.
    const int append = ::open(path("log.txt").c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
    ASSERT_GE(append, 0);
    ASSERT_EQ(::write(append, "hi\n", 3), 3);
    const std::string name = "/dev/fd/" + std::to_string(append);
    write_file_atomic(name, "appended\n");
    EXPECT_EQ(read_text(path("log.txt")), "hi\nappended\n");
    try {
        AtomicFile file(name);
        (void)file.tell();
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), name + ": cannot write: it is open for appending (>>), and this file's header is "
                                                "patched once the rest is written: give a file path");
    }
    EXPECT_EQ(read_text(path("log.txt")), "hi\nappended\n");
    // Two names of one descriptor are one output; a closed one cannot be written, said early.
    EXPECT_TRUE(same_file(name, "/proc/self/fd/" + std::to_string(append)));
    ::close(append);
    const auto message_of = [](auto&& attempt) -> std::string {
        try {
            attempt();
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    const std::string closed = name + ": cannot write: descriptor " + std::to_string(append) + " is not open";
    EXPECT_EQ(message_of([&] { check_writable(name); }), closed);
    EXPECT_EQ(message_of([&] { AtomicFile file(name); }), closed);
    // One open for reading only says so.
    const int reading = ::open(path("log.txt").c_str(), O_RDONLY | O_CLOEXEC);
    ASSERT_GE(reading, 0);
    const std::string read_only = "/dev/fd/" + std::to_string(reading);
    EXPECT_EQ(message_of([&] { check_writable(read_only); }),
              read_only + ": cannot write: descriptor " + std::to_string(reading) + " is open for reading only");
    ::close(reading);
}

// Two descriptors on one pipe are one output (bytes of one would land in the other's), but
// two on one terminal are not: an interactive shell's stdin, stdout and stderr are all one
// terminal, and a script typed there while a scenario is printed there is no clash.
TEST_F(AtomicFileTest, DescriptorsOnOnePipeAreOneFileButNotOnOneTerminal) {
    int ends[2];
    ASSERT_EQ(::pipe(ends), 0);
    EXPECT_TRUE(same_file("/dev/fd/" + std::to_string(ends[1]), "/dev/fd/" + std::to_string(ends[0])));
    ::close(ends[0]);
    ::close(ends[1]);
    const int terminal = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (terminal < 0 || ::grantpt(terminal) != 0 || ::unlockpt(terminal) != 0) {
        if (terminal >= 0) ::close(terminal);
        GTEST_SKIP() << "no pseudo-terminal here";
    }
    const int again = ::fcntl(terminal, F_DUPFD_CLOEXEC, 3);
    ASSERT_GE(again, 0);
    EXPECT_FALSE(same_file("/dev/fd/" + std::to_string(terminal), "/dev/fd/" + std::to_string(again)));
    EXPECT_TRUE(same_file("/dev/fd/" + std::to_string(terminal), "/dev/fd/" + std::to_string(terminal)));
    ::close(again);
    ::close(terminal);
}

// A link to a file: the file gets the new bytes and the link stays a link; a dangling link is
// replaced by the file, as a new file would be.
TEST_F(AtomicFileTest, ALinkKeepsPointingAtTheReplacedFile) {
    write_file_atomic(path("real.txt"), "old");
    fs::create_symlink(path("real.txt"), path("link.txt"));
    write_file_atomic(path("link.txt"), "new");
    EXPECT_TRUE(fs::is_symlink(path("link.txt")));
    EXPECT_EQ(read_text(path("real.txt")), "new");
    fs::create_symlink(path("nowhere.txt"), path("dangling.txt"));
    write_file_atomic(path("dangling.txt"), "made");
    EXPECT_FALSE(fs::is_symlink(path("dangling.txt")));
    EXPECT_EQ(read_text(path("dangling.txt")), "made");
    EXPECT_EQ(files(), (std::vector<std::string>{"dangling.txt", "link.txt", "real.txt"}));
}

}  // namespace
}  // namespace jostle
