// jostle/render/animation.h: a run as one animated PNG (APNG), so a person sees it in one
// file. APNG is lossless RGBA (GIF would cut every frame to 256 colours) and every current
// browser plays it; viewers that know only PNG show the first frame.
//
// The file stays small for game footage, where most pixels stay put from frame to frame:
// each frame after the first stores only the rectangle around the pixels that changed, with
// the pixels that did not change made transparent and the rectangle drawn over the previous
// frame with blend op OVER (dispose op NONE), so that a few sprites moving far apart cost
// little more than their own pixels; a rectangle with a changed pixel that is not opaque is
// stored as it is, with blend op SOURCE. A frame equal to the previous one stores nothing
// and lengthens the previous frame's display time instead.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "jostle/render/png_io.h"

namespace jostle {

struct AnimationDesc {
    // Each added frame shows for delay_num / delay_den seconds: 1/60 is one tick of a 60 Hz
    // game, 5/60 when only every 5th tick is kept. Both in 1..65535.
    int delay_num = 1;
    int delay_den = 60;
    int loops = 0;            // plays this many times; 0 loops forever
    PngEncoding encoding{};   // how each frame's pixels are compressed
};

// Writes an animated PNG frame by frame, keeping only the previous frame in memory. The file
// is atomic (AtomicFile): it appears, whole, on finish(); destroying the writer before that
// leaves no file and the old one, if any, untouched.
class AnimationWriter {
public:
    // Creates the temporary file. Throws InputError naming the path when it cannot, or when
    // the desc is out of range ("delay_num 0: expected 1..65535").
    explicit AnimationWriter(std::string path, const AnimationDesc& desc = {});
    ~AnimationWriter();
    AnimationWriter(const AnimationWriter&) = delete;
    AnimationWriter& operator=(const AnimationWriter&) = delete;

    // Appends a frame. Every frame has the first frame's size (asserted: the caller renders
    // them all at one size). Throws InputError on a write error.
    void add(const Image& frame);
    // Writes the end and renames the file into place. At least one frame must have been
    // added (InputError naming the path otherwise). Throws InputError on a write error.
    void finish();

    std::int64_t frames_added() const;
    std::int64_t frames_stored() const;  // APNG frames in the file (equal runs merge into one)

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace jostle
