// report_browser_test.cpp: the check report in a real browser. A failing `jostle check
// --report` run is opened from disk by Debian's chromium, headless; a copy of report.html with
// a probe script marks every image with the size it loaded at (or "broken"), and the test
// reads the DOM chromium dumps: each failing scenario shows its first divergent tick and its
// expected, actual and diff images, loaded; a passing scenario is not shown.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arena.h"
#include "game/run_jostle.h"
#include "test_support.h"

namespace jostle {
namespace {

namespace fs = std::filesystem;

using test::read_text;

const std::string kAssets = JOSTLE_ASSETS_DIR;
const std::string kChromium = JOSTLE_CHROMIUM;  // found by CMake; "...-NOTFOUND" when missing

// Marks each image with its loaded size once the page (images included) has loaded.
constexpr const char* kProbe = R"(<script>
window.addEventListener('load', () => {
  for (const img of document.images) {
    img.setAttribute('data-loaded', img.complete && img.naturalWidth > 0
        ? img.naturalWidth + 'x' + img.naturalHeight : 'broken');
  }
  document.body.setAttribute('data-probed', 'yes');
});
</script>
)";

// The part of the DOM dump for the scenario with this id (up to the next scenario), or "".
std::string section(const std::string& dom, const std::string& id) {
    const std::string start = "<div class=\"scenario\" id=\"" + id + "\">";
    const std::size_t at = dom.find(start);
    if (at == std::string::npos) return "";
    const std::size_t end = dom.find("<div class=\"scenario\"", at + start.size());
    return dom.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

// What the probe wrote on the image of this class in the section: "640x480", "broken", or
// "(no image)".
std::string loaded(const std::string& html, const std::string& image_class) {
    const std::size_t at = html.find("<img class=\"" + image_class + "\"");
    if (at == std::string::npos) return "(no image)";
    const std::string tag = html.substr(at, html.find('>', at) - at);
    const std::string key = "data-loaded=\"";
    const std::size_t value = tag.find(key);
    if (value == std::string::npos) return "(not probed)";
    const std::size_t from = value + key.size();
    return tag.substr(from, tag.find('"', from) - from);
}

class ReportInBrowser : public ::testing::Test {
protected:
    void SetUp() override {
        fs::create_directories(dir_.path() / "scenarios");
        level_hash_ = game::ArenaGame(kAssets).level_hash("arena");
    }

    void scenario(const std::string& name, const std::string& inputs) {
        std::ofstream(dir_.path() / "scenarios" / (name + ".scn"), std::ios::binary)
            << "jostle-scenario 1\nengine 0.1.0\nlevel arena\nseed 1\ntick-rate 60\nlevel-hash " << level_hash_ << "\n\n"
            << inputs << "at 30 screenshot\n";
    }

    test::RunResult check(std::vector<std::string> args) {
        args.insert(args.begin(), {"check", "--assets", kAssets, dir_.file("scenarios")});
        return test::run_jostle_binary(args);
    }

    const test::TempFolder dir_{"report_browser"};
    std::string level_hash_;
};

TEST_F(ReportInBrowser, ShowsEachFailingScenarioWithItsImagesAndFirstDivergentTick) {
    ASSERT_TRUE(fs::exists(kChromium)) << "no chromium browser found (" << kChromium
                                       << "): run tools/setup, or apt-get install chromium";

    // Three scenarios with goldens; then one changes its input from tick 15 on (the ship turns
    // as well as drives, so tick 15 is the first whose state differs) and one loses its
    // screenshot golden. The third still passes.
    scenario("steady", "0-9 left\n10-49 up\n");
    scenario("wall #2", "0-9 left\n10-49 up\n");
    scenario("fresh", "0-4 right\n5-49 up\n");
    ASSERT_EQ(check({"--update"}).status, 0);
    scenario("wall #2", "0-9 left\n10-14 up\n15-49 left up\n");
    fs::remove(dir_.path() / "scenarios" / "fresh.tick_30.png");

    const fs::path report = dir_.path() / "report";
    const test::RunResult r = check({"--report", report.string()});
    ASSERT_EQ(r.status, 1) << r.out << r.err;
    ASSERT_THAT(r.out, ::testing::HasSubstr("first divergent tick 15"));

    // The probe goes into a copy beside the report, so relative image paths resolve the same.
    std::string html = read_text(report / "report.html");
    const std::size_t body_end = html.rfind("</body>");
    ASSERT_NE(body_end, std::string::npos);
    html.insert(body_end, kProbe);
    std::ofstream(report / "report_probe.html", std::ios::binary) << html;

    const test::RunResult browser = test::run_program(
        kChromium, {"--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-dev-shm-usage",
                    "--user-data-dir=" + dir_.file("profile"), "--virtual-time-budget=10000", "--dump-dom",
                    "file://" + (report / "report_probe.html").string()});
    ASSERT_EQ(browser.status, 0) << browser.err;
    const std::string& dom = browser.out;
    ASSERT_THAT(dom, ::testing::HasSubstr("data-probed=\"yes\"")) << "the page's load event never came:\n" << dom;
    EXPECT_THAT(dom, ::testing::HasSubstr("<h1>jostle check: 2 of 3 scenarios failed</h1>"));

    const std::string changed = section(dom, "wall #2");
    ASSERT_NE(changed, "") << dom;
    EXPECT_THAT(changed, ::testing::HasSubstr("<b class=\"first-divergent-tick\">15</b>"));
    EXPECT_THAT(changed, ::testing::HasSubstr("<td>player</td><td>angle</td>")) << "the field that differs";
    EXPECT_EQ(loaded(changed, "expected"), "640x480");
    EXPECT_EQ(loaded(changed, "actual"), "640x480");
    EXPECT_EQ(loaded(changed, "diff"), "640x480");

    const std::string missing = section(dom, "fresh");
    ASSERT_NE(missing, "") << dom;
    EXPECT_THAT(missing, ::testing::Not(::testing::HasSubstr("first-divergent-tick"))) << "its trace still matches";
    EXPECT_THAT(missing, ::testing::HasSubstr("expected: no golden"));
    EXPECT_EQ(loaded(missing, "expected"), "(no image)");
    EXPECT_EQ(loaded(missing, "actual"), "640x480");

    EXPECT_EQ(section(dom, "steady"), "") << "a passing scenario is not in the report";
}

}  // namespace
}  // namespace jostle
