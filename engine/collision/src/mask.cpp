// mask.cpp: 1-bit pixel masks (slides 09-0 to 09-5 and 09-30): the bit-packed Mask; mask vs
// mask overlap, first shared pixel, count and integer MTD; the same against the other shapes
// by the pixel rule; the nearest point of a mask; and the lecture's loop, corrected, in reference::.
#include <algorithm>
#include <array>
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

#include "jostle/collision.h"
#include "jostle/core/error.h"

namespace jostle {

namespace {

using i64 = std::int64_t;
using u64 = std::uint64_t;

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
    // One clear word past the last row: the mask queries read the word after a row's last one
    // (two adjacent words joined by a shift) and mask off its bits, so a row's last word has a
    // readable neighbour, the next row's first word or this one (8 bytes a mask).
    bits_.assign(static_cast<std::size_t>(words_per_row_) * static_cast<std::size_t>(height) + 1, 0);
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
// width) and O's are its own clear bits or the next row's (or the padding word after the last
// row, see Mask::Mask), so nothing outside a mask's storage is read and every read bit that
// counts lies inside both masks. The setup is a few dozen instructions: for small masks it is
// most of a query's cost.
struct SharedWords {
    const u64* p;             // P's word 0 in the first shared row
    const u64* o;             // O's word holding the column under P's column 0 there
    std::ptrdiff_t p_stride;  // P's words per row
    std::ptrdiff_t o_stride;  // O's words per row
    int shift;                // that column's bit in its O word
    int rows;                 // shared rows, >= 1
    int words;                // chunks per shared row, >= 1
    u64 tail;                 // the valid bits of a row's last chunk
};

// The mask and position of a query's argument (PlacedMask) or of the MTD search's translated
// mask (Placed, whose i64 position cannot overflow).
inline const Mask* mask_of(const PlacedMask& p) { return p.mask; }
inline const Mask* mask_of(const Placed& p) { return p.m; }

// Sets s up for the pair; false when the rectangles share no pixel.
template <class P>
[[gnu::always_inline]] inline bool share_words(const P& a, const P& b, SharedWords& s) {
    const Mask* const am = mask_of(a);
    const Mask* const bm = mask_of(b);
    const auto ax = static_cast<i64>(a.x), ay = static_cast<i64>(a.y);
    const auto bx = static_cast<i64>(b.x), by = static_cast<i64>(b.y);
    const i64 x0 = std::max(ax, bx);
    const i64 x1 = std::min(ax + am->width(), bx + bm->width());
    const i64 y0 = std::max(ay, by);
    const i64 y1 = std::min(ay + am->height(), by + bm->height());
    if (x0 >= x1 || y0 >= y1) return false;
    // P: the mask whose column 0 is x0 (A when a.x >= b.x). GCC makes this a branch; selects
    // done with masks measured slower (they put the choice on the chain of dependent loads).
    const bool a_aligned = ax >= bx;
    const Mask* const pm = a_aligned ? am : bm;
    const Mask* const om = a_aligned ? bm : am;
    const i64 py = a_aligned ? ay : by;
    const i64 ox = a_aligned ? bx : ax;
    const i64 oy = a_aligned ? by : ay;
    // The shared rectangle lies inside both masks, so these differences are small.
    const int c = static_cast<int>(x0 - ox);  // O's column under P's column 0, >= 0
    const int width = static_cast<int>(x1 - x0);
    s.p_stride = pm->words_per_row();
    s.o_stride = om->words_per_row();
    s.p = pm->row(static_cast<int>(y0 - py));
    s.o = om->row(static_cast<int>(y0 - oy)) + (c >> 6);
    s.shift = c & 63;
    s.rows = static_cast<int>(y1 - y0);
    s.words = (width + 63) >> 6;
    s.tail = ~u64{0} >> ((64 - (width & 63)) & 63);  // width % 64 low bits; all 64 when 0
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
//   avx512    bmi2, and rows of 2..8 chunks as one vector each: VPSHRDVQ joins 8 word pairs in
//             one instruction (VBMI2), VPOPCNTQ counts them. Rows of one chunk stay scalar (a
//             gather of 8 such rows measured slower), and the setup stays in bmi2 code: the
//             vector code's frame costs more than a small query's work.
// Each kernel is a whole query, from the setup to the answer, so that the shared words stay in
// registers: a query on small masks is mostly setup.

using MaskKernel = detail::MaskKernel;

#if defined(__x86_64__) && defined(__GNUC__)
#define JOSTLE_MASK_X86_KERNELS 1
#define JOSTLE_BMI2 "popcnt,bmi,bmi2"
#define JOSTLE_AVX512 "popcnt,bmi,bmi2,avx2,avx512f,avx512vl,avx512bw,avx512vpopcntdq,avx512vbmi2"

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
// (the padding word after the last row included), so the same loads give it. Masked loads
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

// 4 * P's stride + O's stride when both are 1 or 2 words (5, 6, 9, 10), else 0.
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

// Rows of two masks with the same stride of kS = 2 or 4 words (up to 128 or 256 wide), 8 / kS
// rows per vector: such rows lie kS words apart in both masks, so one load of 8 words holds
// 8 / kS rows, and lane i * kS + c is chunk c of row r + i (lanes past a row's chunks, or past
// the last row, are masked off and never read). Lanes run in reading order.
struct PackedRows {
    unsigned lanes;  // the chunks of 8 / kS rows
    __m512i tail;    // s.tail in each row's last chunk, ~0 elsewhere
    __m512i shift;
};

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline PackedRows packed_rows(const SharedWords& s) {
    const unsigned row = (1u << s.words) - 1u;  // s.words <= kS: the shared width fits in both
    unsigned lanes = 0;
    unsigned last = 0;
    for (int i = 0; i < 8 / kS; ++i) {
        lanes |= row << (i * kS);
        last |= 1u << (i * kS + s.words - 1);
    }
    return {lanes, _mm512_mask_set1_epi64(_mm512_set1_epi64(-1), static_cast<__mmask8>(last), static_cast<long long>(s.tail)),
            _mm512_set1_epi64(s.shift)};
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline __m512i packed_vector(const SharedWords& s,
                                                                                 const PackedRows& v, int r) {
    const int left = s.rows - r;
    const unsigned rows = left >= 8 / kS ? 0xffu : (1u << (left * kS)) - 1u;
    const auto k = static_cast<__mmask8>(v.lanes & rows);
    const u64* p = s.p + r * kS;
    const u64* o = s.o + r * kS;
    const __m512i pw = _mm512_maskz_loadu_epi64(k, p);
    const __m512i lo = _mm512_maskz_loadu_epi64(k, o);
    const __m512i hi = _mm512_maskz_loadu_epi64(k, o + 1);
    return _mm512_and_si512(_mm512_and_si512(pw, _mm512_shrdv_epi64(lo, hi, v.shift)), v.tail);
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline int count_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    __m512i sum = _mm512_setzero_si512();
    for (int r = 0; r < s.rows; r += 8 / kS) sum = _mm512_add_epi64(sum, _mm512_popcnt_epi64(packed_vector<kS>(s, v, r)));
    return lane_sum(sum);
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline Offset first_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    for (int r = 0; r < s.rows; r += 8 / kS) {
        const __m512i w = packed_vector<kS>(s, v, r);
        if (const unsigned hit = _mm512_test_epi64_mask(w, w); hit != 0) {
            const int lane = std::countr_zero(hit);
            std::array<u64, 8> words;
            _mm512_storeu_si512(words.data(), w);
            return Offset{64 * (lane % kS) + std::countr_zero(words[static_cast<std::size_t>(lane)]), r + lane / kS};
        }
    }
    return kNone;
}

template <int kS>
[[gnu::target(JOSTLE_AVX512), gnu::always_inline]] inline bool any_packed(const SharedWords& s) {
    const PackedRows v = packed_rows<kS>(s);
    for (int r = 0; r < s.rows; r += 8 / kS)
        if (nonzero(packed_vector<kS>(s, v, r))) return true;
    return false;
}

// 2 or 4 when both masks' rows are that many words (rows of 2..4 chunks pack into vectors).
inline int packed_stride(const SharedWords& s) {
    return s.words > 1 && s.p_stride == s.o_stride && (s.p_stride == 2 || s.p_stride == 4) ? static_cast<int>(s.p_stride)
                                                                                             : 0;
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

// The queries, compiled into each kernel below.
template <class P>
[[gnu::always_inline]] inline bool any_query(const P& a, const P& b) {
    SharedWords s;
    return share_words(a, b, s) && any_shared(s);
}

template <class P>
[[gnu::always_inline]] inline Offset first_query(const P& a, const P& b) {
    SharedWords s;
    return share_words(a, b, s) ? first_shared(s) : kNone;
}

template <class P>
[[gnu::always_inline]] inline int count_query(const P& a, const P& b) {
    SharedWords s;
    return share_words(a, b, s) ? count_in_rows(s) : 0;
}

bool any_portable(const PlacedMask& a, const PlacedMask& b) { return any_query(a, b); }
Offset first_portable(const PlacedMask& a, const PlacedMask& b) { return first_query(a, b); }
int count_portable(const PlacedMask& a, const PlacedMask& b) { return count_query(a, b); }

#ifdef JOSTLE_MASK_X86_KERNELS
[[gnu::target(JOSTLE_BMI2)]] bool any_bmi2(const PlacedMask& a, const PlacedMask& b) { return any_query(a, b); }
[[gnu::target(JOSTLE_BMI2)]] Offset first_bmi2(const PlacedMask& a, const PlacedMask& b) {
    return first_query(a, b);
}
[[gnu::target(JOSTLE_BMI2)]] int count_bmi2(const PlacedMask& a, const PlacedMask& b) { return count_query(a, b); }

// The avx512 kernel: 8 rows a vector for rows of one chunk from masks of 1 or 2 words per
// row; 4 or 2 rows a vector for rows of 2..4 chunks from two masks both 2 or 4 words wide; a
// vector a row for the other rows of 2..8 chunks; the bmi2 code for the rest.
[[gnu::target(JOSTLE_AVX512)]] bool any_vector(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    if (!share_words(a, b, s)) return false;
    if (s.words == 1) {
        switch (stride_pair(s)) {
        case 5: return first_row_eight<1, 1>(s) < s.rows;
        case 6: return first_row_eight<1, 2>(s) < s.rows;
        case 9: return first_row_eight<2, 1>(s) < s.rows;
        case 10: return first_row_eight<2, 2>(s) < s.rows;
        default: return any_shared(s);
        }
    }
    if (const int packed = packed_stride(s); packed != 0) return packed == 2 ? any_packed<2>(s) : any_packed<4>(s);
    return s.words <= 8 ? any_avx512(s) : any_shared(s);
}
[[gnu::target(JOSTLE_AVX512)]] Offset first_vector(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    if (!share_words(a, b, s)) return kNone;
    int r = 0;
    if (s.words == 1) {
        switch (stride_pair(s)) {
        case 5: r = first_row_eight<1, 1>(s); break;
        case 6: r = first_row_eight<1, 2>(s); break;
        case 9: r = first_row_eight<2, 1>(s); break;
        case 10: r = first_row_eight<2, 2>(s); break;
        default: return first_shared(s);
        }
        return r < s.rows ? first_in_row<true>(s, r) : kNone;
    }
    if (const int packed = packed_stride(s); packed != 0) return packed == 2 ? first_packed<2>(s) : first_packed<4>(s);
    if (s.words > 8) return first_shared(s);
    r = first_row_avx512(s);
    return r < s.rows ? first_in_row<false>(s, r) : kNone;
}
[[gnu::target(JOSTLE_AVX512)]] int count_vector(const PlacedMask& a, const PlacedMask& b) {
    SharedWords s;
    if (!share_words(a, b, s)) return 0;
    if (s.words == 1) {
        switch (stride_pair(s)) {
        case 5: return count_eight<1, 1>(s);
        case 6: return count_eight<1, 2>(s);
        case 9: return count_eight<2, 1>(s);
        case 10: return count_eight<2, 2>(s);
        default: return count_in_rows(s);
        }
    }
    if (const int packed = packed_stride(s); packed != 0) return packed == 2 ? count_packed<2>(s) : count_packed<4>(s);
    return s.words <= 8 ? count_avx512(s) : count_in_rows(s);
}

bool cpu_has(MaskKernel k) {
    switch (k) {
    case MaskKernel::portable: return true;
    case MaskKernel::bmi2:
        return __builtin_cpu_supports("popcnt") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
    case MaskKernel::avx512:
        return cpu_has(MaskKernel::bmi2) && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
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

bool any_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
#ifdef JOSTLE_MASK_X86_KERNELS
    if (k == MaskKernel::avx512) return any_vector(a, b);
    if (k == MaskKernel::bmi2) return any_bmi2(a, b);
#endif
    (void)k;
    return any_portable(a, b);
}

Offset first_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
#ifdef JOSTLE_MASK_X86_KERNELS
    if (k == MaskKernel::avx512) return first_vector(a, b);
    if (k == MaskKernel::bmi2) return first_bmi2(a, b);
#endif
    (void)k;
    return first_portable(a, b);
}

int count_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
#ifdef JOSTLE_MASK_X86_KERNELS
    if (k == MaskKernel::avx512) return count_vector(a, b);
    if (k == MaskKernel::bmi2) return count_bmi2(a, b);
#endif
    (void)k;
    return count_portable(a, b);
}

// ---------------------------------------------------------------------------------------
// The integer MTD search, shared by every mask pair
// ---------------------------------------------------------------------------------------

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
    for (i64 m = 0; m * m <= best.r2; ++m) {
        for (int side = 0; side < (m == 0 ? 1 : 2); ++side) {
            const i64 dx = side == 0 ? m : -m;
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
        if (dir > 0) {
            at = first_query(moved, b);
        } else if (SharedWords s; share_words(moved, b, s)) {
            at = last_row_first_shared(s);
        }
        if (!at.found()) return false;
        // A's pixel there stays on B's pixels while B's column runs on in the scan direction.
        const int bx = static_cast<int>(std::max(ax, b.x) + at.col - b.x);
        const int by = static_cast<int>(std::max(ay, b.y) + at.row - b.y);
        int run = 1;
        while (b.m->get(bx, by + dir * run)) ++run;
        jump = run;
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

// Either winding is accepted; fewer than 3 or more than 16 points, or no area, is a miss.
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
// the pixel search there would run for ever or overflow, and a miss is a defined answer.
constexpr double kMaxRegionCoordinate = 1e9;

template <class S>
auto region_of(const S& shape) {
    auto r = raw_region_of(shape);
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
        int wj = 0;
        const bool hit = visit_region_words(*m, x + dx, y + dy, *r, box, dir < 0, [&](int j, int, u64) {
            wj = j;
            return true;
        });
        if (!hit) return false;
        if constexpr (R::kSolid) jump = solid_jump(dx, dy, dir, wj);
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
};

// Pushes past this length are outside the coordinate limits (|x|, |y| <= 1e5 plus a mask):
// there the answer is the bound below (a pure-axis push clearing the shape's bounds, at most
// two pixels long), without a search.
constexpr double kMaxSearchedPush = 1 << 20;

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
    return search_mtd(p, AxisPush{static_cast<i64>(bx), static_cast<i64>(by)});
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Mask vs mask (bit-packed)
// ---------------------------------------------------------------------------------------

namespace {

// The best kernel this CPU has, found once (a constant of the machine, not state).
MaskKernel best_kernel() {
    static const MaskKernel best = usable_kernel(MaskKernel::avx512);
    return best;
}

// A 0-wide or 0-high mask shares no pixel: share_words finds that without a test of its own.
bool overlaps_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return a.mask != nullptr && b.mask != nullptr && any_with(a, b, k);
}

std::optional<Pixel> first_overlap_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    if (a.mask == nullptr || b.mask == nullptr) return std::nullopt;
    const Offset at = first_with(a, b, k);
    if (!at.found()) return std::nullopt;
    // The shared rectangle's corner is (max x, max y); the pixel is inside both masks.
    return Pixel{static_cast<int>(std::max<i64>(a.x, b.x) + at.col), static_cast<int>(std::max<i64>(a.y, b.y) + at.row)};
}

int count_overlap_with(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    if (a.mask == nullptr || b.mask == nullptr) return 0;
    return count_with(a, b, k);
}

}  // namespace

bool overlaps(const PlacedMask& a, const PlacedMask& b) { return overlaps_with(a, b, best_kernel()); }
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b) {
    return first_overlap_with(a, b, best_kernel());
}
int count_overlap(const PlacedMask& a, const PlacedMask& b) { return count_overlap_with(a, b, best_kernel()); }

namespace detail {
MaskKernel best_mask_kernel() { return best_kernel(); }
bool overlaps(const PlacedMask& a, const PlacedMask& b, MaskKernel k) { return overlaps_with(a, b, usable_kernel(k)); }
std::optional<Pixel> first_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return first_overlap_with(a, b, usable_kernel(k));
}
int count_overlap(const PlacedMask& a, const PlacedMask& b, MaskKernel k) {
    return count_overlap_with(a, b, usable_kernel(k));
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
