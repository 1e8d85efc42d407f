// bench_plot: draws benchmark series as a log-log line chart PNG with jostle's own renderer
// (off-screen, OSMesa), for tools/bench's "cost per step against entity count".
//
// usage: bench_plot INPUT.csv OUTPUT.png [TITLE]
//   INPUT.csv: a header line, then "series,x,y" rows (x > 0, y > 0), e.g.
//              series,entities,ms_per_step
//              world step,1000,0.61
// Every series is one coloured line with its points marked; the legend lists them in the order
// they first appear. Exit status 0, or 2 with a message naming the file and line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "jostle/core/error.h"
#include "jostle/render/png_io.h"
#include "jostle/render/renderer.h"

namespace {

using jostle::Color;
using jostle::Vec2;

struct Series {
    std::string name;
    std::vector<Vec2> points;  // (log10 x, log10 y)
};

std::vector<Series> read_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw jostle::InputError(jostle::SourceLocation{path, 0, 0}, "cannot open the file");
    std::vector<Series> series;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (number == 1 || line.empty()) continue;  // the header
        std::stringstream fields(line);
        std::string name, x_text, y_text;
        std::getline(fields, name, ',');
        std::getline(fields, x_text, ',');
        std::getline(fields, y_text, ',');
        double x = 0, y = 0;
        try {
            x = std::stod(x_text);
            y = std::stod(y_text);
        } catch (const std::exception&) {
            throw jostle::InputError(jostle::SourceLocation{path, number, 0}, "expected 'series,x,y' with numbers, got '" + line + "'");
        }
        if (!(x > 0) || !(y > 0) || !std::isfinite(x) || !std::isfinite(y)) {
            throw jostle::InputError(jostle::SourceLocation{path, number, 0}, "expected x > 0 and y > 0 (the axes are logarithmic)");
        }
        auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) { return s.name == name; });
        if (it == series.end()) it = series.insert(series.end(), Series{name, {}});
        it->points.push_back({static_cast<float>(std::log10(x)), static_cast<float>(std::log10(y))});
    }
    if (series.empty()) throw jostle::InputError(jostle::SourceLocation{path, number, 0}, "no data rows");
    for (Series& s : series) std::sort(s.points.begin(), s.points.end(), [](Vec2 a, Vec2 b) { return a.x < b.x; });
    return series;
}

std::string decade_label(int exponent) {
    if (exponent >= 0 && exponent <= 6) return std::to_string(static_cast<long>(std::pow(10.0, exponent)));
    if (exponent < 0 && exponent >= -3) return "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + "1";
    return "1e" + std::to_string(exponent);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: bench_plot INPUT.csv OUTPUT.png [TITLE]\n");
        return 2;
    }
    try {
        const std::vector<Series> series = read_csv(argv[1]);
        const std::string title = argc == 4 ? argv[3] : "";
        float x0 = 1e9f, x1 = -1e9f, y0 = 1e9f, y1 = -1e9f;
        for (const Series& s : series) {
            for (const Vec2 p : s.points) {
                x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
            }
        }
        // Whole decades around the data.
        const int dx0 = static_cast<int>(std::floor(x0)), dx1 = std::max(dx0 + 1, static_cast<int>(std::ceil(x1)));
        const int dy0 = static_cast<int>(std::floor(y0)), dy1 = std::max(dy0 + 1, static_cast<int>(std::ceil(y1)));

        constexpr int kWidth = 800, kHeight = 520;
        const float left = 90, right = 560, top = 50, bottom = 460;  // the plot area in image pixels
        const auto to_image = [&](Vec2 p) {
            return Vec2{left + (p.x - static_cast<float>(dx0)) / static_cast<float>(dx1 - dx0) * (right - left),
                        bottom - (p.y - static_cast<float>(dy0)) / static_cast<float>(dy1 - dy0) * (bottom - top)};
        };
        jostle::Renderer renderer;
        renderer.begin_frame(kWidth, kHeight, Color{255, 255, 255, 255});
        const Color grid{225, 225, 225, 255}, ink{40, 40, 40, 255};
        for (int d = dx0; d <= dx1; ++d) {
            const Vec2 a = to_image({static_cast<float>(d), static_cast<float>(dy0)});
            renderer.draw_line({a.x, top}, {a.x, bottom}, grid);
            const std::string label = decade_label(d);
            renderer.draw_text({a.x - 3.0f * static_cast<float>(label.size()), bottom + 8}, label, ink);
        }
        for (int d = dy0; d <= dy1; ++d) {
            const Vec2 a = to_image({static_cast<float>(dx0), static_cast<float>(d)});
            renderer.draw_line({left, a.y}, {right, a.y}, grid);
            const std::string label = decade_label(d);
            renderer.draw_text({left - 8 - 6.0f * static_cast<float>(label.size()), a.y - 3}, label, ink);
        }
        renderer.draw_line({left, bottom}, {right, bottom}, ink);
        renderer.draw_line({left, top}, {left, bottom}, ink);
        renderer.draw_text({left, 16}, title, ink, 2);
        renderer.draw_text({(left + right) / 2 - 40, bottom + 28}, "entities", ink);
        renderer.draw_text({8, top - 20}, "ms per step", ink);

        const Color palette[] = {{31, 119, 180, 255}, {255, 127, 14, 255}, {44, 160, 44, 255}, {214, 39, 40, 255},
                                 {148, 103, 189, 255}, {140, 86, 75, 255}, {227, 119, 194, 255}, {127, 127, 127, 255}};
        for (std::size_t i = 0; i < series.size(); ++i) {
            const Color c = palette[i % std::size(palette)];
            const Series& s = series[i];
            for (std::size_t k = 0; k + 1 < s.points.size(); ++k) {
                renderer.draw_line(to_image(s.points[k]), to_image(s.points[k + 1]), c, 2.0f);
            }
            for (const Vec2 p : s.points) {
                const Vec2 q = to_image(p);
                renderer.fill_rect(jostle::Aabb{{q.x - 3, q.y - 3}, {q.x + 3, q.y + 3}}, c);
            }
            const float y = top + 10 + 18.0f * static_cast<float>(i);
            renderer.fill_rect(jostle::Aabb{{right + 20, y}, {right + 34, y + 8}}, c);
            renderer.draw_text({right + 40, y}, s.name, ink);
        }
        jostle::write_png_atomic(argv[2], renderer.end_frame());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_plot: %s\n", e.what());
        return 2;
    }
    return 0;
}
