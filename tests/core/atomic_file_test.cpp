// atomic_file_test.cpp: AtomicFile leaves either the old file or the whole new one, and
// nothing else: no temporary files, no half-written target.
#include "jostle/core/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
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
    // The rename fails when the target is a non-empty folder, after the data is written.
    fs::create_directories(folder_.path() / "taken" / "inside");
    try {
        write_file_atomic(path("taken"), "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path("taken") + ": cannot write: it is a folder");
    }
    EXPECT_EQ(files(), std::vector<std::string>{"taken"});
}

}  // namespace
}  // namespace jostle
