// tests/fuzz/png_fuzz.cpp: fuzzes decode_png (engine/render/src/png_io.cpp), the reader behind
// read_png (sprites, `jostle imgdiff`, query masks). Bad bytes must be an InputError naming the
// input; a decoded image must be within the documented limits with exactly width*height*4 bytes,
// and (when small) survive jostle's own encoder and the reader again unchanged.
#include <cstring>
#include <span>
#include <string>

#include "fuzz_support.h"
#include "jostle/core/error.h"
#include "jostle/render/png_io.h"

using jostle::fuzz::fuzz_fail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    jostle::Image image;
    try {
        image = jostle::decode_png(std::span<const std::uint8_t>(data, size), "fuzz.png");
    } catch (const jostle::InputError& e) {
        if (std::strstr(e.what(), "fuzz.png") == nullptr) fuzz_fail(std::string("error without its source: ") + e.what());
        return 0;
    }
    if (image.width < 1 || image.height < 1 || image.width > jostle::kMaxImageSide || image.height > jostle::kMaxImageSide ||
        std::int64_t{image.width} * image.height > jostle::kMaxImagePixels ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4u) {
        fuzz_fail("decoded image out of limits or of the wrong size: " + std::to_string(image.width) + " x " +
                  std::to_string(image.height) + ", " + std::to_string(image.rgba.size()) + " bytes");
    }
    if (std::int64_t{image.width} * image.height <= (1 << 16)) {
        const std::vector<std::uint8_t> png = jostle::encode_png(image);
        const jostle::Image again = jostle::decode_png(png, "re-encoded.png");
        if (again.width != image.width || again.height != image.height || again.rgba != image.rgba) {
            fuzz_fail("encode_png then decode_png changed the image");
        }
    }
    return 0;
}
