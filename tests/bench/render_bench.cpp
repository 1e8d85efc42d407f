// render_bench.cpp: the render module's benchmarks (Google Benchmark): frame rendering, readback,
// PNG encoding, the frame pipeline and animated PNGs. Speed is only measured here, never asserted.
//
// Every family pairs candidates with an anchor measured side by side in the same run (its label
// is "anchor"), because on a shared 2-core machine absolute times drift while ratios hold up
// better. Names are BM_<Family>/<size...>/<variant>, registered anchor first, so a pair reads
// side by side; tools/bench-ratios turns the JSON output into a table of candidate/anchor ratios.
//
// All times are wall-clock (UseRealTime): llvmpipe rasterizes on worker threads and the
// FrameWriter encodes on its own thread, so the main thread's CPU time would undercount.
// A failed setup or sanity check ends the benchmark with SkipWithError, which prints
// "ERROR OCCURRED"; the ctest smoke test fails on that text.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "jostle/core/rng.h"
#include "jostle/render/animation.h"
#include "jostle/render/frame_output.h"
#include "jostle/render/png_io.h"
#include "jostle/render/renderer.h"

namespace {

using namespace jostle;
namespace fs = std::filesystem;

struct Size {
    int width;
    int height;
};
constexpr Size kSizes[] = {{640, 480}, {1280, 720}};
constexpr int kSpriteKinds = 8;
constexpr int kSpriteSide = 32;
constexpr int kRunFrames = 60;  // frames per pipeline or animation iteration: one second at 60 Hz
constexpr Color kClear{38, 42, 54, 255};

// ---------------------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------------------

// Eight 32x32 sprites of the kinds games draw: opaque pixel art and gradients, shapes with
// soft (partly transparent) edges and a translucent glow, so that blending and the PNG
// filters meet realistic pixels rather than flat colour.
Image make_sprite(int kind) {
    constexpr Color palette[kSpriteKinds] = {{230, 80, 60},  {200, 160, 90}, {90, 200, 240}, {250, 220, 70},
                                             {255, 255, 200}, {120, 220, 110}, {220, 90, 200}, {160, 160, 170}};
    const Color base = palette[kind];
    Image image{kSpriteSide, kSpriteSide, std::vector<std::uint8_t>(kSpriteSide * kSpriteSide * 4)};
    for (int y = 0; y < kSpriteSide; ++y) {
        for (int x = 0; x < kSpriteSide; ++x) {
            // -1..1 across the sprite, and the distance from its centre.
            const float u = (static_cast<float>(x) + 0.5f) / (kSpriteSide / 2.0f) - 1.0f;
            const float v = (static_cast<float>(y) + 0.5f) / (kSpriteSide / 2.0f) - 1.0f;
            const float r = std::sqrt(u * u + v * v);
            float alpha = 1.0f;
            float shade = 1.0f;
            switch (kind) {
                case 0:  // ball: soft edge, lit from the top left
                    alpha = std::clamp((1.0f - r) * 8.0f, 0.0f, 1.0f);
                    shade = 1.0f - 0.4f * std::sqrt((u + 0.4f) * (u + 0.4f) + (v + 0.4f) * (v + 0.4f));
                    break;
                case 1:  // crate: vertical gradient with a dark border
                    shade = (x < 2 || y < 2 || x > kSpriteSide - 3 || y > kSpriteSide - 3) ? 0.4f : 1.0f - 0.3f * (v + 1.0f) / 2.0f;
                    break;
                case 2:  // ring
                    alpha = std::clamp(1.0f - std::abs(r - 0.7f) * 6.0f, 0.0f, 1.0f);
                    break;
                case 3:  // diamond with a soft edge
                    alpha = std::clamp((1.0f - std::abs(u) - std::abs(v)) * 8.0f, 0.0f, 1.0f);
                    break;
                case 4:  // glow: translucent everywhere
                    alpha = std::clamp(1.0f - r, 0.0f, 1.0f) * std::clamp(1.0f - r, 0.0f, 1.0f);
                    break;
                case 5:  // checkered pixel art, opaque
                    shade = ((x / 4 + y / 4) % 2 == 0) ? 1.0f : 0.55f;
                    break;
                case 6:  // triangle, hard edge
                    alpha = (std::abs(u) <= (v + 1.0f) / 2.0f) ? 1.0f : 0.0f;
                    break;
                default:  // striped panel with a half-transparent window
                    shade = (y / 3) % 2 == 0 ? 1.0f : 0.7f;
                    alpha = (r < 0.5f) ? 0.5f : 1.0f;
                    break;
            }
            std::uint8_t* p = image.rgba.data() + (static_cast<std::size_t>(y) * kSpriteSide + static_cast<std::size_t>(x)) * 4;
            const auto channel = [&](std::uint8_t c) { return static_cast<std::uint8_t>(std::clamp(c * shade, 0.0f, 255.0f)); };
            p[0] = channel(base.r);
            p[1] = channel(base.g);
            p[2] = channel(base.b);
            p[3] = static_cast<std::uint8_t>(std::lround(alpha * 255.0f));
        }
    }
    return image;
}

// A 64x64 ground tile: a gradient under per-pixel noise, like the textured backgrounds many
// games tile behind their sprites. Noise is what PNG filters and zlib find hardest, and the
// tiles make the frames' other extreme next to the flat clear colour of the plain scenes.
Image make_ground_tile() {
    constexpr int side = 64;
    Image image{side, side, std::vector<std::uint8_t>(side * side * 4)};
    Rng rng(7);
    for (int y = 0; y < side; ++y) {
        for (int x = 0; x < side; ++x) {
            const int noise = static_cast<int>(rng.below(24));
            std::uint8_t* p = image.rgba.data() + (static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)) * 4;
            p[0] = static_cast<std::uint8_t>(60 + noise + x / 4);
            p[1] = static_cast<std::uint8_t>(110 + noise + y / 8);
            p[2] = static_cast<std::uint8_t>(50 + noise / 2);
            p[3] = 255;
        }
    }
    return image;
}

// A renderer with the eight sprites and the ground tile in its atlas.
struct Stage {
    Renderer renderer;
    std::vector<SpriteId> sprites;
    SpriteId ground;
    explicit Stage(RenderBackend backend) : renderer(RendererDesc{.backend = backend}) {
        for (int kind = 0; kind < kSpriteKinds; ++kind) sprites.push_back(renderer.add_sprite(make_sprite(kind)));
        ground = renderer.add_sprite(make_ground_tile());
    }
};

struct Actor {
    int kind = 0;  // which of the eight sprites
    Vec2 position;
    Vec2 velocity;  // image pixels per frame
    float angle = 0.0f;
    float spin = 0.0f;  // radians per frame
};

// What a frame shows. Plain scenes are sprites only (one quad each, so the sprite count is
// exact); world scenes add what a game frame has besides sprites: flat platforms and a HUD
// line with the frame number, which changes every frame. A tiled scene draws its sprites over
// ground tiles instead of the flat clear colour.
struct Scene {
    Size size{};
    std::vector<Actor> actors;
    bool world = false;
    bool tiled = false;

    // One tick: movers move and turn, bouncing off the image's edges.
    void step() {
        for (Actor& a : actors) {
            a.position += a.velocity;
            a.angle += a.spin;
            if (a.position.x < 0.0f || a.position.x > static_cast<float>(size.width)) a.velocity.x = -a.velocity.x;
            if (a.position.y < 0.0f || a.position.y > static_cast<float>(size.height)) a.velocity.y = -a.velocity.y;
        }
    }
};

// `count` actors at seeded pseudo-random places and angles. The first `movers` of them move;
// when `cluster` is set the movers stay in a box a quarter of the image's width (a player and
// the enemies around it) instead of roaming the whole image.
Scene make_scene(Size size, int count, int movers, bool world, bool cluster = false, std::uint64_t seed = 42) {
    Rng rng(seed);
    Scene scene{size, {}, world};
    const float w = static_cast<float>(size.width);
    const float h = static_cast<float>(size.height);
    for (int i = 0; i < count; ++i) {
        Actor a;
        a.kind = static_cast<int>(rng.below(kSpriteKinds));
        a.position = {rng.uniform(0.0f, w), rng.uniform(0.0f, h)};
        a.angle = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
        if (i < movers) {
            a.velocity = {rng.uniform(-4.0f, 4.0f), rng.uniform(-4.0f, 4.0f)};
            a.spin = rng.uniform(-0.1f, 0.1f);
            if (cluster) {
                a.position = {w * 0.4f + rng.uniform(0.0f, w * 0.2f), h * 0.4f + rng.uniform(0.0f, h * 0.2f)};
                a.velocity *= 0.25f;  // 60 frames * 1 px: they stay near the middle
            }
        }
        scene.actors.push_back(a);
    }
    return scene;
}

const Image& render(Stage& stage, const Scene& scene, std::int64_t frame) {
    Renderer& renderer = stage.renderer;
    renderer.begin_frame(scene.size.width, scene.size.height, kClear);
    if (scene.tiled) {
        for (int y = 0; y < scene.size.height + 64; y += 64) {
            for (int x = 0; x < scene.size.width + 64; x += 64) {
                renderer.draw_sprite(stage.ground, {static_cast<float>(x) + 32.0f, static_cast<float>(y) + 32.0f});
            }
        }
    }
    if (scene.world) {
        const float w = static_cast<float>(scene.size.width);
        const float h = static_cast<float>(scene.size.height);
        renderer.fill_rect({{0.0f, h - 40.0f}, {w, h}}, {70, 110, 60, 255});
        renderer.fill_rect({{w * 0.1f, h * 0.6f}, {w * 0.4f, h * 0.6f + 16.0f}}, {120, 90, 60, 255});
        renderer.fill_rect({{w * 0.6f, h * 0.35f}, {w * 0.9f, h * 0.35f + 16.0f}}, {120, 90, 60, 255});
    }
    for (const Actor& a : scene.actors) renderer.draw_sprite(stage.sprites[static_cast<std::size_t>(a.kind)], a.position, a.angle);
    if (scene.world) renderer.draw_text({8.0f, 8.0f}, "frame " + std::to_string(frame), {255, 255, 255, 255}, 2);
    return renderer.end_frame();
}

// A fresh folder under the system's temporary folder, removed with everything in it.
class TempFolder {
public:
    TempFolder() {
        std::string pattern = (fs::temp_directory_path() / "jostle_bench_XXXXXX").string();
        if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a folder like " + pattern);
        path_ = pattern;
    }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

bool same_pixels(const Image& a, const Image& b) { return a.width == b.width && a.height == b.height && a.rgba == b.rgba; }

// Inputs that cost seconds to make (rendered frames, reference encodings), made on first use
// and shared by the benchmarks that need them. Owned by main, so nothing is global.
class Inputs {
public:
    // One OSMesa frame of a plain scene of `sprites` still sprites (over ground tiles when
    // `tiled`), and the size of its PNG at libpng's defaults (the encode benchmarks' anchor)
    // and at zlib level 1 with libpng's filter choice (the size yardstick).
    struct Still {
        Image frame;
        std::size_t anchor_bytes = 0;
        std::size_t level1_bytes = 0;
    };
    const Still& still(Size size, int sprites, bool tiled) {
        const auto key = std::tuple{size.width, size.height, sprites, tiled};
        if (const auto found = stills_.find(key); found != stills_.end()) return found->second;
        Still s;
        Scene scene = make_scene(size, sprites, 0, false);
        scene.tiled = tiled;
        s.frame = render(stage(), scene, 0);
        s.anchor_bytes = encode_png(s.frame, kLibpngDefaults).size();
        s.level1_bytes = encode_png(s.frame, kLibpngLevel1).size();
        return stills_[key] = std::move(s);  // only once whole: a throw above caches nothing
    }

    // kRunFrames frames of a world scene where 4 of 100 sprites move (clustered or roaming),
    // and the bytes of the same frames as PNG files at jostle's encoding.
    struct Run {
        std::vector<Image> frames;
        std::size_t png_bytes = 0;
    };
    const Run& few_movers(Size size, bool cluster) {
        const auto key = std::tuple{size.width, size.height, cluster};
        if (const auto found = runs_.find(key); found != runs_.end()) return found->second;
        Run run;
        Scene scene = make_scene(size, 100, 4, true, cluster);
        for (int f = 0; f < kRunFrames; ++f) {
            run.frames.push_back(render(stage(), scene, f));
            run.png_bytes += encode_png(run.frames.back()).size();
            scene.step();
        }
        return runs_[key] = std::move(run);
    }

    static constexpr PngEncoding kLibpngDefaults{.encoder = PngEncoder::libpng, .compression_level = -1,
                                                 .filter = PngFilter::libpng_default};
    static constexpr PngEncoding kLibpngLevel1{.encoder = PngEncoder::libpng, .compression_level = 1,
                                               .filter = PngFilter::libpng_default};

private:
    Stage& stage() {
        if (!stage_) stage_ = std::make_unique<Stage>(RenderBackend::osmesa);
        return *stage_;
    }
    std::unique_ptr<Stage> stage_;
    std::map<std::tuple<int, int, int, bool>, Still> stills_;
    std::map<std::tuple<int, int, bool>, Run> runs_;
};

// Runs a benchmark body, turning an exception from setup (no OSMesa, a full disk) into a
// reported error instead of a crash.
void guarded(benchmark::State& state, const std::function<void()>& body) {
    try {
        body();
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

const char* backend_name(RenderBackend b) { return b == RenderBackend::null ? "null" : "osmesa"; }

// ---------------------------------------------------------------------------------------
// 1. Rendering a frame
// ---------------------------------------------------------------------------------------

// begin_frame .. end_frame of `sprites` still sprites. The null backend is the anchor: it pays
// the CPU side (building the batch) plus filling the image with the clear colour, which is
// most of its time (BM_Readback's null_empty_frame), so osmesa / null compares OSMesa's whole
// frame (rasterizing, clear and readback) with the CPU work every backend pays.
void bm_render_frame(benchmark::State& state, RenderBackend backend, Size size, int sprites) {
    guarded(state, [&] {
        Stage stage(backend);
        const Scene scene = make_scene(size, sprites, 0, false);
        // The first frame uploads the atlas and sizes the buffers; steady state is what counts.
        render(stage, scene, 0);
        for (auto _ : state) {
            const Image& image = render(stage, scene, 0);
            benchmark::DoNotOptimize(image.rgba.data());
        }
        state.counters["frames/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
        state.counters["draw_calls"] = stage.renderer.last_draw_calls();
        if (backend == RenderBackend::osmesa && stage.renderer.last_draw_calls() != 1) {
            state.SkipWithError("expected one draw call per frame");
        }
    });
}

// ---------------------------------------------------------------------------------------
// 2. Readback
// ---------------------------------------------------------------------------------------

// OSMesa renders into a buffer the backend owns, so there is no GPU-to-CPU transfer; getting
// the pixels out of an empty frame (begin_frame + end_frame, nothing drawn) costs the clear,
// glFinish (where Mesa copies its colour buffer into that buffer) and the backend's row flip
// (OSMesa's rows are bottom-up, Image rows top-down) into the Image. The anchor is that row
// flip alone, one memcpy per row as the backend does it: the floor any readback pays. The
// null backend's empty frame (filling the image with the clear colour) is shown as well.
void bm_readback_row_flip(benchmark::State& state, Size size) {
    const std::size_t row = static_cast<std::size_t>(size.width) * 4;
    const std::vector<std::uint8_t> from(row * static_cast<std::size_t>(size.height), 7);
    std::vector<std::uint8_t> to(from.size());
    for (auto _ : state) {
        for (int y = 0; y < size.height; ++y) {
            std::memcpy(to.data() + static_cast<std::size_t>(y) * row,
                        from.data() + static_cast<std::size_t>(size.height - 1 - y) * row, row);
        }
        benchmark::DoNotOptimize(to.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(from.size()));
}

void bm_readback_empty_frame(benchmark::State& state, RenderBackend backend, Size size) {
    guarded(state, [&] {
        Stage stage(backend);
        const Scene empty{size, {}, false};
        render(stage, empty, 0);
        for (auto _ : state) {
            const Image& image = render(stage, empty, 0);
            benchmark::DoNotOptimize(image.rgba.data());
        }
        state.SetBytesProcessed(state.iterations() * size.width * size.height * 4);
    });
}

// ---------------------------------------------------------------------------------------
// 3. PNG encoding
// ---------------------------------------------------------------------------------------

struct PngCandidate {
    const char* name;
    PngEncoding encoding;
};

// libpng's defaults (zlib level 6, adaptive filtering over all five filters) first: the anchor.
// "jostle" is PngEncoding{}, what frames are written with (png_io.h): the fast encoder, "up".
const PngCandidate kPngCandidates[] = {
    {"libpng_default", Inputs::kLibpngDefaults},
    {"libpng_l1", Inputs::kLibpngLevel1},  // the size yardstick: level 1, libpng's filter choice
    {"libpng_l1_up", {.encoder = PngEncoder::libpng, .compression_level = 1, .filter = PngFilter::up}},  // the old frame setting
    {"libpng_l1_rle_up", {.encoder = PngEncoder::libpng, .compression_level = 1, .filter = PngFilter::up, .rle = true}},
    {"jostle", {}},
    {"fast_sub", {.filter = PngFilter::sub}},
    {"fast_paeth", {.filter = PngFilter::paeth}},
    {"fast_adaptive", {.filter = PngFilter::adaptive}},
    {"fast_2_threads", {.threads = 2}},
};

// encode_png of one rendered frame, repeatedly. Three frames, because the best filter depends
// on the pixels: "1000" sprites (the busiest frame the render benchmarks draw; at 640x480 they
// cover the image three times over), "100" sprites on the flat clear colour (mostly empty
// background), and "tiles_100": 100 sprites over noisy ground tiles. Counters: the PNG's bytes,
// its size relative to libpng's defaults on the same frame (size_ratio) and relative to
// libpng at zlib level 1 with libpng's filter choice (size_l1; the issue asks <= 1.3).
void bm_png_encode(benchmark::State& state, Inputs& inputs, Size size, int sprites, bool tiled, PngEncoding encoding) {
    guarded(state, [&] {
        const Inputs::Still& still = inputs.still(size, sprites, tiled);
        std::vector<std::uint8_t> png = encode_png(still.frame, encoding);
        if (!same_pixels(decode_png(png, "encoded frame"), still.frame)) {
            state.SkipWithError("the PNG does not decode to the frame");
            return;
        }
        for (auto _ : state) {
            png = encode_png(still.frame, encoding);
            benchmark::DoNotOptimize(png.data());
        }
        state.counters["bytes"] = static_cast<double>(png.size());
        state.counters["size_ratio"] = static_cast<double>(png.size()) / static_cast<double>(still.anchor_bytes);
        state.counters["size_l1"] = static_cast<double>(png.size()) / static_cast<double>(still.level1_bytes);
        state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(still.frame.rgba.size()));
    });
}

// ---------------------------------------------------------------------------------------
// 4. The frame pipeline
// ---------------------------------------------------------------------------------------

// kRunFrames frames of a world scene (`sprites` moving sprites, so every frame differs, plus
// platforms and a HUD) rendered and written as PNG files in jostle's frame format
// (PngEncoding{}). Sequential renders, encodes and writes each frame before the next (the
// anchor); overlapped hands each frame to a FrameWriter, whose thread encodes and writes it
// while the next one renders: the engine's pipeline, end to end. Both write atomically
// (temporary file, fsync, rename), so the disk is in the figures too. On two cores the encoder
// competes with llvmpipe's own rasterizer threads, which caps the gain.
void bm_pipeline(benchmark::State& state, Size size, int sprites, bool overlapped) {
    guarded(state, [&] {
        Stage stage(RenderBackend::osmesa);
        const Scene start = make_scene(size, sprites, sprites, true);
        const TempFolder folder;
        render(stage, start, 0);
        for (auto _ : state) {
            Scene scene = start;  // the same frames every iteration
            if (overlapped) {
                FrameWriter writer(FrameWriterDesc{.folder = folder.path().string()});
                for (int f = 0; f < kRunFrames; ++f) {
                    writer.write(f, render(stage, scene, f));  // copies: the renderer reuses its image
                    scene.step();
                }
                writer.finish();
            } else {
                for (int f = 0; f < kRunFrames; ++f) {
                    write_png_atomic((folder.path() / frame_file_name(f)).string(), render(stage, scene, f));
                    scene.step();
                }
            }
        }
        state.counters["frames/s"] = benchmark::Counter(kRunFrames, benchmark::Counter::kIsIterationInvariantRate);
        const auto files = std::distance(fs::directory_iterator(folder.path()), fs::directory_iterator{});
        if (files != kRunFrames) state.SkipWithError("the folder does not hold one file per frame");
        // The last file holds the last frame.
        Scene last = start;
        for (int f = 0; f + 1 < kRunFrames; ++f) last.step();
        if (!same_pixels(read_png((folder.path() / frame_file_name(kRunFrames - 1)).string()), render(stage, last, kRunFrames - 1))) {
            state.SkipWithError("the last frame's file does not hold the last frame");
        }
    });
}

// ---------------------------------------------------------------------------------------
// 5. Animated PNG
// ---------------------------------------------------------------------------------------

// The same kRunFrames frames (rendered beforehand; only the writing is timed) as PNG files
// at jostle's encoding (the anchor) or as one APNG by AnimationWriter, which stores only the
// rectangle around each frame's changed pixels. 4 of 100 sprites move and a HUD counts frames:
// "clustered" keeps the movers together, "roaming" lets them spread over the image: the changed
// rectangle is then one box around changes far apart, most of it unchanged pixels (stored
// transparent, drawn OVER the previous frame).
void bm_animation(benchmark::State& state, Inputs& inputs, Size size, bool cluster, bool apng) {
    guarded(state, [&] {
        const Inputs::Run& run = inputs.few_movers(size, cluster);
        const TempFolder folder;
        const std::string apng_path = (folder.path() / "run.png").string();
        for (auto _ : state) {
            if (apng) {
                AnimationWriter writer(apng_path);
                for (const Image& frame : run.frames) writer.add(frame);
                writer.finish();
            } else {
                for (int f = 0; f < kRunFrames; ++f) {
                    write_png_atomic((folder.path() / frame_file_name(f)).string(), run.frames[static_cast<std::size_t>(f)]);
                }
            }
        }
        std::uintmax_t bytes = 0;
        for (const fs::directory_entry& e : fs::directory_iterator(folder.path())) bytes += e.file_size();
        state.counters["bytes"] = static_cast<double>(bytes);
        state.counters["size_ratio"] = static_cast<double>(bytes) / static_cast<double>(run.png_bytes);
        state.counters["frames/s"] = benchmark::Counter(kRunFrames, benchmark::Counter::kIsIterationInvariantRate);
        // A viewer that knows only PNG shows the first frame: it must be the first frame.
        if (apng && !same_pixels(read_png(apng_path), run.frames.front())) {
            state.SkipWithError("the APNG's first frame is not the first frame");
        }
    });
}

// ---------------------------------------------------------------------------------------
// Registration
// ---------------------------------------------------------------------------------------

// Registers one benchmark; anchors carry the label "anchor" (tools/bench-ratios looks for it).
template <class Fn>
void add(const std::string& name, bool anchor, Fn&& fn) {
    benchmark::RegisterBenchmark(name.c_str(),
                                 [anchor, fn = std::forward<Fn>(fn)](benchmark::State& state) {
                                     fn(state);
                                     if (anchor) state.SetLabel("anchor");
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
}

std::string size_name(Size s) { return std::to_string(s.width) + "/" + std::to_string(s.height); }

void register_all(Inputs& inputs) {
    for (const Size size : kSizes) {
        for (const int sprites : {100, 1000}) {
            for (const RenderBackend backend : {RenderBackend::null, RenderBackend::osmesa}) {
                add("BM_RenderFrame/" + size_name(size) + "/" + std::to_string(sprites) + "/" + backend_name(backend),
                    backend == RenderBackend::null,
                    [=](benchmark::State& s) { bm_render_frame(s, backend, size, sprites); });
            }
        }
    }
    for (const Size size : kSizes) {
        const std::string base = "BM_Readback/" + size_name(size) + "/";
        add(base + "row_flip", true, [=](benchmark::State& s) { bm_readback_row_flip(s, size); });
        add(base + "null_empty_frame", false, [=](benchmark::State& s) { bm_readback_empty_frame(s, RenderBackend::null, size); });
        add(base + "osmesa_empty_frame", false, [=](benchmark::State& s) { bm_readback_empty_frame(s, RenderBackend::osmesa, size); });
    }
    struct PngFrame {
        const char* name;
        int sprites;
        bool tiled;
    };
    for (const Size size : kSizes) {
        for (const PngFrame frame : {PngFrame{"100", 100, false}, PngFrame{"1000", 1000, false}, PngFrame{"tiles_100", 100, true}}) {
            for (const PngCandidate& c : kPngCandidates) {
                const PngEncoding encoding = c.encoding;
                add("BM_PngEncode/" + size_name(size) + "/" + frame.name + "/" + c.name, &c == &kPngCandidates[0],
                    [=, &inputs](benchmark::State& s) { bm_png_encode(s, inputs, size, frame.sprites, frame.tiled, encoding); });
            }
        }
    }
    for (const Size size : kSizes) {
        for (const int sprites : {100, 1000}) {
            for (const bool overlapped : {false, true}) {
                add("BM_Pipeline/" + size_name(size) + "/" + std::to_string(sprites) + "/" + (overlapped ? "overlapped" : "sequential"),
                    !overlapped, [=](benchmark::State& s) { bm_pipeline(s, size, sprites, overlapped); });
            }
        }
    }
    for (const Size size : kSizes) {
        for (const bool cluster : {true, false}) {
            for (const bool apng : {false, true}) {
                add("BM_Animation/" + size_name(size) + "/" + (cluster ? "clustered" : "roaming") + "/" + (apng ? "apng" : "png_files"),
                    !apng, [=, &inputs](benchmark::State& s) { bm_animation(s, inputs, size, cluster, apng); });
            }
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    Inputs inputs;
    register_all(inputs);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
