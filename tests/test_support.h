// test_support.h: helpers the test suites share: a temporary folder per test (TempFolder),
// reading a whole file (read_text), the sorted file names in a folder (file_names), and
// setting environment variables for a scope (EnvGuard; a child program inherits them).
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace jostle::test {

// A fresh folder for the running test, removed before and after:
// TempDir()/PREFIX_TEST_PID, so tests run in parallel (one process each) never share one.
class TempFolder {
public:
    explicit TempFolder(const std::string& prefix) {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = info != nullptr ? info->name() : "no_test";
        std::replace(name.begin(), name.end(), '/', '_');  // parameterized tests are named Name/0
        path_ = std::filesystem::path(::testing::TempDir()) / (prefix + "_" + name + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }
    // The path of NAME in the folder, as a string.
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

// The whole file, byte for byte ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The names of the entries in a folder (not recursive), sorted.
inline std::vector<std::string> file_names(const std::filesystem::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Sets or unsets environment variables for its lifetime, then puts back what was there.
class EnvGuard {
public:
    EnvGuard() = default;
    EnvGuard(const std::string& name, const std::string& value) { set(name, value); }
    EnvGuard(const EnvGuard&) = delete;
    EnvGuard& operator=(const EnvGuard&) = delete;
    ~EnvGuard() {
        for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
            if (it->second) ::setenv(it->first.c_str(), it->second->c_str(), 1);
            else ::unsetenv(it->first.c_str());
        }
    }
    void set(const std::string& name, const std::string& value) {
        save(name);
        ::setenv(name.c_str(), value.c_str(), 1);
    }
    void unset(const std::string& name) {
        save(name);
        ::unsetenv(name.c_str());
    }

private:
    void save(const std::string& name) {
        for (const auto& s : saved_) {
            if (s.first == name) return;
        }
        const char* v = std::getenv(name.c_str());
        saved_.emplace_back(name, v != nullptr ? std::optional<std::string>(v) : std::nullopt);
    }
    std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

}  // namespace jostle::test
