// mask.cpp: 1-bit pixel masks (slides 09-0 to 09-5 and 09-30): the bit-packed Mask; mask vs
// mask overlap, first shared pixel, count and integer MTD; the same against the other shapes
// by the pixel rule; the nearest point of a mask; and the lecture's loop, corrected, in reference::.
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <type_traits>
#include <variant>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "internal.h"
#include "jostle/collision.h"
#include "jostle/core/error.h"

namespace jostle {

namespace {

using i64 = std::int64_t;
using u64 = std::uint64_t;

// Clear words past the last row (64 bytes a mask). The mask queries read the word after a
// row's last one (two adjacent words joined by a shift) and mask off its bits, so a row's last
// word has a readable neighbour, the next row's first word or the first of these; and the
// AVX-512 and AVX2 kernels read 8 words (and the one after them) from a shared row's start
// without a load mask, keeping the shared rows' count off the loads' path (they mask the test
// instead): the AVX2 kernel's last read can be the last of these 8 words, so 8 is the least.
constexpr std::size_t kPadWords = 8;

bool usable(const Mask* m) { return m != nullptr && m->width() > 0 && m->height() > 0; }

std::string describe_char(char ch) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte >= 0x20 && byte < 0x7f) return std::string("'") + ch + "'";
    static const char* const digits = "0123456789abcdef";
    return std::string("byte 0x") + digits[byte >> 4] + digits[byte & 15];
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Mask
// ---------------------------------------------------------------------------------------

Mask::Mask(int width, int height) {
    JOSTLE_ASSERT(width >= 0 && width <= kMaxMaskSide && height >= 0 && height <= kMaxMaskSide,
                  "mask width and height must be in 0..kMaxMaskSide");
    width_ = width;
    height_ = height;
    words_per_row_ = (width + 63) / 64;
    bits_.assign(static_cast<std::size_t>(words_per_row_) * static_cast<std::size_t>(height) + kPadWords, 0);
}

// An empty list gives a 0 x 0 mask and empty rows a 0-wide mask: both are valid and hit
// nothing. Too many rows or pixels is an error, like a bad character or a ragged row.
std::optional<Mask> Mask::from_rows(std::span<const std::string_view> rows, std::string* error) {
    auto fail = [error](std::string message) -> std::optional<Mask> {
        if (error != nullptr) *error = std::move(message);
        return std::nullopt;
    };
    const std::string limit = std::to_string(kMaxMaskSide);
    if (rows.size() > static_cast<std::size_t>(kMaxMaskSide))
        return fail(std::to_string(rows.size()) + " rows, at most " + limit);
    const std::size_t w = rows.empty() ? 0 : rows[0].size();
    if (w > static_cast<std::size_t>(kMaxMaskSide))
        return fail("row 1 has " + std::to_string(w) + " pixels, at most " + limit);
    Mask mask(static_cast<int>(w), static_cast<int>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::string_view line = rows[r];
        if (line.size() != w)
            return fail("row " + std::to_string(r + 1) + " has " + std::to_string(line.size()) +
                        " pixels, expected " + std::to_string(w) + " like row 1");
        for (std::size_t c = 0; c < w; ++c) {
            if (line[c] == '#') {
                mask.set(static_cast<int>(c), static_cast<int>(r), true);
            } else if (line[c] != '.') {
                return fail("row " + std::to_string(r + 1) + ", column " + std::to_string(c + 1) +
                            ": expected '#' or '.', got " + describe_char(line[c]));
            }
        }
    }
    return mask;
}

Mask Mask::from_alpha(const std::uint8_t* rgba, int width, int height, std::uint8_t threshold) {
    Mask mask(width, height);
    JOSTLE_ASSERT(rgba != nullptr || width == 0 || height == 0, "from_alpha needs width*height pixels");
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 4 + 3;  // alpha, 09-4
            if (rgba[at] > threshold) mask.set(x, y, true);
        }
    }
    return mask;
}

bool Mask::get(int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return false;
    return ((row(y)[x >> 6] >> (x & 63)) & 1u) != 0;
}

void Mask::set(int x, int y, bool value) {
    JOSTLE_ASSERT(x >= 0 && y >= 0 && x < width_ && y < height_, "pixel outside the mask");
    u64& word = bits_[static_cast<std::size_t>(y) * words_per_row_ + (x >> 6)];
    const u64 bit = u64{1} << (x & 63);
    word = value ? (word | bit) : (word & ~bit);
}

int Mask::count() const {
    int n = 0;
    for (const u64 w : bits_) n += std::popcount(w);
    return n;
}

std::vector<std::string> Mask::to_rows() const {
    std::vector<std::string> out(static_cast<std::size_t>(height_), std::string(static_cast<std::size_t>(width_), '.'));
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x)
            if (get(x, y)) out[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = '#';
    return out;
}

namespace {

// ---------------------------------------------------------------------------------------
// Bit-level helpers
// ---------------------------------------------------------------------------------------

// The set pixels' rectangle, in the mask's own pixels, inclusive; x1 < x0 when none is set.
struct PixelBox {
    int x0 = 0;
    int y0 = 0;
    int x1 = -1;
    int y1 = -1;
    bool empty() const { return x1 < x0; }
};

PixelBox set_pixel_box(const Mask& m) {
    PixelBox box{m.width(), m.height(), -1, -1};
    for (int y = 0; y < m.height(); ++y) {
        const u64* row = m.row(y);
        for (int k = 0; k < m.words_per_row(); ++k) {
            if (row[k] == 0) continue;
            box.x0 = std::min(box.x0, k * 64 + std::countr_zero(row[k]));
            box.x1 = std::max(box.x1, k * 64 + 63 - std::countl_zero(row[k]));
            box.y0 = std::min(box.y0, y);
            box.y1 = y;
        }
    }
    return box.x1 < 0 ? PixelBox{} : box;
}

// The last set pixel at or before column c (0 <= c < width), or -1.
int last_set_at_or_before(const u64* row, int c) {
    int k = c >> 6;
    u64 w = row[k] & (~u64{0} >> (63 - (c & 63)));
    for (;;) {
        if (w != 0) return k * 64 + 63 - std::countl_zero(w);
        if (--k < 0) return -1;
        w = row[k];
    }
}

// The first set pixel at or after column c (0 <= c < width), or -1.
int first_set_at_or_after(const u64* row, int words, int c) {
    int k = c >> 6;
    u64 w = row[k] & (~u64{0} << (c & 63));
    for (;;) {
        if (w != 0) return k * 64 + std::countr_zero(w);
        if (++k >= words) return -1;
        w = row[k];
    }
}

// How many pixels from (i, j) on, stepping `step` rows (+1 down, -1 up), are set in a row,
// counting (i, j) itself (0 when it is clear). The MTD search's jump: a translation that puts a
// set pixel on a blocked world pixel is blocked, so moving a mask against its own run of set
// pixels keeps one of them on that world pixel for run - 1 more steps.
i64 column_run(const Mask& m, int i, int j, int step) {
    const int shift = i & 63;
    const auto word = static_cast<std::size_t>(i >> 6);
    i64 run = 0;
    for (; j >= 0 && j < m.height() && ((m.row(j)[word] >> shift) & 1) != 0; j += step) ++run;
    return run;
}

// A mask at a world position; i64 so that a translated position never overflows.
struct Placed {
    const Mask* m = nullptr;
    i64 x = 0;
    i64 y = 0;
};

Placed placed(const PlacedMask& p) { return {p.mask, p.x, p.y}; }

// 09-30: AND the two masks over the intersection of their rectangles only, 64 pixels per
// AND. The shared rectangle starts at column x0 = max(a.x, b.x), which is column 0 of one
// of the two masks: that one, "P", is read word-aligned (shared chunk i of a row is its word
// i); the 64 pixels of the other, "O", under it are two adjacent O words joined by a shift
// that is the same for every chunk of every row. The last chunk of a row is ANDed with `tail`,
// which clears the columns past the shared rectangle: there P's bits are clear (past its
// width) and O's are its own clear bits or the next row's (or the clear words after the last
// row, see kPadWords), so nothing outside a mask's storage is read and every read bit that
// counts lies inside both masks. The setup is a few dozen instructions: for small masks it is
// most of a query's cost.
struct SharedWords {
    const u64* p = nullptr;       // P's word 0 in the first shared row
    const u64* o = nullptr;       // O's word holding the column under P's column 0 there
    std::ptrdiff_t p_stride = 0;  // P's words per row
    std::ptrdiff_t o_stride = 0;  // O's words per row
    int shift = 0;                // that column's bit in its O word
    int rows = 0;                 // shared rows, >= 1
    int words = 0;                // chunks per shared row, >= 1
    u64 tail = 0;                 // the valid bits of a row's last chunk
    i64 x0 = 0;                   // the shared rectangle's top-left world pixel
    i64 y0 = 0;
};

// The mask and position of a query's argument (PlacedMask) or of the MTD search's translated
// mask (Placed, whose i64 position cannot overflow).
inline const Mask* mask_of(const PlacedMask& p) { return p.mask; }
inline const Mask* mask_of(const Placed& p) { return p.m; }

// lhs <= rhs ? x : y as a conditional move, never a branch, for conditions that are random
// from query to query: GCC 12 branches on a plain ?: there, whatever it is told of the odds, or
// turns the compare into a setcc and a test.
template <class T, class C>
[[gnu::always_inline]] inline T pick_le(C lhs, C rhs, T x, T y) {
#if defined(__x86_64__) && defined(__GNUC__)
    static_assert(sizeof(T) == 8 || sizeof(T) == 4);
    asm("cmp %3, %2\n\tcmovle %1, %0" : "+r"(y) : "r"(x), "r"(lhs), "re"(rhs) : "cc");
    return y;
#else
    return lhs <= rhs ? x : y;
#endif
}

// The rectangle two placed masks share, in each one's own pixels: A's pixel (a_col + i,
// a_top + j) and B's pixel (b_col + i, b_top + j) are the same world pixel, for 0 <= i < width
// and 0 <= j < rows. One of a_col and b_col is 0, and one of a_top and b_top.
struct SharedRect {
    i64 a_col = 0;
    i64 a_top = 0;
    i64 b_col = 0;
    i64 b_top = 0;
    i64 width = 0;
    i64 rows = 0;
};

// Sets r up for the pair (both masks present); false when the rectangles share no pixel.
template <class P>
[[gnu::always_inline]] inline bool shared_rect(const P& a, const P& b, SharedRect& r) {
    // B's offset from A in i64, which cannot overflow.
    const i64 dx = static_cast<i64>(b.x) - static_cast<i64>(a.x);
    const i64 dy = static_cast<i64>(b.y) - static_cast<i64>(a.y);
    r.a_col = std::max<i64>(dx, 0);
    r.b_col = r.a_col - dx;
    r.a_top = std::max<i64>(dy, 0);
    r.b_top = r.a_top - dy;
    r.width = std::min(mask_of(a)->width() - r.a_col, mask_of(b)->width() - r.b_col);
    r.rows = std::min(mask_of(a)->height() - r.a_top, mask_of(b)->height() - r.b_top);
    return std::min(r.width, r.rows) > 0;  // one test and branch for both
}

// width % 64 low bits, all 64 when 0: the valid bits of a row's last chunk.
inline u64 tail_bits(i64 width) { return ~u64{0} >> ((64 - (width & 63)) & 63); }

// Sets s up for the pair (both masks present); false when the rectangles share no pixel.
// kStride: both masks' words per row when the caller has checked that it is that (else 0).
template <int kStride = 0, class P>
[[gnu::always_inline]] inline bool share_words(const P& a, const P& b, SharedWords& s) {
    SharedRect r;
    if (!shared_rect(a, b, r)) return false;
    const Mask* const am = mask_of(a);
    const Mask* const bm = mask_of(b);
    const i64 a_stride = kStride != 0 ? kStride : am->words_per_row();
    const i64 b_stride = kStride != 0 ? kStride : bm->words_per_row();
    const u64* const a_row = am->row(0) + r.a_top * a_stride;
    const u64* const b_row = bm->row(0) + r.b_top * b_stride;
    // P: the mask whose column 0 is the shared rectangle's (A when its a_col is 0). Which one
    // it is is random from pair to pair, so it is chosen by selects once both masks' rows are
    // found: a branch there is mispredicted on half the queries, which costs more than a small
    // query's work.
    const i64 c = r.a_col + r.b_col;  // O's column under P's column 0
    s.p_stride = kStride != 0 ? kStride : pick_le(r.a_col, i64{0}, a_stride, b_stride);
    s.o_stride = kStride != 0 ? kStride : pick_le(r.a_col, i64{0}, b_stride, a_stride);
    s.p = pick_le(r.a_col, i64{0}, a_row, b_row);
    // With one word a row, c < 64 (the rectangle lies inside both masks).
    s.o = pick_le(r.a_col, i64{0}, b_row, a_row) + (kStride == 1 ? 0 : c >> 6);
    s.shift = static_cast<int>(c & 63);
    s.x0 = a.x + r.a_col;
    s.y0 = a.y + r.a_top;
    s.rows = static_cast<int>(r.rows);
    s.words = kStride == 1 ? 1 : static_cast<int>((r.width + 63) >> 6);
    s.tail = tail_bits(r.width);
    return true;
}

// 64 pixels starting at bit `shift` of lo and running on into hi. hi << 1 << (63 - shift)
// rather than hi << (64 - shift): a shift by 64 is undefined, and for shift 0 this gives 0.
inline u64 join(u64 lo, u64 hi, int shift) { return (lo >> shift) | ((hi << 1) << (63 - shift)); }

// Chunk i of shared row r (P's word AND the O pixels under it), without the tail.
[[gnu::always_inline]] inline u64 chunk(const SharedWords& s, int r, int i) {
    const u64* p = s.p + r * s.p_stride;
    const u64* o = s.o + r * s.o_stride;
    return p[i] & join(o[i], o[i + 1], s.shift);
}

// Row r's only chunk (s.words == 1: always so for masks up to 64 wide), tail applied.
[[gnu::always_inline]] inline u64 only_chunk(const SharedWords& s, int r) { return chunk(s, r, 0) & s.tail; }

// One shared row: f(i, chunk i) for i = 0..words-1, left to right, until f returns true.
template <class F>
[[gnu::always_inline]] inline bool for_row_words(const SharedWords& s, int r, F&& f) {
    const u64* p = s.p + r * s.p_stride;
    const u64* o = s.o + r * s.o_stride;
    const int last = s.words - 1;
    u64 lo = o[0];
    for (int i = 0; i < last; ++i) {
        const u64 hi = o[i + 1];
        if (f(i, p[i] & join(lo, hi, s.shift))) return true;
        lo = hi;
    }
    return f(last, p[last] & join(lo, o[last + 1], s.shift) & s.tail);
}

// The OR of a row's shared chunks: non-zero when the row has a shared pixel.
template <bool kOneWord>
[[gnu::always_inline]] inline u64 row_any(const SharedWords& s, int r) {
    if constexpr (kOneWord) {
        return only_chunk(s, r);
    } else {
        u64 any = 0;
        for_row_words(s, r, [&](int, u64 w) {
            any |= w;
            return false;
        });
        return any;
    }
}

// Rows are tested kBlock at a time with one branch per block, then one at a time: where the
// first shared row falls is random, and a branch per row is mispredicted about once a query,
// which costs as much as the AND work of small masks.
constexpr int kBlock = 4;

// Bit k set: row r0 + k has a shared pixel (rows r0 .. r0 + kBlock - 1 exist).
template <bool kOneWord>
[[gnu::always_inline]] inline unsigned block_flags(const SharedWords& s, int r0) {
    unsigned flags = 0;
    for (int k = 0; k < kBlock; ++k) flags |= static_cast<unsigned>(row_any<kOneWord>(s, r0 + k) != 0) << k;
    return flags;
}

// The first row at or after r with a shared pixel, or s.rows.
template <bool kOneWord>
[[gnu::always_inline]] inline int first_row_from(const SharedWords& s, int r) {
    for (; r + kBlock <= s.rows; r += kBlock)
        if (const unsigned flags = block_flags<kOneWord>(s, r); flags != 0) return r + std::countr_zero(flags);
    for (; r < s.rows; ++r)
        if (row_any<kOneWord>(s, r) != 0) return r;
    return s.rows;
}

// Yes/no needs no row number: the rows of a block are simply ORed.
template <bool kOneWord>
[[gnu::always_inline]] inline bool any_shared_in(const SharedWords& s) {
    int r = 0;
    for (; r + kBlock <= s.rows; r += kBlock) {
        u64 any = 0;
        for (int k = 0; k < kBlock; ++k) any |= row_any<kOneWord>(s, r + k);
        if (any != 0) return true;
    }
    for (; r < s.rows; ++r)
        if (row_any<kOneWord>(s, r) != 0) return true;
    return false;
}

[[gnu::always_inline]] inline bool any_shared(const SharedWords& s) {
    return s.words == 1 ? any_shared_in<true>(s) : any_shared_in<false>(s);
}

// A shared pixel as its column and row in the shared rectangle (world x0 + col, y0 + row);
// row -1: none. Eight bytes, so the kernels return it in a register.
struct Offset {
    int col;
    int row;
    bool found() const { return row >= 0; }
};
constexpr Offset kNone{0, -1};

// A kernel's first_overlap answer, in two registers: the world pixel's x in the low half of xy
// and y in the high half, found 0 or 1. (A kernel compiled for AVX-512 that builds a
// std::optional<Pixel> itself gets its stack aligned to 64 bytes in its prologue by GCC 12, on
// every query.)
struct FirstPixel {
    u64 xy;
    u64 found;
};

// The world pixel at `at` in a shared rectangle whose top-left is world (x0, y0), or none.
[[gnu::always_inline]] inline FirstPixel first_pixel(i64 x0, i64 y0, Offset at) {
    const auto x = static_cast<std::uint32_t>(x0 + at.col), y = static_cast<std::uint32_t>(y0 + at.row);
    return {x | u64{y} << 32, at.found() ? 1u : 0u};
}
[[gnu::always_inline]] inline FirstPixel first_pixel(const SharedWords& s, Offset at) { return first_pixel(s.x0, s.y0, at); }

// first_overlap's result, made from its bytes where the layout is known (libstdc++ keeps the
// Pixel, then the engaged flag; the tests compare every answer with reference::'s): GCC 12
// builds a std::optional<Pixel> made the usual way on the stack and reads it back with loads
// wider than its stores, a store-forwarding stall on every answer, while these bytes come
// back in two registers.
inline std::optional<Pixel> to_optional(FirstPixel p) {
#if defined(__GLIBCXX__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    struct [[gnu::packed]] Bytes {
        u64 xy;
        std::uint32_t engaged;
    };
    static_assert(sizeof(Bytes) == sizeof(std::optional<Pixel>));
    return std::bit_cast<std::optional<Pixel>>(Bytes{p.xy, static_cast<std::uint32_t>(p.found)});
#else
    if (p.found == 0) return std::nullopt;
    return Pixel{static_cast<int>(static_cast<std::uint32_t>(p.xy)), static_cast<int>(static_cast<std::uint32_t>(p.xy >> 32))};
#endif
}

// The first shared pixel of row r, known to have one.
template <bool kOneWord>
[[gnu::always_inline]] inline Offset first_in_row(const SharedWords& s, int r) {
    Offset out{0, r};
    if constexpr (kOneWord) {
        out.col = std::countr_zero(only_chunk(s, r));
    } else {
        for_row_words(s, r, [&](int i, u64 w) {
            out.col = 64 * i + std::countr_zero(w);
            return w != 0;
        });
    }
    return out;
}

// The first shared pixel of the lowest row that has one (the MTD search's witness when it
// scans upward; not worth blocks there).
Offset last_row_first_shared(const SharedWords& s) {
    for (int r = s.rows - 1; r >= 0; --r)
        if (row_any<false>(s, r) != 0) return first_in_row<false>(s, r);
    return kNone;
}

// The first shared pixel, rows top to bottom, left to right.
[[gnu::always_inline]] inline Offset first_shared(const SharedWords& s) {
    if (s.words == 1) {
        const int r = first_row_from<true>(s, 0);
        return r < s.rows ? first_in_row<true>(s, r) : kNone;
    }
    const int r = first_row_from<false>(s, 0);
    return r < s.rows ? first_in_row<false>(s, r) : kNone;
}

[[gnu::always_inline]] inline int count_in_rows(const SharedWords& s) {
    int n = 0;
    if (s.words == 1) {
        for (int r = 0; r < s.rows; ++r) n += std::popcount(only_chunk(s, r));
        return n;
    }
    for (int r = 0; r < s.rows; ++r)
        for_row_words(s, r, [&](int, u64 w) {
            n += std::popcount(w);
            return false;
        });
    return n;
}

// ---------------------------------------------------------------------------------------
// The kernels by instruction set, chosen at run time
// ---------------------------------------------------------------------------------------
// The kernels above are integer-only and always inlined, so each copy below compiles them for
// its own [[gnu::target]]. Whole-file flags (-march=...) would let the compiler change
// floating-point code too (FMA), which the determinism rule forbids; a target attribute on an
// integer-only function cannot. Every copy gives the same answers (tests run each one the CPU
// has against reference::):
//   portable  baseline x86-64 (or any other machine): std::popcount is a libgcc call there
//   bmi2      POPCNT, TZCNT and BMI2's shifts by any register (the join's two shifts need no
//             shuffling through CL)
//   avx2      bmi2, and two masks of the same 1, 2, 4 or 8 words per row read 8 words a step
//             in two 256-bit vectors, one branch a step (counted by a nibble table)
//   avx512    bmi2, and VPSHRDVQ (VBMI2) joining 8 word pairs in one instruction, VPOPCNTQ
//             counting them: 8 / stride rows a vector for two masks of the same 1, 2, 4 or 8
//             words per row, else 8 one-chunk rows or one row of 2..8 chunks a vector.
// Each kernel is a whole query, from the setup to the answer, so that the shared words stay in
// registers: a query on small masks is mostly setup. A query is issue-bound (about 6
// instructions a cycle on the machines measured), so instructions count, and a branch on the
// data costs a pipeline refill whenever it is mispredicted.

using MaskKernel = detail::MaskKernel;

#if defined(__x86_64__) && defined(__GNUC__)
#define JOSTLE_MASK_X86_KERNELS 1
#define JOSTLE_BMI2 "popcnt,bmi,bmi2"
#define JOSTLE_AVX2_MASKS "popcnt,bmi,bmi2,avx,avx2"
#define JOSTLE_AVX512 "popcnt,bmi,bmi2,avx2,avx512f,avx512vl,avx512bw,avx512dq,avx512vpopcntdq,avx512vbmi2"

// A shared row of 2..8 chunks as one vector: lane i is chunk i (lanes past the row are 0).
struct RowVectors {
    __mmask8 lanes;  // the row's chunks
    __m512i tail;    // ~0 in every lane but the last chunk's, which holds s.tail
    __m512i shift;   // s.shift in every lane
};

[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline RowVectors row_vectors(const SharedWords& s) {
    RowVectors v;
    v.lanes = static_cast<__mmask8>((1u << s.words) - 1u);
    v.tail = _mm512_mask_set1_epi64(_mm512_set1_epi64(-1), static_cast<__mmask8>(1u << (s.words - 1)),
                                    static_cast<long long>(s.tail));
    v.shift = _mm512_set1_epi64(s.shift);
    return v;
}

// Masked loads read only the row's words (a masked-off lane is never read); lane i of `hi` is
// O's word i + 1, the readable neighbour of the last chunk (see SharedWords).
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i row_vector(const SharedWords& s, const RowVectors& v,
                                                                              int r) {
    const u64* p = s.p + r * s.p_stride;
    const u64* o = s.o + r * s.o_stride;
    const __m512i pw = _mm512_maskz_loadu_epi64(v.lanes, p);
    const __m512i lo = _mm512_maskz_loadu_epi64(v.lanes, o);
    const __m512i hi = _mm512_maskz_loadu_epi64(v.lanes, o + 1);
    return _mm512_and_si512(_mm512_and_si512(pw, _mm512_shrdv_epi64(lo, hi, v.shift)), v.tail);
}

[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline bool nonzero(__m512i w) {
    return _mm512_test_epi64_mask(w, w) != 0;
}

// The sum of the 8 lanes (stored and added: _mm512_reduce_add_epi64's GCC 12 header warns).
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int lane_sum(__m512i v) {
    std::array<long long, 8> lanes{};
    _mm512_storeu_si512(lanes.data(), v);
    long long n = 0;
    for (const long long lane : lanes) n += lane;
    return static_cast<int>(n);
}

// Rows of one chunk (shared width <= 64) from masks of 1 or 2 words per row, 8 rows per vector:
// lane k is row r + k's chunk, tail applied, 0 past the last row. A stride-1 mask's 8 words
// are one load; a stride-2 mask's 16 words are two, split into even and odd lanes by one
// permute each. O's word after a row's chunk word is the next word in memory at both strides
// (the clear words after the last row included), so the same loads give it. Masked loads
// read only the lanes they keep: never past rows r .. s.rows - 1 (and their following word).
template <int kPStride, int kOStride>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i eight_rows(const SharedWords& s, int r,
                                                                              __m512i shift, __m512i tail) {
    const int left = std::min(s.rows - r, 8);
    const unsigned words = (1u << left) - 1u;                   // lane k: row r + k exists
    const unsigned pairs = (1u << (2 * left)) - 1u;             // 2 lanes a row, 16 at most
    const __m512i even = _mm512_set_epi64(14, 12, 10, 8, 6, 4, 2, 0);
    const __m512i odd = _mm512_set_epi64(15, 13, 11, 9, 7, 5, 3, 1);
    __m512i pw;
    if constexpr (kPStride == 1) {
        pw = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(words), s.p + r);
    } else {
        const u64* p = s.p + 2 * r;
        const __m512i v0 = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(pairs), p);
        const __m512i v1 = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(pairs >> 8), p + 8);
        pw = _mm512_permutex2var_epi64(v0, even, v1);
    }
    __m512i lo;
    __m512i hi;
    if constexpr (kOStride == 1) {
        lo = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(words), s.o + r);
        hi = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(words), s.o + r + 1);
    } else {
        const u64* o = s.o + 2 * r;
        const __m512i v0 = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(pairs), o);
        const __m512i v1 = _mm512_maskz_loadu_epi64(static_cast<__mmask8>(pairs >> 8), o + 8);
        lo = _mm512_permutex2var_epi64(v0, even, v1);
        hi = _mm512_permutex2var_epi64(v0, odd, v1);
    }
    return _mm512_and_si512(_mm512_and_si512(pw, _mm512_shrdv_epi64(lo, hi, shift)), tail);
}

// 4 * P's stride + O's stride when both are 1 or 2 words (6 and 9: different strides; equal
// ones are packed), else 0.
inline int stride_pair(const SharedWords& s) {
    return s.p_stride <= 2 && s.o_stride <= 2 ? static_cast<int>(4 * s.p_stride + s.o_stride) : 0;
}

// The first row with a shared pixel, 8 rows a test, or s.rows; rows of one chunk, strides 1-2.
template <int kP, int kO>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int first_row_eight(const SharedWords& s) {
    const __m512i shift = _mm512_set1_epi64(s.shift);
    const __m512i tail = _mm512_set1_epi64(static_cast<long long>(s.tail));
    for (int r = 0; r < s.rows; r += 8) {
        const __m512i w = eight_rows<kP, kO>(s, r, shift, tail);
        if (const unsigned hit = _mm512_test_epi64_mask(w, w); hit != 0) return r + std::countr_zero(hit);
    }
    return s.rows;
}

template <int kP, int kO>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int count_eight(const SharedWords& s) {
    const __m512i shift = _mm512_set1_epi64(s.shift);
    const __m512i tail = _mm512_set1_epi64(static_cast<long long>(s.tail));
    __m512i sum = _mm512_setzero_si512();
    for (int r = 0; r < s.rows; r += 8) sum = _mm512_add_epi64(sum, _mm512_popcnt_epi64(eight_rows<kP, kO>(s, r, shift, tail)));
    return lane_sum(sum);
}

// Rows of two masks with the same stride of kS = 1, 2, 4 or 8 words (up to 64, 128, 256 or
// 512 wide), 8 / kS rows per vector, whatever the shared width: such rows lie kS words apart in
// both masks, so vector v is the 8 words from 8 * v on in each, and lane i * kS + c is chunk c
// of the vector's row i (lanes past a row's chunks, or past the last row, are masked off: not
// read, but for the first vector's, which are read and left out of its test; see first_and).
// Lanes run in reading order. One code path for every offset of the pair: a
// branch on the shared width would be mispredicted on about half the queries (it is random
// from pair to pair).
struct PackedRows {
    unsigned lanes;  // the shared chunks among a vector's rows
    unsigned last;   // each row's last chunk among them
    int words;       // the shared rows' words: rows * kS
};
// (The vectors are kept out of the struct: a local with a 64-byte member makes GCC 12 align
// the stack in the kernel's prologue even when nothing is spilled.)

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline PackedRows packed_rows(const SharedWords& s) {
    static_assert(kS == 1 || kS == 2 || kS == 4 || kS == 8);
    constexpr unsigned row_starts = kS == 1 ? 0xffu : kS == 2 ? 0x55u : kS == 4 ? 0x11u : 0x01u;  // chunk 0 of each row
    // s.words <= kS: no carries below.
    return {((1u << s.words) - 1u) * row_starts, (1u << (s.words - 1)) * row_starts, s.rows * kS};
}

// s.tail in each row's last chunk, ~0 elsewhere.
template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i packed_tail(const SharedWords& s, const PackedRows& v) {
    const auto tail = static_cast<long long>(s.tail);
    if constexpr (kS == 1) return _mm512_set1_epi64(tail);
    return _mm512_mask_set1_epi64(_mm512_set1_epi64(-1), static_cast<__mmask8>(v.last), tail);
}

// The lanes of the last vector, at `at` (1..8 words left).
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline unsigned last_lanes(const PackedRows& v, int at) {
    return v.lanes & _bzhi_u32(0xffu, static_cast<unsigned>(v.words - at));
}

// P AND the joined O in the 8 words from `at` on, the lanes of k only (the others 0, unread),
// without the tail.
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i packed_and(const SharedWords& s, __m512i shift, int at,
                                                                              unsigned k) {
    const auto m = static_cast<__mmask8>(k);
    const __m512i pw = _mm512_maskz_loadu_epi64(m, s.p + at);
    const __m512i lo = _mm512_maskz_loadu_epi64(m, s.o + at);
    const __m512i hi = _mm512_maskz_loadu_epi64(m, s.o + at + 1);
    return _mm512_and_si512(pw, _mm512_shrdv_epi64(lo, hi, shift));
}

[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline bool any_lane(__m512i w, __m512i tail) {
    return _mm512_test_epi64_mask(w, tail) != 0;
}

// The first vector's lanes: the shared chunks of the rows that exist. Lane i's row, i / kS,
// compared with the shared rows' count in a vector: two instructions for any count, and no
// branch (most queries end with this vector: sprites at random offsets mostly share a pixel in
// their first few shared rows).
template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __mmask8 first_lanes(const SharedWords& s, const PackedRows& v) {
    const __m512i row_of_lane = _mm512_srli_epi64(_mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0), std::countr_zero(unsigned{kS}));
    const __mmask8 lanes = kS == 1 ? 0xff : static_cast<__mmask8>(v.lanes);
    return _mm512_mask_cmplt_epi64_mask(lanes, row_of_lane, _mm512_set1_epi64(s.rows));
}

// The first vector, P AND the joined O, read without a load mask: 8 words (and the one after
// them) from a shared row's start stay inside the mask's storage (kPadWords), and the lanes
// outside the shared rows are left to the test's mask, so the loads wait for the row pointers
// alone.
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i first_and(const SharedWords& s, __m512i shift) {
    const __m512i pw = _mm512_loadu_si512(s.p);
    const __m512i lo = _mm512_loadu_si512(s.o);
    const __m512i hi = _mm512_loadu_si512(s.o + 1);
    return _mm512_and_si512(pw, _mm512_shrdv_epi64(lo, hi, shift));
}

// The first vector; then full vectors and the last one, with two branches a vector (one on
// the data alone: measured faster than one on both).
template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline bool any_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    const __m512i tail = packed_tail<kS>(s, v);
    const __m512i shift = _mm512_set1_epi64(s.shift);
    if (_mm512_mask_test_epi64_mask(first_lanes<kS>(s, v), first_and(s, shift), tail) != 0) return true;
    int at = 8;
    for (; at + 8 < v.words; at += 8)
        if (any_lane(packed_and(s, shift, at, v.lanes), tail)) return true;
    return at < v.words && any_lane(packed_and(s, shift, at, last_lanes(v, at)), tail);
}

// The first shared pixel of vector w at `at` whose lanes with a shared pixel are `hit`, as
// first_overlap's answer (none when hit is 0, without a branch). The lowest set bit of a lane
// with a shared pixel is one: the tail keeps a chunk's low bits.
template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline FirstPixel first_in_vector(const SharedWords& s, __m512i w,
                                                                                     unsigned hit, int at) {
    const int word = at + std::countr_zero(hit);  // in the shared rows
    const __m512i first = _mm512_maskz_compress_epi64(static_cast<__mmask8>(_blsi_u32(hit)), w);  // to lane 0
    const int col = 64 * (word % kS) + std::countr_zero(static_cast<u64>(first[0]));
    const auto x = static_cast<std::uint32_t>(s.x0 + col), y = static_cast<std::uint32_t>(s.y0 + word / kS);
    return {x | u64{y} << 32, hit != 0};
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline FirstPixel first_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    const __m512i tail = packed_tail<kS>(s, v);
    const __m512i shift = _mm512_set1_epi64(s.shift);
    const __m512i w0 = first_and(s, shift);
    const unsigned hit0 = _mm512_mask_test_epi64_mask(first_lanes<kS>(s, v), w0, tail);
    if (hit0 != 0 || v.words <= 8) return first_in_vector<kS>(s, w0, hit0, 0);
    int at = 8;
    for (; at + 8 < v.words; at += 8) {
        const __m512i w = packed_and(s, shift, at, v.lanes);
        if (const unsigned hit = _mm512_test_epi64_mask(w, tail); hit != 0) return first_in_vector<kS>(s, w, hit, at);
    }
    const __m512i w = packed_and(s, shift, at, last_lanes(v, at));
    return first_in_vector<kS>(s, w, _mm512_test_epi64_mask(w, tail), at);
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int count_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    const __m512i tail = packed_tail<kS>(s, v);
    const __m512i shift = _mm512_set1_epi64(s.shift);
    __m512i sum = _mm512_popcnt_epi64(_mm512_maskz_and_epi64(first_lanes<kS>(s, v), first_and(s, shift), tail));
    int at = 8;
    for (; at + 8 < v.words; at += 8)
        sum = _mm512_add_epi64(sum, _mm512_popcnt_epi64(_mm512_and_si512(packed_and(s, shift, at, v.lanes), tail)));
    if (at < v.words) sum = _mm512_add_epi64(sum, _mm512_popcnt_epi64(_mm512_and_si512(packed_and(s, shift, at, last_lanes(v, at)), tail)));
    return lane_sum(sum);
}

// The first row (from 0) with a shared pixel, or s.rows; s.words in 2..8.
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int first_row_avx512(const SharedWords& s) {
    const RowVectors v = row_vectors(s);
    int r = 0;
    for (; r + kBlock <= s.rows; r += kBlock) {
        unsigned flags = 0;
        for (int k = 0; k < kBlock; ++k) flags |= static_cast<unsigned>(nonzero(row_vector(s, v, r + k))) << k;
        if (flags != 0) return r + std::countr_zero(flags);
    }
    for (; r < s.rows; ++r)
        if (nonzero(row_vector(s, v, r))) return r;
    return s.rows;
}

// Yes/no: the rows of a block are ORed; s.words in 2..8.
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline bool any_avx512(const SharedWords& s) {
    const RowVectors v = row_vectors(s);
    int r = 0;
    for (; r + kBlock <= s.rows; r += kBlock) {
        __m512i any = row_vector(s, v, r);
        for (int k = 1; k < kBlock; ++k) any = _mm512_or_si512(any, row_vector(s, v, r + k));
        if (nonzero(any)) return true;
    }
    for (; r < s.rows; ++r)
        if (nonzero(row_vector(s, v, r))) return true;
    return false;
}

// s.words in 2..8.
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int count_avx512(const SharedWords& s) {
    const RowVectors v = row_vectors(s);
    __m512i sum = _mm512_setzero_si512();
    for (int r = 0; r < s.rows; ++r) sum = _mm512_add_epi64(sum, _mm512_popcnt_epi64(row_vector(s, v, r)));
    return lane_sum(sum);
}
#endif

#ifdef JOSTLE_MASK_X86_KERNELS
// The avx2 kernels (CPUs without AVX-512: AMD's Zen 1-3, Intel's client cores before Ice Lake):
// two masks of the same stride of kS = 1, 2, 4 or 8 words, read as the AVX-512 packed kernels
// read them (rows kS words apart in both masks, so word `at` of the shared rows is P's word
// at and O's words at, at + 1 joined), 8 words a step in two 4-lane vectors and one branch a
// step: 8 rows of a 64 px pair, 4 of a 128 px one (the count: no branch but the loop's). A
// lane's column mask (~0, the tail, or 0 past the shared chunks) repeats every step (kS
// divides 8); lanes past the shared rows' last word are masked by comparing their index with
// it. The loads are not masked. The last step starts at most one row before the shared rows
// end (at <= rows * kS - kS, at a multiple of 8), so it reads P up to word rows * kS + 7 - kS
// from s.p and O up to word rows * kS + 7 of its first shared row (s.o is c >> 6 <= kS - 1 words
// into it): at worst the last of O's kPadWords clear words. What they read outside the shared
// rows is masked. A vector shift by 64 or more gives 0, so the join needs no special case for
// shift 0.
struct Avx2Step {
    __m256i cols0, cols1;  // the column masks of a step's two vectors
    __m256i shift_lo;      // s.shift in lane 0 (the vector shifts' count operand)
    __m256i shift_hi;      // 64 - s.shift
};

template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline __m256i avx2_columns(const SharedWords& s, int first_lane) {
    // Lane j holds chunk (first_lane + j) % kS of its row: ~0 before the row's last shared
    // chunk, the tail at it, 0 after it.
    const __m256i chunk = _mm256_and_si256(_mm256_add_epi64(_mm256_set1_epi64x(first_lane), _mm256_set_epi64x(3, 2, 1, 0)),
                                           _mm256_set1_epi64x(kS - 1));
    const __m256i last = _mm256_set1_epi64x(s.words - 1);
    const __m256i before = _mm256_cmpgt_epi64(last, chunk);
    const __m256i at_last = _mm256_and_si256(_mm256_cmpeq_epi64(last, chunk), _mm256_set1_epi64x(static_cast<long long>(s.tail)));
    return _mm256_or_si256(before, at_last);
}

// P AND the joined O for the 4 words from `at` on, the column mask applied.
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline __m256i avx2_and(const SharedWords& s, const Avx2Step& v, int at,
                                                                                __m256i cols) {
    const __m256i pw = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s.p + at));
    const __m256i lo = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s.o + at));
    const __m256i hi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(s.o + at + 1));
    const __m256i joined = _mm256_or_si256(_mm256_srl_epi64(lo, _mm256_castsi256_si128(v.shift_lo)),
                                           _mm256_sll_epi64(hi, _mm256_castsi256_si128(v.shift_hi)));
    return _mm256_and_si256(_mm256_and_si256(pw, joined), cols);
}

template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline Avx2Step avx2_step(const SharedWords& s) {
    static_assert(kS == 1 || kS == 2 || kS == 4 || kS == 8);
    return {avx2_columns<kS>(s, 0), avx2_columns<kS>(s, 4), _mm256_castsi128_si256(_mm_cvtsi32_si128(s.shift)),
            _mm256_castsi128_si256(_mm_cvtsi32_si128(64 - s.shift))};
}

// Lanes whose word index (at + lane) is below `words` (the shared rows' words): ~0, else 0.
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline __m256i avx2_below(__m256i words, __m256i index) {
    return _mm256_cmpgt_epi64(words, index);
}

// A scan of the shared rows' words, 8 a step: the step's constants and its lanes' word indexes.
struct Avx2Scan {
    Avx2Step v;
    int words;      // the shared rows' words, rows * kS
    __m256i limit;  // words, in every lane
    __m256i index0, index1;
};

template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline Avx2Scan avx2_scan(const SharedWords& s) {
    return {avx2_step<kS>(s), s.rows * kS, _mm256_set1_epi64x(s.rows * kS), _mm256_set_epi64x(3, 2, 1, 0),
            _mm256_set_epi64x(7, 6, 5, 4)};
}

// The step at `at` (the scan's indexes at it): two vectors, lanes past the shared rows cleared;
// then the indexes move on to the next step.
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline void avx2_words(const SharedWords& s, Avx2Scan& c, int at,
                                                                               __m256i& w0, __m256i& w1) {
    w0 = _mm256_and_si256(avx2_and(s, c.v, at, c.v.cols0), avx2_below(c.limit, c.index0));
    w1 = _mm256_and_si256(avx2_and(s, c.v, at + 4, c.v.cols1), avx2_below(c.limit, c.index1));
    c.index0 = _mm256_add_epi64(c.index0, _mm256_set1_epi64x(8));
    c.index1 = _mm256_add_epi64(c.index1, _mm256_set1_epi64x(8));
}

// Whether a step has a shared pixel. One branch a step.
template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline bool any_avx2(const SharedWords& s) {
    Avx2Scan c = avx2_scan<kS>(s);
    for (int at = 0; at < c.words; at += 8) {
        __m256i w0, w1;
        avx2_words(s, c, at, w0, w1);
        const __m256i any = _mm256_or_si256(w0, w1);
        if (_mm256_testz_si256(any, any) == 0) return true;
    }
    return false;
}

// The set bits of each byte (a table lookup per nibble: AVX2 has no vector popcount).
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline __m256i byte_popcounts(__m256i v) {
    const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4);
    const __m256i nibble = _mm256_set1_epi8(0x0f);
    return _mm256_add_epi8(_mm256_shuffle_epi8(table, _mm256_and_si256(v, nibble)),
                           _mm256_shuffle_epi8(table, _mm256_and_si256(_mm256_srli_epi16(v, 4), nibble)));
}

// Every shared pixel: per step, the two vectors' byte counts added (at most 16 a byte) and
// summed into the four lanes by VPSADBW.
template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline int count_avx2(const SharedWords& s) {
    Avx2Scan c = avx2_scan<kS>(s);
    __m256i sum = _mm256_setzero_si256();
    for (int at = 0; at < c.words; at += 8) {
        __m256i w0, w1;
        avx2_words(s, c, at, w0, w1);
        const __m256i bytes = _mm256_add_epi8(byte_popcounts(w0), byte_popcounts(w1));
        sum = _mm256_add_epi64(sum, _mm256_sad_epu8(bytes, _mm256_setzero_si256()));
    }
    const __m128i half = _mm_add_epi64(_mm256_castsi256_si128(sum), _mm256_extracti128_si256(sum, 1));
    return static_cast<int>(_mm_cvtsi128_si64(half) + _mm_extract_epi64(half, 1));
}

// The lanes of w0 (bits 0-3) and w1 (bits 4-7) that are 0.
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline unsigned empty_lanes(__m256i w0, __m256i w1) {
    const __m256i zero = _mm256_setzero_si256();
    const auto empty0 = static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(w0, zero))));
    const auto empty1 = static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(w1, zero))));
    return empty0 | empty1 << 4;
}

// The step's test is the lanes' emptiness itself, so the first lane with a shared pixel is
// known at the branch; its word is then made again from memory in scalar registers (three
// loads that hit the cache), sooner than moved out of the vectors.
template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS), gnu::always_inline]] inline FirstPixel first_avx2(const SharedWords& s) {
    Avx2Scan c = avx2_scan<kS>(s);
    for (int at = 0; at < c.words; at += 8) {
        __m256i w0, w1;
        avx2_words(s, c, at, w0, w1);
        if (const unsigned empty = empty_lanes(w0, w1); empty != 0xffu) {
            const int word = at + std::countr_zero(~empty);  // in the shared rows, in reading order
            const int chunk = word % kS;
            const u64 cols = chunk == s.words - 1 ? s.tail : ~u64{0};  // a lane with a pixel is a shared chunk
            const u64 bits = s.p[word] & join(s.o[word], s.o[word + 1], s.shift) & cols;
            const int col = 64 * chunk + std::countr_zero(bits);
            const auto x = static_cast<std::uint32_t>(s.x0 + col), y = static_cast<std::uint32_t>(s.y0 + word / kS);
            return {x | u64{y} << 32, 1};
        }
    }
    return {0, 0};
}

template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS)]] bool any_avx2_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) && any_avx2<kS>(s);
}
template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS)]] FirstPixel first_avx2_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) ? first_avx2<kS>(s) : FirstPixel{0, 0};
}
template <int kS>
[[gnu::target(JOSTLE_AVX2_MASKS)]] int count_avx2_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) ? count_avx2<kS>(s) : 0;
}
#endif

// The kernels: each one a whole query on two present masks. The portable and bmi2 ones are the
// code above, compiled for their [[gnu::target]]s.
bool any_portable(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words(a, b, s) && any_shared(s);
}
FirstPixel first_portable(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return first_pixel(s, share_words(a, b, s) ? first_shared(s) : kNone);
}
int count_portable(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words(a, b, s) ? count_in_rows(s) : 0;
}

#ifdef JOSTLE_MASK_X86_KERNELS
[[gnu::target(JOSTLE_BMI2)]] bool any_bmi2(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words(a, b, s) && any_shared(s);
}
[[gnu::target(JOSTLE_BMI2)]] FirstPixel first_bmi2(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return first_pixel(s, share_words(a, b, s) ? first_shared(s) : kNone);
}
[[gnu::target(JOSTLE_BMI2)]] int count_bmi2(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words(a, b, s) ? count_in_rows(s) : 0;
}

// The avx512 kernels: two masks of the same stride of 1, 2, 4 or 8 words (up to 64, 128, 256
// or 512 wide) take the packed rows, 8 / stride rows a vector, at every shared width, in one
// function per stride. The other pairs take *_vector_other: 8 rows a vector for rows of one
// chunk from a mask 1 and a mask 2 words wide; a vector a row for the other rows of 2..8
// chunks; the bmi2 code for the rest.
[[gnu::target(JOSTLE_AVX512)]] bool any_vector_other(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    if (!share_words(a, b, s)) return false;
    if (s.words == 1) {
        switch (stride_pair(s)) {
        case 6: return first_row_eight<1, 2>(s) < s.rows;
        case 9: return first_row_eight<2, 1>(s) < s.rows;
        default: return any_shared(s);
        }
    }
    return s.words <= 8 ? any_avx512(s) : any_shared(s);
}
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline Offset first_other(const SharedWords& s) {
    if (s.words == 1) {
        int r = 0;
        switch (stride_pair(s)) {
        case 6: r = first_row_eight<1, 2>(s); break;
        case 9: r = first_row_eight<2, 1>(s); break;
        default: return first_shared(s);
        }
        return r < s.rows ? first_in_row<true>(s, r) : kNone;
    }
    if (s.words > 8) return first_shared(s);
    const int r = first_row_avx512(s);
    return r < s.rows ? first_in_row<false>(s, r) : kNone;
}
[[gnu::target(JOSTLE_AVX512)]] FirstPixel first_vector_other(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return first_pixel(s, share_words(a, b, s) ? first_other(s) : kNone);
}
[[gnu::target(JOSTLE_AVX512)]] int count_vector_other(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    if (!share_words(a, b, s)) return 0;
    if (s.words == 1) {
        switch (stride_pair(s)) {
        case 6: return count_eight<1, 2>(s);
        case 9: return count_eight<2, 1>(s);
        default: return count_in_rows(s);
        }
    }
    return s.words <= 8 ? count_avx512(s) : count_in_rows(s);
}

template <int kS>
[[gnu::target(JOSTLE_AVX512)]] bool any_vector_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) && any_packed<kS>(s);
}
template <int kS>
[[gnu::target(JOSTLE_AVX512)]] FirstPixel first_vector_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) ? first_packed<kS>(s) : FirstPixel{0, 0};
}
template <int kS>
[[gnu::target(JOSTLE_AVX512)]] int count_vector_packed(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    return share_words<kS>(a, b, s) ? count_packed<kS>(s) : 0;
}

bool cpu_has(MaskKernel k) {
    __builtin_cpu_init();  // kBestKernel asks from a static initializer, maybe before libgcc's
    switch (k) {
    case MaskKernel::portable: return true;
    case MaskKernel::bmi2:
        return __builtin_cpu_supports("popcnt") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    case MaskKernel::avx2: return cpu_has(MaskKernel::bmi2) && __builtin_cpu_supports("avx") && __builtin_cpu_supports("avx2");
    case MaskKernel::avx512:
        return cpu_has(MaskKernel::avx2) && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vpopcntdq") && __builtin_cpu_supports("avx512vbmi2");
    }
    return false;
}
#else
bool cpu_has(MaskKernel k) { return k == MaskKernel::portable; }
#endif

// The kernel asked for, or the best one the CPU has below it.
MaskKernel usable_kernel(MaskKernel k) {
    while (k != MaskKernel::portable && !cpu_has(k)) k = static_cast<MaskKernel>(static_cast<int>(k) - 1);
    return k;
}

// One kernel's three queries.
struct Kernels {
    bool (*any)(const PlacedMask&, const PlacedMask&);
    FirstPixel (*first)(const PlacedMask&, const PlacedMask&);
    int (*count)(const PlacedMask&, const PlacedMask&);
};

constexpr Kernels kPortable{any_portable, first_portable, count_portable};
#ifdef JOSTLE_MASK_X86_KERNELS
constexpr Kernels kBmi2{any_bmi2, first_bmi2, count_bmi2};
// By both masks' words per row when it is the same and at most 8, else entry 0. A table, not
// a switch: one indirect call, predicted like the switch's branches, in fewer instructions.
template <int kS>
constexpr Kernels kPacked{any_vector_packed<kS>, first_vector_packed<kS>, count_vector_packed<kS>};
constexpr Kernels kOther{any_vector_other, first_vector_other, count_vector_other};
constexpr std::array<Kernels, 9> kVector{kOther, kPacked<1>, kPacked<2>, kOther, kPacked<4>,
                                         kOther, kOther,     kOther,     kPacked<8>};
// The avx2 kernel: packed by stride as above; every other pair takes the bmi2 code.
template <int kS>
constexpr Kernels kAvx2Packed{any_avx2_packed<kS>, first_avx2_packed<kS>, count_avx2_packed<kS>};
constexpr std::array<Kernels, 9> kAvx2{kBmi2, kAvx2Packed<1>, kAvx2Packed<2>, kBmi2, kAvx2Packed<4>,
                                       kBmi2, kBmi2,          kBmi2,          kAvx2Packed<8>};
#endif

// The queries of kernel k (one the CPU has) for two present masks.
inline const Kernels& kernels_for(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
#ifdef JOSTLE_MASK_X86_KERNELS
    if (k >= MaskKernel::avx2) {
        const auto stride = static_cast<unsigned>(a.mask->words_per_row());
        const unsigned entry = stride == static_cast<unsigned>(b.mask->words_per_row()) && stride <= 8 ? stride : 0;
        return k == MaskKernel::avx512 ? kVector[entry] : kAvx2[entry];
    }
    if (k == MaskKernel::bmi2) return kBmi2;
#endif
    (void)a, (void)b, (void)k;
    return kPortable;
}

// A missing mask (a null PlacedMask::mask) shares no pixel; so does a 0-wide or 0-high one,
// which the kernels find without a test of their own.
bool any_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return a.mask != nullptr && b.mask != nullptr && kernels_for(a, b, k).any(a, b);
}
std::optional<Pixel> first_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    // One to_optional on both paths: two would merge their results through the stack.
    return to_optional(a.mask != nullptr && b.mask != nullptr ? kernels_for(a, b, k).first(a, b) : FirstPixel{0, 0});
}
int count_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return a.mask != nullptr && b.mask != nullptr ? kernels_for(a, b, k).count(a, b) : 0;
}

// ---------------------------------------------------------------------------------------
// The integer MTD search, shared by every mask pair
// ---------------------------------------------------------------------------------------

// Whether the search takes its shortcuts: a convex region's seeds and skipped columns, and
// the jumps along a mask's own columns (detail::use_mask_search_shortcuts: tests and the
// benchmarks compare the answers with the plain scan's).
std::atomic<bool> search_shortcuts{true};

// A candidate translation T of A, ranked by the mask MTD rule: shorter first; then the larger
// dot(T, centre A - centre B), which pushes A away from B's centre; then a fixed order: more
// horizontal first (smaller |dy|), then smaller dx, then smaller dy. So a pair with equal
// centres pushes A toward -x (normal {1, 0}), like coincident circles.
template <class Dot>
struct Candidate {
    i64 dx = 0;
    i64 dy = 0;
    i64 r2 = 0;
    Dot dot{};
};

template <class Dot>
bool ranks_before(const Candidate<Dot>& a, const Candidate<Dot>& b) {
    if (a.r2 != b.r2) return a.r2 < b.r2;
    if (a.dot != b.dot) return a.dot > b.dot;
    const i64 ady = a.dy < 0 ? -a.dy : a.dy;
    const i64 bdy = b.dy < 0 ? -b.dy : b.dy;
    if (ady != bdy) return ady < bdy;
    if (a.dx != b.dx) return a.dx < b.dx;
    return a.dy < b.dy;
}

// hit, depth = |T|, normal = -T / |T| (from A toward B): mtd() gives T back.
Manifold manifold_from(double dx, double dy) {
    const double len = std::sqrt(dx * dx + dy * dy);
    Manifold out;
    out.hit = true;
    out.depth = static_cast<float>(len);
    // 0 - v rather than -v: a zero component is +0, never -0 (state hashes read the bytes).
    out.normal = {static_cast<float>(0.0 - dx / len), static_cast<float>(0.0 - dy / len)};
    return out;
}

Manifold manifold_from(i64 dx, i64 dy) { return manifold_from(static_cast<double>(dx), static_cast<double>(dy)); }

// A pure-axis translation known to leave no shared pixel: it bounds the search.
struct AxisPush {
    i64 dx = 0;
    i64 dy = 0;
    i64 length() const { return std::abs(dx) + std::abs(dy); }
};

// The shortest free translation (09-31's MTD on the integer grid). Enumerating rings of equal
// dx^2 + dy^2 outward would test every translation shorter than the answer; instead, columns
// dx = 0, 1, -1, 2, -2, ... while dx^2 <= best: in a column only the smallest free |dy| can
// win, so scan down and up from dy = 0 and stop at the first free one or past the best length
// so far. The best under ranks_before is the same answer the rings give (ties included), with
// fewer tests: a problem may report a jump, that many translations on in the scan direction
// being certainly blocked. The bound is a free pure-axis push, so the search always ends at or
// before it; work grows with the answer, not with the bound. No allocation.
// Problem: bool blocked(i64 dx, i64 dy, int dir, i64& jump); Dot dot(i64 dx, i64 dy).
//
// The column scan alone still costs time linear in the answer's length (a mask deep in a large
// box tests every column out to it). A problem over a convex region offers two more hooks:
//   seed(consider)        free translations found from the region's geometry, so that best
//                         starts near the answer;
//   min_free_dy(d0, d1)   a lower bound on |dy| for every free translation with dx in [d0, d1];
//                         a run of columns that bound puts strictly beyond best is skipped.
// Neither can change the answer: a seed is one more free candidate for ranks_before, and a
// skipped column holds only longer ones. Runs start one column long and double after each
// skip; after a failed try the next waits twice as long, so a region that never allows a
// skip (a disc around the mask: every column's answer lies on the same ring) pays for a few
// tries only.
template <class Problem>
Manifold search_mtd(const Problem& p, AxisPush bound) {
    using Dot = decltype(p.dot(0, 0));
    const i64 limit = bound.length();
    Candidate<Dot> best;
    best.r2 = limit * limit;
    bool found = false;
    auto consider = [&](i64 dx, i64 dy) {
        const Candidate<Dot> c{dx, dy, dx * dx + dy * dy, p.dot(dx, dy)};
        if (!found || ranks_before(c, best)) {
            best = c;
            found = true;
        }
    };
    constexpr bool kBounded = requires { p.min_free_dy(i64{0}, i64{0}); };
    const auto seed = [&](i64 dx, i64 dy) {
        if (dx * dx + dy * dy <= best.r2) consider(dx, dy);
    };
    if constexpr (requires { p.seed(seed); }) p.seed(seed);
    struct Runs {  // per side: columns skipped up to skip_to; the next try's length and column
        i64 skip_to = -1;
        i64 span = 1;
        i64 next_try = 0;
        i64 wait = 1;
    };
    std::array<Runs, 2> runs;
    for (i64 m = 0; m * m <= best.r2; ++m) {
        for (int side = 0; side < (m == 0 ? 1 : 2); ++side) {
            const i64 dx = side == 0 ? m : -m;
            if constexpr (kBounded) {
                Runs& run = runs[static_cast<std::size_t>(side)];
                if (m <= run.skip_to) continue;
                if (m >= run.next_try) {
                    const i64 last = m + run.span - 1;
                    // Capped past the bound: nothing longer than it can be best.
                    const i64 dy = std::min(side == 0 ? p.min_free_dy(m, last) : p.min_free_dy(-last, -m), limit + 1);
                    if (m * m + dy * dy > best.r2) {
                        run = {last, run.span * 2, last + 1, 1};
                        continue;
                    }
                    run.span = 1;
                    run.next_try = m + run.wait;
                    run.wait *= 2;
                }
            }
            i64 jump = 1;
            if (!p.blocked(dx, 0, +1, jump)) {
                consider(dx, 0);
                continue;
            }
            // k stays <= limit + 1 (the bound is at most a few million), so k * k cannot overflow.
            for (i64 k = std::min(jump, limit + 1); k <= limit && dx * dx + k * k <= best.r2;) {
                if (!p.blocked(dx, k, +1, jump)) {
                    consider(dx, k);
                    break;
                }
                k += std::min(jump, limit + 1);
            }
            for (i64 k = 1; k <= limit && dx * dx + k * k <= best.r2;) {
                if (!p.blocked(dx, -k, -1, jump)) {
                    consider(dx, -k);
                    break;
                }
                k += std::min(jump, limit + 1);
            }
        }
    }
    // The bound itself is free, so `found` always holds; the fallback only keeps this total.
    return found ? manifold_from(best.dx, best.dy) : manifold_from(bound.dx, bound.dy);
}

// Mask vs mask: A moves, B stays.
struct MaskPairProblem {
    Placed a;
    Placed b;
    PixelBox box_a;  // set pixels, own coordinates
    PixelBox box_b;
    i64 cx2 = 0;  // 2 * (centre A - centre B), exact
    i64 cy2 = 0;

    i64 dot(i64 dx, i64 dy) const { return dx * cx2 + dy * cy2; }

    bool blocked(i64 dx, i64 dy, int dir, i64& jump) const {
        jump = 1;
        const i64 ax = a.x + dx;
        const i64 ay = a.y + dy;
        // The set pixels' rectangles apart: free without reading a word.
        if (ax + box_a.x0 > b.x + box_b.x1 || ax + box_a.x1 < b.x + box_b.x0 ||
            ay + box_a.y0 > b.y + box_b.y1 || ay + box_a.y1 < b.y + box_b.y0)
            return false;
        const Placed moved{a.m, ax, ay};
        Offset at = kNone;
        if (SharedWords s; share_words(moved, b, s)) at = dir > 0 ? first_shared(s) : last_row_first_shared(s);
        if (!at.found()) return false;
        // A's pixel there stays on B's pixels while B's column runs on in the scan direction,
        // and B's pixel stays under A's while A's column runs on against it: either run is a
        // jump (a thin B under a solid A needs the second).
        const i64 wx = std::max(ax, b.x) + at.col;
        const i64 wy = std::max(ay, b.y) + at.row;
        jump = column_run(*b.m, static_cast<int>(wx - b.x), static_cast<int>(wy - b.y), dir);
        if (search_shortcuts.load(std::memory_order_relaxed))
            jump = std::max(jump, column_run(*a.m, static_cast<int>(wx - ax), static_cast<int>(wy - ay), -dir));
        return true;
    }
};

// ---------------------------------------------------------------------------------------
// The other shapes as pixel regions (the pair table's "mask" rule)
// ---------------------------------------------------------------------------------------
// Each region gives: the pixel rule meets(left, top) for the pixel square with that top-left
// corner; row_range(top), the x-range where the shape meets the row's test line (solid: the
// centre line y = top + 0.5) or band (segment: top <= y <= top + 1); for solid shapes (kSolid)
// column_range(x), the vertical chord at x, and top_x / bottom_x, where the chord reaches
// highest / lowest; bounds; a centre for the tie rule. kNear and kFar give the
// part of a pixel the rule looks at along an axis: its centre (0.5, 0.5) or its square (0, 1).
// Tests run in double on float inputs: exact for coordinates on a fine binary grid, so pixel
// centres on a boundary count as inside exactly as the closed shapes require.

struct Bounds {
    double min_x = 0.0;
    double min_y = 0.0;
    double max_x = 0.0;
    double max_y = 0.0;
};

// A convex solid shape (Aabb, Obb, Polygon) as closed half-planes n.p <= c.
// Where a region is, for every kind: its bounds and its centre (the tie rule's "B's centre").
struct RegionPlace {
    Bounds bounds;
    double centre_x = 0.0;
    double centre_y = 0.0;
};

// A solid region also knows where its vertical chords end at the top and bottom.
struct SolidRegionPlace : RegionPlace {
    double top_x = 0.0;
    double bottom_x = 0.0;
};

struct ConvexRegion : SolidRegionPlace {
    static constexpr bool kSolid = true;
    static constexpr double kNear = 0.5;
    static constexpr double kFar = 0.5;
    int count = 0;
    std::array<double, kMaxPolygonVertices> nx{};
    std::array<double, kMaxPolygonVertices> ny{};
    std::array<double, kMaxPolygonVertices> c{};

    void add(double px, double py, double pc) {
        nx[static_cast<std::size_t>(count)] = px;
        ny[static_cast<std::size_t>(count)] = py;
        c[static_cast<std::size_t>(count)] = pc;
        ++count;
    }
    bool contains(double px, double py) const {
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i)
            if (!(nx[i] * px + ny[i] * py <= c[i])) return false;
        return true;
    }
    bool meets(double left, double top) const { return contains(left + 0.5, top + 0.5); }
    // Inside by at least `margin` from every face's line (for the MTD search's bound). Tested
    // against the faces themselves, not the vertices' bounds: a polygon moved or turned in
    // float may have a vertex a rounding outside the faces' intersection, which is the region.
    // (c - n.p >= margin |n|, squared: no root, and nothing added to building a region.)
    bool inside_by(double px, double py, double margin) const {
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
            const double room = c[i] - (nx[i] * px + ny[i] * py);
            if (!(room >= 0.0 && room * room >= margin * margin * (nx[i] * nx[i] + ny[i] * ny[i]))) return false;
        }
        return true;
    }
    // For the MTD search's seeds: through each face, the unit normal and the distance along it
    // that takes every point of the rectangle `pts` out of the region.
    template <class F>
    void exits(const Bounds& pts, F&& f) const {
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
            const double len = std::hypot(nx[i], ny[i]);
            if (!(len > 0.0)) continue;
            // The rectangle's corner farthest behind the face: the least n.p.
            const double least = (nx[i] >= 0.0 ? nx[i] * pts.min_x : nx[i] * pts.max_x) +
                                 (ny[i] >= 0.0 ? ny[i] * pts.min_y : ny[i] * pts.max_y);
            f(nx[i] / len, ny[i] / len, (c[i] - least) / len);
        }
    }
    // A plane with nx == 0 decides the row exactly as contains() does; the others give the
    // range approximately, and the caller settles its ends with meets().
    bool row_range(double top, double& lo, double& hi) const {
        const double py = top + 0.5;
        lo = -std::numeric_limits<double>::infinity();
        hi = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
            if (nx[i] == 0.0) {
                if (!(ny[i] * py <= c[i])) return false;
            } else if (nx[i] > 0.0) {
                hi = std::min(hi, (c[i] - ny[i] * py) / nx[i]);
            } else {
                lo = std::max(lo, (c[i] - ny[i] * py) / nx[i]);
            }
        }
        return true;
    }
    bool column_range(double px, double& lo, double& hi) const {
        lo = -std::numeric_limits<double>::infinity();
        hi = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
            if (ny[i] > 0.0) hi = std::min(hi, (c[i] - nx[i] * px) / ny[i]);
            else if (ny[i] < 0.0) lo = std::max(lo, (c[i] - nx[i] * px) / ny[i]);
        }
        return true;
    }
};

struct DiscRegion : SolidRegionPlace {
    static constexpr bool kSolid = true;
    static constexpr double kNear = 0.5;
    static constexpr double kFar = 0.5;
    double cx = 0.0;
    double cy = 0.0;
    double r = 0.0;

    bool meets(double left, double top) const {
        const double dx = left + 0.5 - cx;
        const double dy = top + 0.5 - cy;
        return dx * dx + dy * dy <= r * r;
    }
    // Inside by at least `margin` from the circle (for the MTD search's bound).
    bool inside_by(double px, double py, double margin) const {
        const double room = r - margin;
        return room > 0.0 && (px - cx) * (px - cx) + (py - cy) * (py - cy) <= room * room;
    }
    // For the MTD search's seeds: away from the centre through the rectangle's middle, far
    // enough that every point of the rectangle `pts` leaves the disc.
    template <class F>
    void exits(const Bounds& pts, F&& f) const {
        const double mx = 0.5 * (pts.min_x + pts.max_x);
        const double my = 0.5 * (pts.min_y + pts.max_y);
        const double half_diagonal = 0.5 * std::hypot(pts.max_x - pts.min_x, pts.max_y - pts.min_y);
        const double d = std::hypot(mx - cx, my - cy);
        if (d > 0.0) f((mx - cx) / d, (my - cy) / d, r + half_diagonal - d);
        else f(-1.0, 0.0, r + half_diagonal);
    }
    // Empty exactly when meets() is false for the whole row: dx^2 + dy^2 >= dy^2 > r^2.
    bool row_range(double top, double& lo, double& hi) const {
        const double dy = top + 0.5 - cy;
        const double room = r * r - dy * dy;
        if (room < 0.0) return false;
        const double s = std::sqrt(room);
        lo = cx - s;
        hi = cx + s;
        return true;
    }
    bool column_range(double px, double& lo, double& hi) const {
        const double dx = px - cx;
        const double room = std::max(0.0, r * r - dx * dx);
        const double s = std::sqrt(room);
        lo = cy - s;
        hi = cy + s;
        return true;
    }
};

// A segment meets a pixel when it touches the pixel's closed square: SAT with the axes x, y
// and the segment's normal (the square's corners not all strictly on one side).
struct SegmentRegion : RegionPlace {
    static constexpr bool kSolid = false;
    static constexpr double kNear = 0.0;
    static constexpr double kFar = 1.0;
    double ax = 0.0;
    double ay = 0.0;
    double bx = 0.0;
    double by = 0.0;

    bool meets(double left, double top) const {
        if (bounds.max_x < left || bounds.min_x > left + 1.0 || bounds.max_y < top || bounds.min_y > top + 1.0)
            return false;
        const double ex = bx - ax;
        const double ey = by - ay;
        bool below = false;
        bool above = false;
        const std::array<double, 4> xs{left, left + 1.0, left + 1.0, left};
        const std::array<double, 4> ys{top, top, top + 1.0, top + 1.0};
        for (std::size_t i = 0; i < 4; ++i) {
            const double s = ex * (ys[i] - ay) - ey * (xs[i] - ax);
            below = below || s <= 0.0;
            above = above || s >= 0.0;
        }
        return below && above;
    }
    // The part of the segment inside the band top <= y <= top + 1: emptiness is exact, the
    // x-range approximate (the caller widens it by a column and settles the ends).
    bool row_range(double top, double& lo, double& hi) const {
        if (bounds.max_y < top || bounds.min_y > top + 1.0) return false;
        if (ay == by) {
            lo = bounds.min_x;
            hi = bounds.max_x;
            return true;
        }
        double t0 = (top - ay) / (by - ay);
        double t1 = (top + 1.0 - ay) / (by - ay);
        if (t0 > t1) std::swap(t0, t1);
        t0 = std::clamp(t0, 0.0, 1.0);
        t1 = std::clamp(t1, 0.0, 1.0);
        const double x0 = ax + t0 * (bx - ax);
        const double x1 = ax + t1 * (bx - ax);
        lo = std::min(x0, x1);
        hi = std::max(x0, x1);
        return true;
    }
};

// Builders: a shape with a NaN or infinite coordinate (or a negative radius) is no region,
// so every query against it is a miss.
std::optional<ConvexRegion> raw_region_of(const Aabb& box) {
    if (!is_finite(box.min) || !is_finite(box.max)) return std::nullopt;
    ConvexRegion r;
    const double x0 = box.min.x, y0 = box.min.y, x1 = box.max.x, y1 = box.max.y;
    r.add(1.0, 0.0, x1);
    r.add(-1.0, 0.0, -x0);
    r.add(0.0, 1.0, y1);
    r.add(0.0, -1.0, -y0);
    r.bounds = {x0, y0, x1, y1};
    r.centre_x = 0.5 * (x0 + x1);
    r.centre_y = 0.5 * (y0 + y1);
    r.top_x = r.centre_x;
    r.bottom_x = r.centre_x;
    return r;
}

std::optional<ConvexRegion> raw_region_of(const Obb& box) {
    if (!is_finite(box.center) || !is_finite(box.half) || !std::isfinite(box.angle())) return std::nullopt;
    const Rot q = box.rotation();  // the same float rotation as the rest of the module
    const double ux = q.c, uy = q.s, vx = -q.s, vy = q.c;
    const double cx = box.center.x, cy = box.center.y, hx = box.half.x, hy = box.half.y;
    const double cu = ux * cx + uy * cy;
    const double cv = vx * cx + vy * cy;
    ConvexRegion r;
    r.add(ux, uy, cu + hx);
    r.add(-ux, -uy, -cu + hx);
    r.add(vx, vy, cv + hy);
    r.add(-vx, -vy, -cv + hy);
    const double ex = std::abs(ux) * hx + std::abs(vx) * hy;
    const double ey = std::abs(uy) * hx + std::abs(vy) * hy;
    r.bounds = {cx - ex, cy - ey, cx + ex, cy + ey};
    r.centre_x = cx;
    r.centre_y = cy;
    // The lowest corner is centre + (+-u hx) + (+-v hy) with the signs of uy and vy; the top
    // one is opposite.
    const double sx = (uy >= 0.0 ? ux : -ux) * hx + (vy >= 0.0 ? vx : -vx) * hy;
    r.top_x = cx - sx;
    r.bottom_x = cx + sx;
    return r;
}

// A Polygon is convex and wound one way by construction; its half-planes are rebuilt here in
// double from the points (the winding read from the area, whichever way it is), so that a
// pixel is decided by the exact edge line. Non-finite points (a polygon moved past float's
// range) are a miss, as is anything without area (kept as a guard: no valid Polygon has none).
std::optional<ConvexRegion> raw_region_of(const Polygon& poly) {
    if (poly.count() < 3 || poly.count() > kMaxPolygonVertices) return std::nullopt;
    const auto n = static_cast<std::size_t>(poly.count());
    double area2 = 0.0;
    Bounds b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    double sx = 0.0;
    double sy = 0.0;
    Vec2 top = poly.points()[0];
    Vec2 bottom = poly.points()[0];
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 p = poly.points()[i];
        const Vec2 p2 = poly.points()[(i + 1) % n];
        if (!is_finite(p)) return std::nullopt;
        if (p.y < top.y) top = p;
        if (p.y > bottom.y) bottom = p;
        area2 += static_cast<double>(p.x) * p2.y - static_cast<double>(p.y) * p2.x;
        b = {std::min<double>(b.min_x, p.x), std::min<double>(b.min_y, p.y), std::max<double>(b.max_x, p.x),
             std::max<double>(b.max_y, p.y)};
        sx += p.x;
        sy += p.y;
    }
    if (area2 == 0.0 || !std::isfinite(area2)) return std::nullopt;
    const double sign = area2 > 0.0 ? 1.0 : -1.0;
    ConvexRegion r;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 p = poly.points()[i];
        const Vec2 p2 = poly.points()[(i + 1) % n];
        // Inside when cross(e, q - p) >= 0 (for cross(e[i], e[i+1]) > 0): n = (e.y, -e.x).
        const double ex = static_cast<double>(p2.x) - p.x;
        const double ey = static_cast<double>(p2.y) - p.y;
        const double nx = sign * ey;
        const double ny = -sign * ex;
        r.add(nx, ny, nx * p.x + ny * p.y);
    }
    r.bounds = b;
    r.centre_x = sx / static_cast<double>(n);  // the vertex mean
    r.centre_y = sy / static_cast<double>(n);
    r.top_x = top.x;
    r.bottom_x = bottom.x;
    return r;
}

std::optional<DiscRegion> raw_region_of(const Circle& c) {
    if (!is_finite(c.center) || !std::isfinite(c.radius) || c.radius < 0.0f) return std::nullopt;
    DiscRegion r;
    r.cx = c.center.x;
    r.cy = c.center.y;
    r.r = c.radius;
    r.bounds = {r.cx - r.r, r.cy - r.r, r.cx + r.r, r.cy + r.r};
    r.centre_x = r.cx;
    r.centre_y = r.cy;
    r.top_x = r.cx;
    r.bottom_x = r.cx;
    return r;
}

std::optional<SegmentRegion> raw_region_of(const Segment& s) {
    if (!is_finite(s.a) || !is_finite(s.b)) return std::nullopt;
    SegmentRegion r;
    r.ax = s.a.x;
    r.ay = s.a.y;
    r.bx = s.b.x;
    r.by = s.b.y;
    r.bounds = {std::min(r.ax, r.bx), std::min(r.ay, r.by), std::max(r.ax, r.bx), std::max(r.ay, r.by)};
    r.centre_x = 0.5 * (r.ax + r.bx);
    r.centre_y = 0.5 * (r.ay + r.by);
    return r;
}

// Shapes reaching beyond +-1e9 px (far outside the coordinate limits) are no region either:
// the pixel search there would run for ever or overflow, and a miss is a defined answer. So is
// a shape the other queries call malformed (detail::valid: the module's one rule).
constexpr double kMaxRegionCoordinate = 1e9;

template <class S>
auto region_of(const S& shape) {
    auto r = raw_region_of(shape);
    if (r && !detail::valid(shape)) r.reset();
    if (r && !(std::abs(r->bounds.min_x) <= kMaxRegionCoordinate && std::abs(r->bounds.min_y) <= kMaxRegionCoordinate &&
               std::abs(r->bounds.max_x) <= kMaxRegionCoordinate && std::abs(r->bounds.max_y) <= kMaxRegionCoordinate)) {
        r.reset();
    }
    return r;
}

// Turns a range of pixel indices computed in double into ints inside [limit_lo, limit_hi];
// false when it misses them (NaN compares false, so it misses too).
bool clamp_range(double f0, double f1, int limit_lo, int limit_hi, int& i0, int& i1) {
    if (!(f0 <= f1) || f1 < limit_lo || f0 > limit_hi) return false;
    i0 = f0 < limit_lo ? limit_lo : static_cast<int>(f0);
    i1 = f1 > limit_hi ? limit_hi : static_cast<int>(f1);
    return true;
}

// Columns [i0, i1] (of limit_lo..limit_hi) of the mask row whose top is `top`, placed at x,
// that meet the region. A convex shape meets a row in one interval (one run of pixels, which
// is why a row costs one span and a few word ANDs): the region's x-range, widened a column each
// way for rounding, then its ends settled by the exact pixel test.
template <class R>
bool row_columns(const R& r, i64 x, i64 top, int limit_lo, int limit_hi, int& i0, int& i1) {
    double lo = 0.0;
    double hi = 0.0;
    const double yd = static_cast<double>(top);
    if (!r.row_range(yd, lo, hi)) return false;
    const double xd = static_cast<double>(x);
    if (!clamp_range(std::ceil(lo - xd - R::kFar) - 1.0, std::floor(hi - xd - R::kNear) + 1.0, limit_lo, limit_hi,
                     i0, i1))
        return false;
    while (i0 <= i1 && !r.meets(xd + i0, yd)) ++i0;
    while (i1 >= i0 && !r.meets(xd + i1, yd)) --i1;
    return i0 <= i1;
}

// Visits the set pixels of mask m (placed at x, y) that meet region r, a word at a time:
// visit(row, column of bit 0, word), rows top to bottom (bottom to top when `upward`), only
// inside `window` (the mask's own pixels, inclusive); returning true stops the walk.
template <class R, class Visit>
bool visit_region_words(const Mask& m, i64 x, i64 y, const R& r, const PixelBox& window, bool upward, Visit&& visit) {
    const double yd = static_cast<double>(y);
    int j0 = 0;
    int j1 = 0;
    if (!clamp_range(std::ceil(r.bounds.min_y - yd - R::kFar) - 1.0, std::floor(r.bounds.max_y - yd - R::kNear) + 1.0,
                     window.y0, window.y1, j0, j1))
        return false;
    for (int n = 0; n <= j1 - j0; ++n) {
        const int j = upward ? j1 - n : j0 + n;
        int i0 = 0;
        int i1 = 0;
        if (!row_columns(r, x, y + j, window.x0, window.x1, i0, i1)) continue;
        const u64* row = m.row(j);
        for (int k = i0 >> 6; k <= i1 >> 6; ++k) {
            u64 w = row[k];
            if (k == i0 >> 6) w &= ~u64{0} << (i0 & 63);
            if (k == i1 >> 6) w &= ~u64{0} >> (63 - (i1 & 63));
            if (w != 0 && visit(j, k * 64, w)) return true;
        }
    }
    return false;
}

PixelBox whole(const Mask& m) { return {0, 0, m.width() - 1, m.height() - 1}; }

template <class R>
std::optional<Pixel> first_in(const PlacedMask& a, const std::optional<R>& r) {
    if (!usable(a.mask) || !r) return std::nullopt;
    std::optional<Pixel> out;
    visit_region_words(*a.mask, a.x, a.y, *r, whole(*a.mask), false, [&](int j, int i, u64 w) {
        out = Pixel{static_cast<int>(static_cast<i64>(a.x) + i + std::countr_zero(w)),
                    static_cast<int>(static_cast<i64>(a.y) + j)};
        return true;
    });
    return out;
}

template <class R>
int count_in(const PlacedMask& a, const std::optional<R>& r) {
    if (!usable(a.mask) || !r) return 0;
    int n = 0;
    visit_region_words(*a.mask, a.x, a.y, *r, whole(*a.mask), false, [&](int, int, u64 w) {
        n += std::popcount(w);
        return false;
    });
    return n;
}

// Pushes past this length are outside the coordinate limits (|x|, |y| <= 1e5 plus a mask):
// there the answer is the bound below (a pure-axis push clearing the shape's bounds, at most
// two pixels long), without a search.
constexpr double kMaxSearchedPush = 1 << 20;

// Pushes up to this length are searched column by column alone; past it, a convex region's
// search also takes seeds and skips columns (search_mtd), which costs a few tests to set up.
constexpr double kProbedPush = 16;

// Mask vs a fixed region: the mask moves.
template <class R>
struct RegionProblem {
    const Mask* m = nullptr;
    i64 x = 0;
    i64 y = 0;
    const R* r = nullptr;
    PixelBox box;      // set pixels, own coordinates
    double cx = 0.0;   // centre A - centre B
    double cy = 0.0;

    double dot(i64 dx, i64 dy) const { return static_cast<double>(dx) * cx + static_cast<double>(dy) * cy; }

    bool blocked(i64 dx, i64 dy, int dir, i64& jump) const {
        jump = 1;
        const double left = static_cast<double>(x + dx + box.x0);
        const double right = static_cast<double>(x + dx + box.x1);
        const double top = static_cast<double>(y + dy + box.y0);
        const double bottom = static_cast<double>(y + dy + box.y1);
        // The set pixels' rectangle apart from the region's bounds: free without a test.
        if (left + R::kNear > r->bounds.max_x || right + R::kFar < r->bounds.min_x ||
            top + R::kNear > r->bounds.max_y || bottom + R::kFar < r->bounds.min_y)
            return false;
        int wi = 0;
        int wj = 0;
        const bool hit = visit_region_words(*m, x + dx, y + dy, *r, box, dir < 0, [&](int j, int i, u64 w) {
            wi = i + std::countr_zero(w);
            wj = j;
            return true;
        });
        if (!hit) return false;
        // The witness pixel's column in the mask: its set pixels behind it (against the scan)
        // take its place on the region in turn. It is what lets a segment or a sliver, which
        // holds no pixel inside, cross a solid mask in a few tests a column.
        // (A solid region's chord usually gives more, and a run is at most the rows behind.)
        if constexpr (R::kSolid) jump = solid_jump(dx, dy, dir, wj);
        if (jump < (dir > 0 ? wj - box.y0 : box.y1 - wj) + 1 && search_shortcuts.load(std::memory_order_relaxed))
            jump = std::max(jump, column_run(*m, wi, wj, -dir));
        return true;
    }

    // A pixel whose centre is inside the convex shape stays inside until it leaves the vertical
    // chord through it: floor(room) more steps are certainly blocked (rounding of less than a
    // pixel cannot make that too many). Any such witness will do; the row farthest back
    // (first met walking against the motion), at the set pixel nearest the column where the
    // chord reaches farthest, gives a long jump, so a deep mask leaves a large shape in a few tests.
    i64 solid_jump(i64 dx, i64 dy, int dir, int j) const {
        int i0 = 0;
        int i1 = 0;
        if (!row_columns(*r, x + dx, y + dy + j, box.x0, box.x1, i0, i1)) return 1;
        const double far_x = (dir > 0 ? r->bottom_x : r->top_x) - static_cast<double>(x + dx) - 0.5;
        const int c = static_cast<int>(std::clamp(std::round(far_x), static_cast<double>(i0), static_cast<double>(i1)));
        const u64* row = m->row(j);
        const std::array<int, 2> witnesses{last_set_at_or_before(row, c), first_set_at_or_after(row, m->words_per_row(), c)};
        const double qy = static_cast<double>(y + dy + j) + 0.5;
        i64 jump = 1;
        for (const int i : witnesses) {
            if (i < i0 || i > i1) continue;
            double lo = 0.0;
            double hi = 0.0;
            r->column_range(static_cast<double>(x + dx + i) + 0.5, lo, hi);
            const double room = dir > 0 ? hi - qy : qy - lo;
            if (room >= 1.0) jump = std::max(jump, static_cast<i64>(std::floor(std::min(room, 1e12))));
        }
        return jump;
    }

    // For search_mtd's hooks (solid regions): set pixels, in own coordinates, whose vertical
    // chords bound the push: the top and the bottom set pixel of five columns across the set
    // pixels' box. None: no seeds, no bound.
    struct Probe {
        int i = 0;
        int j = 0;
    };
    std::array<Probe, 10> probes{};
    int probe_count = 0;

    void add_probes() {
        const int w = box.x1 - box.x0;
        for (const int i : {box.x0, box.x0 + w / 4, box.x0 + w / 2, box.x0 + 3 * w / 4, box.x1}) {
            int top = -1;
            int bottom = -1;
            for (int j = box.y0; j <= box.y1; ++j)
                if (m->get(i, j)) {
                    if (top < 0) top = j;
                    bottom = j;
                }
            if (top < 0) continue;
            probes[static_cast<std::size_t>(probe_count++)] = {i, top};
            probes[static_cast<std::size_t>(probe_count++)] = {i, bottom};
        }
    }

    // Each face's (or the disc's) exit, a pixel longer than needed: rounding the translation to
    // whole pixels moves it less than 0.71 px. Offered only if free.
    template <class F>
    void seed(F&& consider) const
        requires R::kSolid
    {
        if (probe_count == 0) return;
        const Bounds centres{static_cast<double>(x + box.x0) + 0.5, static_cast<double>(y + box.y0) + 0.5,
                             static_cast<double>(x + box.x1) + 0.5, static_cast<double>(y + box.y1) + 0.5};
        r->exits(centres, [&](double ux, double uy, double t) {
            if (!(t > 0.0 && t <= kMaxSearchedPush)) return;
            const i64 dx = std::llround(ux * (t + 1.0));
            const i64 dy = std::llround(uy * (t + 1.0));
            i64 jump = 1;
            if (!blocked(dx, dy, +1, jump)) consider(dx, dy);
        });
    }

    // A lower bound on |dy| for a free translation with dx in [d0, d1]. A probe whose centre
    // lies inside the region, by a margin, at d0 and at d1 lies inside at every column between
    // (the region, an intersection of half-planes or a disc, is convex), and moved along its
    // column by less than the distance to the chord's end it stays inside. That distance is a
    // concave function of the column (the chord's top is convex, its bottom concave), so its
    // least over the run is at d0 or d1. Every probe inside must leave: moving up by more than
    // the largest such distance up, or down by more than the largest down. The margin covers
    // rounding in the chord's ends; inside by it from every face, a probe's column is one
    // where the faces that are not vertical (those column_range reads) bound the chord.
    i64 min_free_dy(i64 d0, i64 d1) const
        requires R::kSolid
    {
        constexpr double kMargin = 1e-3;
        double up = 0.0;
        double down = 0.0;
        for (int k = 0; k < probe_count; ++k) {
            const Probe& q = probes[static_cast<std::size_t>(k)];
            const double qy = static_cast<double>(y + q.j) + 0.5;
            double need_up = std::numeric_limits<double>::infinity();
            double need_down = need_up;
            bool inside = true;
            for (const i64 d : {d0, d1}) {
                const double px = static_cast<double>(x + d + q.i) + 0.5;
                inside = r->inside_by(px, qy, kMargin);
                if (!inside) break;
                double lo = 0.0;
                double hi = 0.0;
                r->column_range(px, lo, hi);
                need_up = std::min(need_up, qy - lo);
                need_down = std::min(need_down, hi - qy);
            }
            if (!inside) continue;
            up = std::max(up, need_up);
            down = std::max(down, need_down);
        }
        const double need = std::min(up, down);
        return need > kMargin ? static_cast<i64>(std::floor(std::min(need - kMargin, 1e12))) + 1 : 0;
    }
};

template <class R>
Manifold collide_region(const PlacedMask& a, const std::optional<R>& r) {
    if (!usable(a.mask) || !r) return {};
    const Mask& m = *a.mask;
    const auto stop = [](int, int, u64) { return true; };
    if (!visit_region_words(m, a.x, a.y, *r, whole(m), false, stop)) return {};
    const PixelBox box = set_pixel_box(m);
    // The bound: move the set pixels' rectangle past the region's bounds along one axis (a
    // pixel more than needed, so rounding in the bounds cannot matter).
    const double x0 = static_cast<double>(a.x) + box.x0;
    const double x1 = static_cast<double>(a.x) + box.x1;
    const double y0 = static_cast<double>(a.y) + box.y0;
    const double y1 = static_cast<double>(a.y) + box.y1;
    const std::array<double, 4> push{
        std::floor(r->bounds.max_x - x0 - R::kNear) + 2.0,  // right
        std::ceil(r->bounds.min_x - x1 - R::kFar) - 2.0,   // left
        std::floor(r->bounds.max_y - y0 - R::kNear) + 2.0,  // down
        std::ceil(r->bounds.min_y - y1 - R::kFar) - 2.0,   // up
    };
    std::size_t pick = 0;
    for (std::size_t i = 1; i < 4; ++i)
        if (std::abs(push[i]) < std::abs(push[pick])) pick = i;
    const double length = std::max(1.0, std::abs(push[pick]));
    const double sign = (pick % 2 == 0) ? 1.0 : -1.0;
    const double bx = pick < 2 ? sign * length : 0.0;
    const double by = pick < 2 ? 0.0 : sign * length;
    if (length > kMaxSearchedPush) return manifold_from(bx, by);
    RegionProblem<R> p;
    p.m = &m;
    p.x = a.x;
    p.y = a.y;
    p.r = &*r;
    p.box = box;
    p.cx = static_cast<double>(a.x) + 0.5 * m.width() - r->centre_x;
    p.cy = static_cast<double>(a.y) + 0.5 * m.height() - r->centre_y;
    if constexpr (R::kSolid)
        if (length > kProbedPush && search_shortcuts.load(std::memory_order_relaxed)) p.add_probes();
    return search_mtd(p, AxisPush{static_cast<i64>(bx), static_cast<i64>(by)});
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Mask vs mask (bit-packed)
// ---------------------------------------------------------------------------------------

namespace {

// The best kernel this CPU has, found when the library is loaded: a constant of the machine,
// not state. A query made before that (from another file's static initializer) reads its zero
// value, portable: slower, with the same answers.
const MaskKernel kBestKernel = usable_kernel(MaskKernel::avx512);

}  // namespace

bool overlaps(const PlacedMask& a, const PlacedMask& b) { return any_with(a, b, kBestKernel); }
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b) { return first_with(a, b, kBestKernel); }
int count_overlap(const PlacedMask& a, const PlacedMask& b) { return count_with(a, b, kBestKernel); }

namespace detail {
MaskKernel best_mask_kernel() { return kBestKernel; }
bool overlaps(const PlacedMask& a, const PlacedMask& b, MaskKernel k) { return any_with(a, b, usable_kernel(k)); }
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return first_with(a, b, usable_kernel(k));
}
int count_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k) { return count_with(a, b, usable_kernel(k)); }
bool use_mask_search_shortcuts(bool on) {
    search_shortcuts.store(on, std::memory_order_relaxed);
    return on;
}
}  // namespace detail

Manifold collide(const PlacedMask& a, const PlacedMask& b) {
    if (!overlaps(a, b)) return {};
    MaskPairProblem p;
    p.a = placed(a);
    p.b = placed(b);
    p.box_a = set_pixel_box(*a.mask);
    p.box_b = set_pixel_box(*b.mask);
    p.cx2 = 2 * (p.a.x - p.b.x) + a.mask->width() - b.mask->width();
    p.cy2 = 2 * (p.a.y - p.b.y) + a.mask->height() - b.mask->height();
    // The bound: the cheapest push of A's set pixels' rectangle past B's along one axis.
    const i64 ax0 = p.a.x + p.box_a.x0, ax1 = p.a.x + p.box_a.x1, ay0 = p.a.y + p.box_a.y0, ay1 = p.a.y + p.box_a.y1;
    const i64 bx0 = p.b.x + p.box_b.x0, bx1 = p.b.x + p.box_b.x1, by0 = p.b.y + p.box_b.y0, by1 = p.b.y + p.box_b.y1;
    const std::array<AxisPush, 4> pushes{AxisPush{bx1 - ax0 + 1, 0}, AxisPush{-(ax1 - bx0 + 1), 0},
                                         AxisPush{0, by1 - ay0 + 1}, AxisPush{0, -(ay1 - by0 + 1)}};
    AxisPush bound = pushes[0];
    for (const AxisPush& push : pushes)
        if (push.length() < bound.length()) bound = push;
    return search_mtd(p, bound);
}

// ---------------------------------------------------------------------------------------
// Mask vs the other shapes
// ---------------------------------------------------------------------------------------

bool overlaps(const PlacedMask& a, const Aabb& b) { return first_in(a, region_of(b)).has_value(); }
std::optional<Pixel> first_overlap(const PlacedMask& a, const Aabb& b) { return first_in(a, region_of(b)); }
int count_overlap(const PlacedMask& a, const Aabb& b) { return count_in(a, region_of(b)); }

Manifold collide(const PlacedMask& a, const Aabb& b) { return collide_region(a, region_of(b)); }
Manifold collide(const PlacedMask& a, const Obb& b) { return collide_region(a, region_of(b)); }
Manifold collide(const PlacedMask& a, const Polygon& b) { return collide_region(a, region_of(b)); }
Manifold collide(const PlacedMask& a, const Circle& b) { return collide_region(a, region_of(b)); }
Manifold collide(const PlacedMask& a, const Segment& b) { return collide_region(a, region_of(b)); }

int count_overlap(const PlacedMask& a, const Shape& b) {
    return std::visit(
        [&](const auto& s) -> int {
            if constexpr (std::is_same_v<std::decay_t<decltype(s)>, PlacedMask>) return count_overlap(a, s);
            else return count_in(a, region_of(s));
        },
        b);
}

std::optional<Pixel> first_overlap(const PlacedMask& a, const Shape& b) {
    return std::visit(
        [&](const auto& s) -> std::optional<Pixel> {
            if constexpr (std::is_same_v<std::decay_t<decltype(s)>, PlacedMask>) return first_overlap(a, s);
            else return first_in(a, region_of(s));
        },
        b);
}

// The nearest point of any set pixel's closed square. An empty or missing mask, or a
// non-finite q, has no nearest point: the answer is point {0, 0}, distance = +infinity.
// Rows are visited outward from q's row and stop once a row is farther than the best; in a
// row only the set pixels just left and right of q's column can be nearest.
ClosestPoint closest_point(const PlacedMask& m, Vec2 q) {
    const ClosestPoint none{{0.0f, 0.0f}, std::numeric_limits<float>::infinity()};  // as for every shape
    if (!usable(m.mask) || !is_finite(q)) return none;
    const Mask& mask = *m.mask;
    const double qx = q.x;
    const double qy = q.y;
    const double mx = m.x;
    const double my = m.y;
    const double w = mask.width();
    const double h = mask.height();
    const int start_row = static_cast<int>(std::clamp(std::floor(qy - my), 0.0, h - 1.0));
    const int column = static_cast<int>(std::clamp(std::floor(qx - mx), 0.0, w - 1.0));
    double best = std::numeric_limits<double>::infinity();
    double px = qx;
    double py = qy;
    auto gap = [](double v, double lo) { return std::max({0.0, lo - v, v - (lo + 1.0)}); };
    auto try_row = [&](int j) -> bool {  // false once this row and all beyond are too far
        const double gy = gap(qy, my + j);
        if (gy * gy >= best) return false;
        const u64* row = mask.row(j);
        const std::array<int, 2> candidates{last_set_at_or_before(row, column),
                                            first_set_at_or_after(row, mask.words_per_row(), column)};
        for (const int i : candidates) {
            if (i < 0) continue;
            const double gx = gap(qx, mx + i);
            const double d2 = gx * gx + gy * gy;
            if (d2 < best) {
                best = d2;
                px = std::clamp(qx, mx + i, mx + i + 1.0);
                py = std::clamp(qy, my + j, my + j + 1.0);
            }
        }
        return true;
    };
    for (int j = start_row; j < mask.height() && try_row(j); ++j) {
    }
    for (int j = start_row - 1; j >= 0 && try_row(j); --j) {
    }
    if (best == std::numeric_limits<double>::infinity()) return none;
    return {Vec2{static_cast<float>(px), static_cast<float>(py)}, static_cast<float>(std::sqrt(best))};
}

// ---------------------------------------------------------------------------------------
// reference: the lecture's brute-force loop (09-3), corrected; slow, for tests
// ---------------------------------------------------------------------------------------

namespace reference {

namespace {

// The slide's loop: T1 is A at (x1, y1), T2 is B at (x2, y2), deltax = x2 - x1. It has two
// mistakes, fixed here: pixel x of A lies at world x1 + x, which is pixel x1 + x - x2 =
// x - deltax of B (the slide writes x + deltax); and B's column and row 0 are valid, so the
// bounds are >= 0 (the slide writes > 0). visit(world x, world y) gets every shared pixel.
template <class Visit>
bool lecture_loop(const Mask& t1, i64 x1, i64 y1, const Mask& t2, i64 x2, i64 y2, Visit&& visit) {
    const i64 w1 = t1.width(), h1 = t1.height(), w2 = t2.width(), h2 = t2.height();
    const i64 deltax = x2 - x1;
    const i64 deltay = y2 - y1;
    // 09-30: only A's pixels inside the intersection of the two rectangles.
    const i64 x_begin = std::max<i64>(0, deltax), x_end = std::min(w1, deltax + w2);
    const i64 y_begin = std::max<i64>(0, deltay), y_end = std::min(h1, deltay + h2);
    // Rows outside, unlike the slide, so that pixels come in reading order (first_overlap).
    for (i64 y = y_begin; y < y_end; ++y) {
        for (i64 x = x_begin; x < x_end; ++x) {
            if (x - deltax >= 0 && x - deltax < w2 && y - deltay >= 0 && y - deltay < h2 &&  // fixed: >= 0
                t1.get(static_cast<int>(x), static_cast<int>(y)) &&
                t2.get(static_cast<int>(x - deltax), static_cast<int>(y - deltay)))  // fixed: x - deltax
                if (visit(x1 + x, y1 + y)) return true;
        }
    }
    return false;
}

}  // namespace

bool overlaps(const PlacedMask& a, const PlacedMask& b) {
    if (a.mask == nullptr || b.mask == nullptr) return false;
    return lecture_loop(*a.mask, a.x, a.y, *b.mask, b.x, b.y, [](i64, i64) { return true; });
}

std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b) {
    if (a.mask == nullptr || b.mask == nullptr) return std::nullopt;
    std::optional<Pixel> out;
    lecture_loop(*a.mask, a.x, a.y, *b.mask, b.x, b.y, [&](i64 x, i64 y) {
        out = Pixel{static_cast<int>(x), static_cast<int>(y)};
        return true;
    });
    return out;
}

int count_overlap(const PlacedMask& a, const PlacedMask& b) {
    if (a.mask == nullptr || b.mask == nullptr) return 0;
    int n = 0;
    lecture_loop(*a.mask, a.x, a.y, *b.mask, b.x, b.y, [&](i64, i64) {
        ++n;
        return false;
    });
    return n;
}

Manifold collide(const PlacedMask& a, const PlacedMask& b) {
    if (a.mask == nullptr || b.mask == nullptr) return {};
    const Mask& ma = *a.mask;
    const Mask& mb = *b.mask;
    auto blocked = [&](i64 dx, i64 dy) {
        return lecture_loop(ma, a.x + dx, a.y + dy, mb, b.x, b.y, [](i64, i64) { return true; });
    };
    if (!blocked(0, 0)) return {};
    // The bound: the cheapest pure-axis push, found by stepping each way until free (after
    // the two widths or heights the rectangles are apart, so each walk ends).
    i64 bound = std::numeric_limits<i64>::max();
    const std::array<std::array<i64, 2>, 4> axes{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    for (const auto& axis : axes) {
        for (i64 k = 1;; ++k) {
            if (!blocked(k * axis[0], k * axis[1])) {
                bound = std::min(bound, k);
                break;
            }
        }
    }
    // Every translation in the bound's disc; the best by (length, larger dot with the centres'
    // difference, smaller |dy|, smaller dx, smaller dy) is the shortest-first answer.
    const i64 cx2 = 2 * (static_cast<i64>(a.x) - b.x) + ma.width() - mb.width();
    const i64 cy2 = 2 * (static_cast<i64>(a.y) - b.y) + ma.height() - mb.height();
    std::optional<std::tuple<i64, i64, i64, i64, i64>> best;
    for (i64 dy = -bound; dy <= bound; ++dy) {
        for (i64 dx = -bound; dx <= bound; ++dx) {
            const i64 r2 = dx * dx + dy * dy;
            if (r2 == 0 || r2 > bound * bound || blocked(dx, dy)) continue;
            const std::tuple<i64, i64, i64, i64, i64> key{r2, -(dx * cx2 + dy * cy2), std::abs(dy), dx, dy};
            if (!best || key < *best) best = key;
        }
    }
    return manifold_from(std::get<3>(*best), std::get<4>(*best));
}

}  // namespace reference

}  // namespace jostle
