// atomic_file_test.cpp: AtomicFile leaves either the old file or the whole new one, and
// nothing else: no temporary files, no half-written target.
#include "jostle/core/atomic_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "jostle/core/error.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;
using ::testing::StartsWith;

class AtomicFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        folder_ = fs::path(::testing::TempDir()) /
                  ("jostle_atomic_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(folder_);
        fs::create_directories(folder_);
    }
    void TearDown() override { fs::remove_all(folder_); }
    std::vector<std::string> files() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(folder_)) names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }
    std::string path(const char* name) const { return (folder_ / name).string(); }
    static std::string contents(const std::string& p) {
        std::ifstream in(p, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    fs::path folder_;
};

TEST_F(AtomicFileTest, CommitReplacesTheTargetWhole) {
    write_file_atomic(path("a.txt"), "old contents");
    {
        AtomicFile file(path("a.txt"));
        file.write("new");
        // Until commit the target is the old file, and the new bytes sit in a temporary file.
        EXPECT_EQ(contents(path("a.txt")), "old contents");
        EXPECT_EQ(files().size(), 2u);
        EXPECT_THAT(file.temp_path(), StartsWith(path("a.txt") + "."));
        file.commit();
    }
    EXPECT_EQ(contents(path("a.txt")), "new");
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
    EXPECT_EQ(contents(path("a.txt")), "old");
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
    EXPECT_EQ(contents(path("h.bin")), "count=42;data;end");
}

TEST_F(AtomicFileTest, ErrorsNameTheTargetAndLeaveNothingBehind) {
    const std::string missing = (folder_ / "no_such_folder" / "a.txt").string();
    try {
        write_file_atomic(missing, "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(missing + ": cannot write: cannot create temporary file "));
    }
    // The rename fails when the target is a non-empty folder, after the data is written.
    fs::create_directories(folder_ / "taken" / "inside");
    try {
        write_file_atomic(path("taken"), "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), StartsWith(path("taken") + ": cannot write: cannot rename "));
    }
    EXPECT_EQ(files(), std::vector<std::string>{"taken"});
}

}  // namespace
}  // namespace jostle
