// png_io.cpp: reading any PNG as RGBA8 and encoding RGBA8 PNGs (in memory, then written
// atomically by AtomicFile), with libpng; PngEncoder::fast hands encoding to png_fast.cpp.
// libpng reports errors by longjmp. Every setjmp sits in a small function whose frame holds
// only trivially destructible objects, so a longjmp never skips a C++ destructor; whatever
// owns memory or a file (PngRead, PngWrite) lives in the caller and cleans up there.
#include "jostle/render/png_io.h"

#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>

#include "jostle/core/atomic_file.h"
#include "jostle/core/error.h"
#include "png_fast.h"

namespace jostle {
namespace {

// What the libpng callbacks report back: plain C data, safe to touch across a longjmp.
struct PngStatus {
    char message[256];
    int saved_errno;  // errno of a failed fwrite/fflush in the write callbacks, else 0
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
    auto* status = static_cast<PngStatus*>(png_get_error_ptr(png));
    std::snprintf(status->message, sizeof status->message, "%s", message ? message : "libpng error");
    png_longjmp(png, 1);
}

// Warnings (a bad CRC in an ancillary chunk, an odd colour profile) do not stop the read
// and are not printed: the image is still well defined.
void on_png_warning(png_structp, png_const_charp) {}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw InputError(SourceLocation{path, 0, 0}, what);
}

// ---------------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------------

// Owns the file and the libpng read structures. The bytes come from `file`, or from
// memory (`data`, `size`, read position `at`) when file is null.
struct PngRead {
    std::FILE* file = nullptr;
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
    std::size_t at = 0;
    png_structp png = nullptr;
    png_infop info = nullptr;
    PngStatus status{};

    PngRead() = default;
    PngRead(const PngRead&) = delete;
    PngRead& operator=(const PngRead&) = delete;
    ~PngRead() {
        if (png != nullptr) png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
        if (file != nullptr) std::fclose(file);
    }
};

// libpng's allocations while reading. It allocates an ancillary chunk's declared length (up
// to 2 GiB) before reading the chunk, even past its own chunk limit, so a 100-byte file could
// make it ask for gigabytes (found by tests/fuzz/png_fuzz.cpp). Its real needs are rows
// (16384 px * 8 bytes), zlib's state and small chunks; a request above 16 MiB is refused, which
// libpng handles as a chunk it cannot keep (the file then fails as truncated or corrupt). The
// pixels themselves are jostle's own allocation, bounded by kMaxImagePixels.
constexpr png_alloc_size_t kMaxLibpngAllocation = png_alloc_size_t{16} << 20;
png_voidp bounded_malloc(png_structp, png_alloc_size_t size) {
    return size <= kMaxLibpngAllocation ? std::malloc(size) : nullptr;
}
void bounded_free(png_structp, png_voidp p) { std::free(p); }

// Read callback: tells a truncated file from a failed read.
void read_bytes(png_structp png, png_bytep data, png_size_t length) {
    auto* r = static_cast<PngRead*>(png_get_io_ptr(png));
    if (r->file == nullptr) {
        if (r->size - r->at < length) png_error(png, "unexpected end of file (truncated)");
        std::memcpy(data, r->data + r->at, length);
        r->at += length;
        return;
    }
    if (std::fread(data, 1, length, r->file) != length) {
        png_error(png, std::ferror(r->file) ? "read error" : "unexpected end of file (truncated)");
    }
}

// Phase 1: reads the chunks up to the image data. Allocates nothing in proportion to the
// image size. Returns false (message in r.status) on a libpng error.
bool read_png_header(PngRead& r, png_uint_32* width, png_uint_32* height) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_set_read_fn(r.png, &r, read_bytes);
    png_set_sig_bytes(r.png, 8);
    // libpng's own size limit (1e6 per side by default) would fail inside png_read_info with
    // a less useful message; read_png checks kMaxImageSide itself right after this.
    png_set_user_limits(r.png, 0x7fffffffU, 0x7fffffffU);
    // Text and colour-profile chunks inflate to at most this much (libpng's own bound is none).
    png_set_chunk_malloc_max(r.png, kMaxLibpngAllocation);
    png_read_info(r.png, r.info);
    *width = png_get_image_width(r.png, r.info);
    *height = png_get_image_height(r.png, r.info);
    return true;
}

// Phase 2: sets up the conversion to RGBA8 and decodes into `rows` (allocated by the caller
// for height rows of width * 4 bytes), then reads the chunks after the image so a bad CRC or
// a truncated file is noticed. Returns false (message in r.status) on a libpng error.
bool read_png_pixels(PngRead& r, png_bytep* rows, png_size_t row_bytes) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    const int color_type = png_get_color_type(r.png, r.info);
    const int bit_depth = png_get_bit_depth(r.png, r.info);
    const bool has_trns = png_get_valid(r.png, r.info, PNG_INFO_tRNS) != 0;
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r.png);
    if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(r.png);
    if (has_trns) png_set_tRNS_to_alpha(r.png);
    if (bit_depth == 16) png_set_scale_16(r.png);  // rounds, unlike png_set_strip_16
    if (color_type == PNG_COLOR_TYPE_GRAY || color_type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(r.png);
    if ((color_type & PNG_COLOR_MASK_ALPHA) == 0 && !has_trns) png_set_add_alpha(r.png, 0xff, PNG_FILLER_AFTER);
    png_set_interlace_handling(r.png);
    png_read_update_info(r.png, r.info);
    if (png_get_rowbytes(r.png, r.info) != row_bytes || png_get_bit_depth(r.png, r.info) != 8 ||
        png_get_channels(r.png, r.info) != 4) {
        png_error(r.png, "unsupported pixel format (cannot convert it to RGBA8)");
    }
    png_read_image(r.png, rows);
    png_read_end(r.png, nullptr);
    return true;
}

// ---------------------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------------------

// Appends libpng's output to a byte vector; there is nothing to flush.
void write_to_memory(png_structp png, png_bytep data, png_size_t length) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + length);
}

void flush_nothing(png_structp) {}

// Owns the libpng write structures.
struct PngWrite {
    png_structp png = nullptr;
    png_infop info = nullptr;
    PngStatus status{};

    PngWrite() = default;
    PngWrite(const PngWrite&) = delete;
    PngWrite& operator=(const PngWrite&) = delete;
    ~PngWrite() {
        if (png != nullptr) png_destroy_write_struct(&png, info != nullptr ? &info : nullptr);
    }
};

// Encodes RGBA8 rows into `out`. Returns false (message in w.status) on a libpng error.
bool write_png_data(PngWrite& w, std::vector<std::uint8_t>* out, png_bytep* rows, png_uint_32 width,
                    png_uint_32 height, const PngEncoding& encoding) {
    if (setjmp(png_jmpbuf(w.png))) return false;
    png_set_write_fn(w.png, out, write_to_memory, flush_nothing);
    if (encoding.compression_level >= 0) png_set_compression_level(w.png, encoding.compression_level);
    if (encoding.filter == PngFilter::none) png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    if (encoding.filter == PngFilter::sub) png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    if (encoding.filter == PngFilter::up) png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
    if (encoding.filter == PngFilter::paeth) png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_PAETH);
    if (encoding.filter == PngFilter::adaptive) png_set_filter(w.png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
    if (encoding.rle) png_set_compression_strategy(w.png, Z_RLE);
    png_set_IHDR(w.png, w.info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(w.png, w.info);
    png_write_image(w.png, rows);
    png_write_end(w.png, nullptr);
    return true;
}

// Reads the header and the pixels of the PNG whose signature `r` has just consumed; `name`
// (a path, or what the bytes are) goes into the error messages.
Image decode_after_signature(PngRead& r, const std::string& name) {
    r.png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &r.status, on_png_error, on_png_warning, nullptr,
                                     bounded_malloc, bounded_free);
    if (r.png != nullptr) r.info = png_create_info_struct(r.png);
    if (r.png == nullptr || r.info == nullptr) fail(name, "cannot read: out of memory");

    png_uint_32 width = 0;
    png_uint_32 height = 0;
    if (!read_png_header(r, &width, &height)) fail(name, std::string("corrupt PNG: ") + r.status.message);
    if (width > static_cast<png_uint_32>(kMaxImageSide) || height > static_cast<png_uint_32>(kMaxImageSide) ||
        std::int64_t{width} * std::int64_t{height} > kMaxImagePixels) {
        fail(name, "image is " + std::to_string(width) + " x " + std::to_string(height) +
                       " pixels; the limit is " + std::to_string(kMaxImageSide) + " x " +
                       std::to_string(kMaxImageSide) + " and " + std::to_string(kMaxImagePixels) +
                       " pixels in total");
    }

    Image image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    const std::size_t row_bytes = std::size_t{width} * 4;
    image.rgba.resize(row_bytes * height);
    std::vector<png_bytep> rows(height);
    for (std::size_t y = 0; y < height; ++y) rows[y] = image.rgba.data() + y * row_bytes;
    if (!read_png_pixels(r, rows.data(), row_bytes)) fail(name, std::string("corrupt PNG: ") + r.status.message);
    return image;
}

}  // namespace

Image read_png(const std::string& path) {
    PngRead r;
    r.file = std::fopen(path.c_str(), "rb");
    if (r.file == nullptr) {
        const int e = errno;
        fail(path, std::string("cannot open: ") + std::strerror(e));
    }
    png_byte signature[8] = {};
    const std::size_t got = std::fread(signature, 1, sizeof signature, r.file);
    if (got != sizeof signature && std::ferror(r.file)) {
        const int e = errno;
        // Said as the text files say it (core/text.cpp), not as strerror's "Is a directory".
        fail(path, e == EISDIR ? std::string("is a folder, expected a PNG file") : std::string("cannot read: ") + std::strerror(e));
    }
    if (got != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
        fail(path, "not a PNG file (no PNG signature)");
    }
    return decode_after_signature(r, path);
}

Image decode_png(std::span<const std::uint8_t> bytes, const std::string& name) {
    if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) fail(name, "not a PNG file (no PNG signature)");
    PngRead r;
    r.data = bytes.data();
    r.size = bytes.size();
    r.at = 8;
    return decode_after_signature(r, name);
}

namespace {

// The sides an encoder takes (an Image's, or a rectangle's of one).
void check_sides(int width, int height) {
    JOSTLE_ASSERT(width >= 1 && width <= kMaxImageSide && height >= 1 && height <= kMaxImageSide,
                  "encode_png: image sides must be in 1..kMaxImageSide");
    JOSTLE_ASSERT(std::int64_t{width} * height <= kMaxImagePixels, "encode_png: image has more than kMaxImagePixels pixels");
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image, const PngEncoding& encoding) {
    check_sides(image.width, image.height);
    JOSTLE_ASSERT(image.rgba.size() == static_cast<std::size_t>(image.width) * 4 * static_cast<std::size_t>(image.height),
                  "encode_png: rgba.size() must be width * height * 4");
    return detail::encode_png_rows(detail::rows_of(image), encoding);
}

std::vector<std::uint8_t> detail::encode_png_rows(const PixelRows& image, const PngEncoding& encoding) {
    check_sides(image.width, image.height);
    JOSTLE_ASSERT(image.stride >= static_cast<std::size_t>(image.width) * 4, "encode_png: rows overlap");
    JOSTLE_ASSERT(encoding.compression_level >= -1 && encoding.compression_level <= 9,
                  "encode_png: compression level must be in 0..9 (or -1, libpng's default)");
    JOSTLE_ASSERT(encoding.threads >= 1 && encoding.threads <= 16, "encode_png: threads must be in 1..16");
    if (encoding.encoder == PngEncoder::fast) return detail::encode_png_fast(image, encoding.filter, encoding.threads);

    std::vector<std::uint8_t> out;
    // Raw size plus a little: one reservation covers all but incompressible noise.
    out.reserve(static_cast<std::size_t>(image.width) * 4 * static_cast<std::size_t>(image.height) / 2 + 1024);
    PngWrite w;
    w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w.status, on_png_error, on_png_warning);
    if (w.png != nullptr) w.info = png_create_info_struct(w.png);
    if (w.png == nullptr || w.info == nullptr) throw std::bad_alloc();
    // libpng does not modify the rows it writes; its API just lacks the const.
    std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
    for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = const_cast<png_bytep>(image.row(static_cast<int>(y)));
    const bool ok = write_png_data(w, &out, rows.data(), static_cast<png_uint_32>(image.width),
                                   static_cast<png_uint_32>(image.height), encoding);
    // Encoding into memory fails only when memory runs out.
    if (!ok) throw std::bad_alloc();
    return out;
}

void write_png_atomic(const std::string& path, const Image& image, const PngEncoding& encoding) {
    const std::vector<std::uint8_t> bytes = encode_png(image, encoding);
    write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void write_png_atomic(const std::string& path, const Image& image, int compression_level) {
    JOSTLE_ASSERT(compression_level >= 0 && compression_level <= 9,
                  "write_png_atomic: compression level must be in 0..9");
    write_png_atomic(path, image, PngEncoding{.encoder = PngEncoder::libpng, .compression_level = compression_level});
}

}  // namespace jostle
