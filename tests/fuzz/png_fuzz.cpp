// tests/fuzz/png_fuzz.cpp: fuzzes decode_png (engine/render/src/png_io.cpp), the reader behind
// read_png (sprites, `jostle imgdiff`, query masks). Bad bytes must be an InputError naming the
// input; a decoded image must be within the documented limits with exactly width*height*4 bytes,
// and (when small) survive jostle's own encoder and the reader again unchanged; a rectangle of it,
// chosen by the input's bytes, encodes in place (as an animation frame does) to the bytes of
// its copy, with both encoders.
#include <cstring>
#include <span>
#include <string>

#include "fuzz_support.h"
#include "jostle/core/error.h"
#include "jostle/render/png_io.h"
#include "pixel_rows.h"  // engine/render/src (private): detail::encode_png_rows

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
        // The rectangle from the input's last bytes (any rectangle inside the image).
        const auto byte = [&](std::size_t k) { return size > k ? static_cast<int>(data[size - 1 - k]) : 0; };
        const int x = byte(0) % image.width, y = byte(1) % image.height;
        const int w = 1 + byte(2) % (image.width - x), h = 1 + byte(3) % (image.height - y);
        jostle::Image copy;
        copy.width = w;
        copy.height = h;
        for (int row = y; row < y + h; ++row) {
            const auto* first = image.rgba.data() + (static_cast<std::size_t>(row) * static_cast<std::size_t>(image.width) +
                                                     static_cast<std::size_t>(x)) * 4;
            copy.rgba.insert(copy.rgba.end(), first, first + static_cast<std::size_t>(w) * 4);
        }
        for (const jostle::PngEncoding& e : {jostle::PngEncoding{}, jostle::PngEncoding{.encoder = jostle::PngEncoder::libpng}}) {
            if (jostle::detail::encode_png_rows(jostle::detail::rows_of(image, x, y, w, h), e) != jostle::encode_png(copy, e)) {
                fuzz_fail("a rectangle encoded in place differs from its copy encoded");
            }
        }
    }
    return 0;
}
