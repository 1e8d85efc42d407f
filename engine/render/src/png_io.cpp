// png_io.cpp: reading any PNG as RGBA8 and writing RGBA8 PNGs atomically, with libpng.
// libpng reports errors by longjmp. Every setjmp sits in a small function whose frame holds
// only trivially destructible objects, so a longjmp never skips a C++ destructor; whatever
// owns memory or a file (PngRead, PngWrite, TempFile) lives in the caller and cleans up there.
#include "jostle/render/png_io.h"

#include <fcntl.h>
#include <png.h>
#include <unistd.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "jostle/core/error.h"

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

// Owns the file and the libpng read structures.
struct PngRead {
    std::FILE* file = nullptr;
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

// fread callback: tells a truncated file from a failed read.
void read_from_file(png_structp png, png_bytep data, png_size_t length) {
    auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
    if (std::fread(data, 1, length, file) != length) {
        png_error(png, std::ferror(file) ? "read error" : "unexpected end of file (truncated)");
    }
}

// Phase 1: reads the chunks up to the image data. Allocates nothing in proportion to the
// image size. Returns false (message in r.status) on a libpng error.
bool read_png_header(PngRead& r, png_uint_32* width, png_uint_32* height) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_set_read_fn(r.png, r.file, read_from_file);
    png_set_sig_bytes(r.png, 8);
    // libpng's own size limit (1e6 per side by default) would fail inside png_read_info with
    // a less useful message; read_png checks kMaxImageSide itself right after this.
    png_set_user_limits(r.png, 0x7fffffffU, 0x7fffffffU);
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

// fwrite/fflush callbacks that keep errno, so "No space left on device" reaches the message.
void write_to_file(png_structp png, png_bytep data, png_size_t length) {
    auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
    if (std::fwrite(data, 1, length, file) != length) {
        static_cast<PngStatus*>(png_get_error_ptr(png))->saved_errno = errno;
        png_error(png, "write error");
    }
}

void flush_file(png_structp png) {
    auto* file = static_cast<std::FILE*>(png_get_io_ptr(png));
    if (std::fflush(file) != 0) {
        static_cast<PngStatus*>(png_get_error_ptr(png))->saved_errno = errno;
        png_error(png, "write error");
    }
}

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

// Encodes RGBA8 rows into `file`. Returns false (message in w.status) on a libpng error.
bool write_png_data(PngWrite& w, std::FILE* file, png_bytep* rows, png_uint_32 width, png_uint_32 height,
                    int compression_level) {
    if (setjmp(png_jmpbuf(w.png))) return false;
    png_set_write_fn(w.png, file, write_to_file, flush_file);
    png_set_compression_level(w.png, compression_level);
    png_set_IHDR(w.png, w.info, width, height, 8, PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(w.png, w.info);
    png_write_image(w.png, rows);
    png_write_end(w.png, nullptr);
    return true;
}

// A temporary file next to the target; removed on destruction unless renamed into place.
struct TempFile {
    std::string path;
    std::FILE* file = nullptr;
    bool renamed = false;

    TempFile() = default;
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    ~TempFile() {
        if (file != nullptr) std::fclose(file);
        if (!path.empty() && !renamed) ::unlink(path.c_str());
    }
};

// Creates "<path>.<pid>.<n>.tmp" with O_EXCL (so two writers never share one), mode 0666
// minus the umask, like any new file.
void create_temp_file(const std::string& path, TempFile* temp) {
    const std::string prefix = path + "." + std::to_string(::getpid()) + ".";
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::string name = prefix + std::to_string(attempt) + ".tmp";
        const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            if (errno == EEXIST) continue;
            const int e = errno;
            fail(path, "cannot write: cannot create temporary file " + name + ": " + std::strerror(e));
        }
        temp->path = std::move(name);
        temp->file = ::fdopen(fd, "wb");
        if (temp->file == nullptr) {
            const int e = errno;
            ::close(fd);
            fail(path, std::string("cannot write: ") + std::strerror(e));
        }
        return;
    }
    fail(path, "cannot write: 100 temporary files " + prefix + "*.tmp already exist");
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
        fail(path, std::string("cannot read: ") + std::strerror(e));
    }
    if (got != sizeof signature || png_sig_cmp(signature, 0, sizeof signature) != 0) {
        fail(path, "not a PNG file (no PNG signature)");
    }

    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r.status, on_png_error, on_png_warning);
    if (r.png != nullptr) r.info = png_create_info_struct(r.png);
    if (r.png == nullptr || r.info == nullptr) fail(path, "cannot read: out of memory");

    png_uint_32 width = 0;
    png_uint_32 height = 0;
    if (!read_png_header(r, &width, &height)) fail(path, std::string("corrupt PNG: ") + r.status.message);
    if (width > static_cast<png_uint_32>(kMaxImageSide) || height > static_cast<png_uint_32>(kMaxImageSide) ||
        std::int64_t{width} * std::int64_t{height} > kMaxImagePixels) {
        fail(path, "image is " + std::to_string(width) + " x " + std::to_string(height) +
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
    if (!read_png_pixels(r, rows.data(), row_bytes)) fail(path, std::string("corrupt PNG: ") + r.status.message);
    return image;
}

void write_png_atomic(const std::string& path, const Image& image, int compression_level) {
    JOSTLE_ASSERT(image.width >= 1 && image.width <= kMaxImageSide && image.height >= 1 &&
                      image.height <= kMaxImageSide,
                  "write_png_atomic: image sides must be in 1..kMaxImageSide");
    JOSTLE_ASSERT(std::int64_t{image.width} * image.height <= kMaxImagePixels,
                  "write_png_atomic: image has more than kMaxImagePixels pixels");
    const std::size_t row_bytes = static_cast<std::size_t>(image.width) * 4;
    JOSTLE_ASSERT(image.rgba.size() == row_bytes * static_cast<std::size_t>(image.height),
                  "write_png_atomic: rgba.size() must be width * height * 4");
    JOSTLE_ASSERT(compression_level >= 0 && compression_level <= 9,
                  "write_png_atomic: compression level must be in 0..9");

    TempFile temp;
    create_temp_file(path, &temp);

    {
        PngWrite w;
        w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &w.status, on_png_error, on_png_warning);
        if (w.png != nullptr) w.info = png_create_info_struct(w.png);
        if (w.png == nullptr || w.info == nullptr) fail(path, "cannot write: out of memory");
        // libpng does not modify the rows it writes; its API just lacks the const.
        std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
        auto* pixels = const_cast<png_bytep>(image.rgba.data());
        for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = pixels + y * row_bytes;
        if (!write_png_data(w, temp.file, rows.data(), static_cast<png_uint_32>(image.width),
                            static_cast<png_uint_32>(image.height), compression_level)) {
            const int e = w.status.saved_errno;
            fail(path, std::string("cannot write: ") + (e != 0 ? std::strerror(e) : w.status.message));
        }
    }

    // Flush to the disk before the rename, so the name never points at data still in flight.
    if (std::fflush(temp.file) != 0 || ::fsync(::fileno(temp.file)) != 0) {
        const int e = errno;
        fail(path, std::string("cannot write: ") + std::strerror(e));
    }
    const int closed = std::fclose(temp.file);
    temp.file = nullptr;
    if (closed != 0) {
        const int e = errno;
        fail(path, std::string("cannot write: ") + std::strerror(e));
    }
    if (std::rename(temp.path.c_str(), path.c_str()) != 0) {
        const int e = errno;
        fail(path, std::string("cannot write: cannot rename ") + temp.path + " to it: " + std::strerror(e));
    }
    temp.renamed = true;
}

}  // namespace jostle
