// hostile_test.cpp: the hostile-input catalogue, tests/hostile/catalogue.json. Each case runs
// the real jostle program on one bad input (a file, the command line, stdin, an output place
// that cannot be written, a full disk) and must give exactly its message and its exit status
// (2 for every bad input; the few accepted-by-design files, a BOM and CRLF line ends, give 0).
// Each case runs in a fresh output folder seeded with files it may try to overwrite; afterwards
// they must be byte-identical and nothing else may be there: no partial and no temporary file.
//
// Placeholders in a case's strings: {hostile} tests/hostile, {out} the case's output folder,
// {gen} the files this test writes first (too large to commit), {data} tests/data.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "game/run_jostle.h"

namespace jostle::test {
namespace {

namespace fs = std::filesystem;

struct HostileCase {
    std::string name;
    std::string what;                 // the input, in words
    std::vector<std::string> args;
    std::string stdin_path = "/dev/null";
    std::string cwd;
    std::optional<std::string> out;   // exact stdout, when the case says
    std::string err;                  // exact stderr
    int exit = 2;
    long long file_size_limit = -1;   // RLIMIT_FSIZE in bytes: a full disk
    std::string problem;              // the catalogue entry itself is malformed
};

// How gtest (and so ctest) names a case's parameter: by its name, not its bytes.
void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.name; }

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
}

// Read when the test binary starts, so that each case is a test of its own (and a ctest test).
std::vector<HostileCase> load_catalogue() {
    std::vector<HostileCase> cases;
    try {
        const nlohmann::json catalogue = nlohmann::json::parse(read_bytes(fs::path(JOSTLE_HOSTILE_DIR) / "catalogue.json"));
        for (const nlohmann::json& entry : catalogue.at("cases")) {
            HostileCase c;
            c.name = entry.at("name").get<std::string>();
            c.what = entry.at("what").get<std::string>();
            c.args = entry.at("args").get<std::vector<std::string>>();
            c.err = entry.at("stderr").get<std::string>();
            if (entry.contains("stdin")) c.stdin_path = entry["stdin"].get<std::string>();
            if (entry.contains("cwd")) c.cwd = entry["cwd"].get<std::string>();
            if (entry.contains("stdout")) c.out = entry["stdout"].get<std::string>();
            if (entry.contains("exit")) c.exit = entry["exit"].get<int>();
            if (entry.contains("file_size_limit")) c.file_size_limit = entry["file_size_limit"].get<long long>();
            cases.push_back(std::move(c));
        }
    } catch (const std::exception& e) {
        HostileCase broken;
        broken.name = "catalogue";
        broken.problem = std::string("tests/hostile/catalogue.json: ") + e.what();
        cases.push_back(broken);
    }
    return cases;
}

// The files too large to commit, written once per test process into {gen}.
void write_generated_files(const fs::path& gen) {
    // A scenario with a 100,000-byte line (the limit is 65,536).
    write_bytes(gen / "long_line.scn", "jostle-scenario 1\nengine 0.1.0\nlevel ok\nseed 1\ntick-rate 60\n# " +
                                           std::string(100000, 'x') + "\n");
    // 10,001 pickups: one more than a level may hold (kMaxLevelThings).
    std::string crowded = "jostle-level 1\nsize 200 100\nplayer 100 50 0\n";
    for (int i = 0; i <= 10000; ++i) crowded += "pickup p" + std::to_string(i) + " 20 20 1\n";
    write_bytes(gen / "assets/levels/too_many_things.level", crowded);
    // 1,000 cannons in a column, each firing a fast ball every tick along its own row (the
    // balls never touch): the world would pass kMaxEntities (20,000) at tick 18.
    std::string cannons = "jostle-level 1\nsize 10000 20000\nplayer 5000 50 0\n";
    for (int i = 0; i < 1000; ++i) {
        cannons += "cannon k" + std::to_string(i) + " 10 " + std::to_string(20 * i + 10) + " 0 1 10000\n";
    }
    write_bytes(gen / "assets/levels/too_many_entities.level", cannons);
    // JSON arrays nested 100,000 deep on one query line (under the 1 MiB line limit).
    write_bytes(gen / "deep.jsonl", std::string(100000, '[') + std::string(100000, ']') + "\n");
    // A query line of 2 MiB (the limit is 1 MiB).
    write_bytes(gen / "long_line.jsonl", "{\"op\":\"" + std::string(2 << 20, 'x') + "\"}\n");
}

std::string replace_all(std::string text, const std::map<std::string, std::string>& values) {
    for (const auto& [key, value] : values) {
        for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size())) {
            text.replace(at, key.size(), value);
        }
    }
    return text;
}

// Every regular file below `folder` with its bytes, by path relative to it; folders too
// (an empty one that appeared counts), with "/" appended.
std::map<std::string, std::string> snapshot(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        const std::string relative = fs::relative(entry.path(), folder).string();
        files[entry.is_directory() ? relative + "/" : relative] = entry.is_regular_file() ? read_bytes(entry.path()) : "";
    }
    return files;
}

class Hostile : public testing::TestWithParam<HostileCase> {
protected:
    static void SetUpTestSuite() {
        char pattern[] = "/tmp/jostle_hostile_gen_XXXXXX";
        ASSERT_NE(mkdtemp(pattern), nullptr);
        gen_ = pattern;
        write_generated_files(gen_);
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(gen_, ec);
    }
    static inline fs::path gen_;
};

TEST_P(Hostile, ExactMessageAndNothingWritten) {
    const HostileCase& c = GetParam();
    ASSERT_TRUE(c.problem.empty()) << c.problem;
    char pattern[] = "/tmp/jostle_hostile_out_XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    const fs::path out = pattern;
    // What the case may try to overwrite, or write beside.
    for (const char* name : {"kept.trace", "kept.scn", "kept.png"}) {
        write_bytes(out / name, std::string("jostle hostile-input test: ") + name + " must survive unchanged\n");
    }
    const std::map<std::string, std::string> before = snapshot(out);
    const std::map<std::string, std::string> inputs_before = snapshot(JOSTLE_HOSTILE_DIR);
    const std::map<std::string, std::string> places = {
        {"{hostile}", JOSTLE_HOSTILE_DIR}, {"{out}", out.string()}, {"{gen}", gen_.string()}, {"{data}", JOSTLE_TEST_DATA}};

    std::vector<std::string> args;
    for (const std::string& arg : c.args) args.push_back(replace_all(arg, places));
    const RunResult r = run_jostle_binary(args, replace_all(c.stdin_path, places), replace_all(c.cwd, places), -1,
                                          c.file_size_limit);

    EXPECT_EQ(r.err, replace_all(c.err, places)) << c.what;
    if (c.out) {
        EXPECT_EQ(r.out, replace_all(*c.out, places)) << c.what;
    }
    EXPECT_EQ(r.term_signal, 0) << c.what << ": jostle died of a signal";
    EXPECT_EQ(r.status, c.exit) << c.what;
    EXPECT_EQ(snapshot(out), before) << c.what << ": a file in the output folder changed, appeared or went";
    EXPECT_EQ(snapshot(JOSTLE_HOSTILE_DIR), inputs_before) << c.what << ": a file appeared beside the inputs";
    std::error_code ec;
    fs::remove_all(out, ec);
}

INSTANTIATE_TEST_SUITE_P(Catalogue, Hostile, testing::ValuesIn(load_catalogue()),
                         [](const testing::TestParamInfo<HostileCase>& param) { return param.param.name; });

// The catalogue is the issue's: at least 40 bad inputs (exit 2), every name a valid test name
// and unique (gtest would refuse a duplicate only at run time).
TEST(HostileCatalogue, HasFortyBadInputsWithUniqueNames) {
    const std::vector<HostileCase> cases = load_catalogue();
    int bad = 0;
    std::map<std::string, int> names;
    for (const HostileCase& c : cases) {
        EXPECT_TRUE(c.problem.empty()) << c.problem;
        bad += c.exit == 2;
        EXPECT_EQ(++names[c.name], 1) << "two cases named " << c.name;
        EXPECT_TRUE(c.exit == 2 || c.exit == 0) << c.name << ": a bad input exits 2 (or 0 when it is accepted by design)";
    }
    EXPECT_GE(bad, 40);
}

}  // namespace
}  // namespace jostle::test
