// `jostle imgdiff`: argument parsing and the report; the comparison itself is
// jostle/render/image_compare.h.
#include "imgdiff.h"

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "arena.h"
#include "cli.h"
#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "jostle/render/image_compare.h"
#include "jostle/render/png_io.h"

namespace jostle {

namespace {

int usage(std::ostream& err, const std::string& message) {
    err << "jostle imgdiff: " << message << "\nRun 'jostle imgdiff --help' for usage.\n";
    return 2;
}

}  // namespace

std::string_view imgdiff_help() {
    return R"(usage: jostle imgdiff EXPECTED.png ACTUAL.png [--out DIFF.png] [--tolerance N] [--max-pixels N]

Compares two PNG images. Identical bytes match at once; otherwise a pixel differs when one
of its R, G, B, A channels differs by more than the tolerance, and the images match when at
most --max-pixels pixels differ. Images of different sizes never match.

options:
  --out DIFF.png    write a diff picture: EXPECTED faded toward white with every differing
                    pixel in red (written atomically, whatever the outcome); to /dev/stdout
                    the picture alone, the line below then on stderr; not a level or sprite of
                    the assets ($JOSTLE_ASSETS, else the source tree's), nor a new .png there
  --tolerance N     largest channel difference (0..255) that still counts as equal; default 0
  --max-pixels N    how many differing pixels are allowed (0..9223372036854775807); default 0
  --                what follows are the images, even if they start with '-'

output: one line, "identical", "match" or "differ", with the counts.
exit status: 0 the images match, 1 they differ, 2 bad usage, an unreadable image or a standard
output that could not be written.
)";
}

int imgdiff_command(std::span<const std::string_view> args, std::ostream& out, std::ostream& err) {
    std::vector<std::string> files;
    std::optional<std::string> diff_path;
    CompareOptions options;
    bool options_ended = false;  // after "--", an image named "-a.png" is an image
    game::OnceOnly once;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view a = args[i];
        if (options_ended || a.size() < 2 || a.front() != '-') {
            if (a.empty()) return usage(err, "expected a PNG file, got an empty argument");
            files.emplace_back(a);
        } else if (a == "--") {
            options_ended = true;
        } else if (a == "--out" || a == "--tolerance" || a == "--max-pixels") {
            std::string_view v;
            if (std::string e = game::option_value(args, i, a, v); !e.empty()) return usage(err, e);
            if (std::string e = once.take(a); !e.empty()) return usage(err, e);
            if (a == "--out") {
                diff_path = std::string(v);
            } else if (a == "--tolerance") {
                const auto n = game::parse_whole(v, 0, 255);
                if (!n) return usage(err, game::whole_number_error("--tolerance", 0, 255, v));
                options.max_channel_delta = static_cast<int>(*n);
            } else {
                const auto n = game::parse_whole(v, 0, INT64_MAX);
                if (!n) return usage(err, game::whole_number_error("--max-pixels", 0, INT64_MAX, v));
                options.max_differing_pixels = static_cast<std::int64_t>(*n);
            }
        } else if (a == "--help" || a == "-h") {  // anywhere an option may stand, as right after the command
            out << imgdiff_help();
            return 0;
        } else {
            return usage(err, "unknown option '" + std::string(a) + "'");
        }
    }
    if (files.size() != 2) return usage(err, "expected two PNG files (EXPECTED and ACTUAL), got " + std::to_string(files.size()));
    if (diff_path && same_file(*diff_path, files[0])) return usage(err, "--out: '" + *diff_path + "' is EXPECTED, being compared; give another path");
    if (diff_path && same_file(*diff_path, files[1])) return usage(err, "--out: '" + *diff_path + "' is ACTUAL, being compared; give another path");

    if (diff_path) {
        // A diff picture over a level or sprite of the assets, or new among the sprites, would
        // change the game ($JOSTLE_ASSETS, else the source tree's; without assets, nothing to keep).
        std::string asset;
        try {
            asset = game::ArenaGame(game::default_assets_dir()).asset_named(*diff_path);
        } catch (const InputError&) {
        }
        if (!asset.empty()) return usage(err, "--out: '" + *diff_path + "' " + asset + "; give another path");
    }

    try {
        const Image expected = read_png(files[0]);
        const Image actual = read_png(files[1]);
        const CompareResult r = compare_images(expected, actual, options);
        if (diff_path) write_png_atomic(*diff_path, diff_image(expected, actual, options.max_channel_delta));
        // A diff picture on standard output keeps it to itself: the verdict goes to stderr.
        std::ostream& verdict = diff_path && same_file(*diff_path, "/dev/stdout") ? err : out;
        const auto size = [](const Image& im) { return std::to_string(im.width) + "x" + std::to_string(im.height); };
        if (r.identical) {
            verdict << "identical: " << size(expected) << '\n';
        } else if (!r.same_size) {
            verdict << "differ: sizes " << size(expected) << " and " << size(actual) << '\n';
        } else {
            verdict << (r.within_tolerance ? "match: " : "differ: ") << r.differing_pixels << " of "
                    << std::int64_t{expected.width} * expected.height << " pixels differ by more than "
                    << options.max_channel_delta << " (allowed " << options.max_differing_pixels
                    << "); largest channel difference " << r.max_channel_delta << '\n';
        }
        return r.within_tolerance ? 0 : 1;
    } catch (const InputError& e) {
        err << "jostle imgdiff: " << e.what() << '\n';
        return 2;
    }
}

}  // namespace jostle
