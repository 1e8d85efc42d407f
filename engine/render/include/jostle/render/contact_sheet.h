// jostle/render/contact_sheet.h: many frames in one picture. A grid of thumbnails, each
// labelled with its frame number, so a person sees a whole run at a glance.
#pragma once

#include <cstdint>
#include <span>

#include "jostle/render/png_io.h"
#include "jostle/render/renderer.h"

namespace jostle {

struct SheetFrame {
    std::int64_t frame = 0;         // the label: "frame 123"
    const Image* image = nullptr;   // borrowed for the call
};

struct SheetDesc {
    int columns = 0;        // 0: as square a grid as the frame count allows
    int thumb_width = 0;    // 0: the first frame's width, at most 320 px
    Color background{32, 32, 32, 255};
    Color label{255, 255, 255, 255};
};

// The sheet: cells of thumb_width x (the aspect-correct height of the first frame), each
// frame scaled to fit its cell by nearest pixels (centred, letterboxed), a label row under
// each, 4 px gaps. Pure CPU work: the same frames give the same bytes. An empty list gives an
// empty Image.
Image contact_sheet(std::span<const SheetFrame> frames, const SheetDesc& desc = {});

}  // namespace jostle
