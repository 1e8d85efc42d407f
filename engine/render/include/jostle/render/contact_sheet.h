// jostle/render/contact_sheet.h: many frames in one picture. A grid of thumbnails, each
// labelled with its frame number, so a person sees a whole run at a glance.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

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
// empty Image. (Frames that are not a whole image, e.g. empty, get their label only; the
// first whole one sets the cell size.)
Image contact_sheet(std::span<const SheetFrame> frames, const SheetDesc& desc = {});

// The same sheet built a frame at a time, for a caller that renders its frames over a long
// run: each frame is drawn into its cell when added and need not be kept (a sheet of 64
// frames at 1280x720 would otherwise hold 236 MB of frames until the end). Given the same
// frames in the same order, finish() returns contact_sheet()'s bytes exactly.
class ContactSheetBuilder {
public:
    // `count`: how many frames the sheet will have (it fixes the grid).
    explicit ContactSheetBuilder(int count, const SheetDesc& desc = {});
    void add(std::int64_t frame, const Image& image);
    // The sheet; frames not added leave their cells empty (no label). Call once.
    Image finish();

private:
    void start(const Image* first);
    void draw(int cell, std::int64_t frame, const Image* image);
    bool started() const { return columns_ > 0; }  // the grid is laid out (start() ran)

    int count_;
    SheetDesc desc_;
    int added_ = 0;
    int columns_ = 0, thumb_w_ = 0, thumb_h_ = 0;
    Image sheet_;
    std::vector<std::int64_t> waiting_;  // labels of frames added before the first whole one
};

}  // namespace jostle
