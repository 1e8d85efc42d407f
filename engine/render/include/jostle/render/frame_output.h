// jostle/render/frame_output.h: choosing which frames to keep and writing them as PNG files.
// FrameSelection answers "is frame N wanted?" for --frames/--every; FrameWriter encodes and
// writes frames on its own thread, so rendering the next frame overlaps encoding this one.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jostle/render/png_io.h"

namespace jostle {

// Frames are numbered from 0 (the state after tick 0's step is frame 0). A selection is a
// list of ranges, and optionally every Nth frame of each range counted from its first frame.
class FrameSelection {
public:
    // Everything (the default).
    FrameSelection() = default;

    // "all", or a comma-separated list of frames and ranges: "120", "10-20", "300-" (to the
    // end), "0-9,50,100-". On bad text returns nullopt and, if error is given, says what was
    // expected ("frames '10-5': range ends before it starts").
    static std::optional<FrameSelection> parse(std::string_view text, std::string* error = nullptr);

    // Keep every nth frame of each range, counted from the range's first frame (n >= 1;
    // asserted). "10-20" every 5 is 10, 15, 20; "all" every 5 is 0, 5, 10, ...
    void set_every(std::int64_t n);
    std::int64_t every() const { return every_; }

    bool contains(std::int64_t frame) const;
    // The last frame wanted, or nullopt when a range is open (runs to the end).
    std::optional<std::int64_t> last() const;

private:
    struct Range {
        std::int64_t first = 0;
        std::int64_t last = INT64_MAX;  // inclusive
    };
    std::vector<Range> ranges_{Range{}};
    std::int64_t every_ = 1;
};

// "frame_000123.png": the prefix, the frame number zero-padded to at least `digits` digits.
std::string frame_file_name(std::int64_t frame, std::string_view prefix = "frame_", int digits = 6);

struct FrameWriterDesc {
    std::string folder;          // created when missing
    PngEncoding encoding{};      // jostle's fast encoder, "up" filter, one thread (png_io.h)
    int max_queued = 4;          // frames waiting for the encoder before write() blocks
};

// Writes frames as folder/frame_NNNNNN.png on a thread of its own; every file is written
// atomically (write_png_atomic), so an interrupted run never leaves a half-written image.
class FrameWriter {
public:
    // Throws InputError naming the folder when it cannot be created.
    explicit FrameWriter(const FrameWriterDesc& desc);
    // Waits for the queued frames; errors are dropped here (call finish() to see them). When
    // it runs while an exception unwinds (a failed or interrupted run), the folders the
    // constructor created are removed if they are still empty.
    ~FrameWriter();
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;

    // Queues a frame (blocking while max_queued frames wait). Throws the first write error
    // seen so far, if any (later frames are then not written).
    void write(std::int64_t frame, Image image);
    // Waits until every queued frame is on disk; throws the first write error, if any.
    void finish();
    // The paths of the frames queued so far, in order (all on disk after finish()).
    std::vector<std::string> written() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace jostle
