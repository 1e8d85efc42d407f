// png_fast.cpp: jostle's fast PNG encoder (png_fast.h). The PNG format (RFC 2083) around a
// deflate stream (RFC 1951) written here: per strip of rows, the filtered bytes are split into
// literals and matches by a greedy LZ77 (a match at the previous pixel is tried first, then one
// hash-table probe; no lazy matching, no chains: zlib's level 1 does a little more), then coded
// in one dynamic Huffman block (or stored, when that is smaller). Strips are independent
// (each ends on a byte boundary with an empty stored block, as zlib's Z_SYNC_FLUSH does), so
// they can be compressed on several threads and concatenated; their Adler-32s are combined.
// zlib provides the CRC-32 and adler32_combine; the Adler-32 of the rows is computed here.
#include "png_fast.h"

#include <zlib.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <memory>
#include <thread>

#include "jostle/core/error.h"

namespace jostle::detail {

namespace {

// ---------------------------------------------------------------------------------------
// Filtering (PNG filter types 0..4, 4 bytes per pixel)
// ---------------------------------------------------------------------------------------

constexpr std::size_t kBpp = 4;

std::uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(a);
    return static_cast<std::uint8_t>(pb <= pc ? b : c);
}

// One row filtered with `type` into out[0..n); `above` is null for the first row (zeros).
void filter_row(int type, const std::uint8_t* row, const std::uint8_t* above, std::size_t n, std::uint8_t* out) {
    switch (type) {
        case 0:
            std::memcpy(out, row, n);
            return;
        case 1:
            for (std::size_t i = 0; i < kBpp; ++i) out[i] = row[i];
            for (std::size_t i = kBpp; i < n; ++i) out[i] = static_cast<std::uint8_t>(row[i] - row[i - kBpp]);
            return;
        case 2:
            if (above == nullptr) { std::memcpy(out, row, n); return; }
            for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<std::uint8_t>(row[i] - above[i]);
            return;
        case 3:
            for (std::size_t i = 0; i < n; ++i) {
                const int left = i >= kBpp ? row[i - kBpp] : 0;
                const int up = above != nullptr ? above[i] : 0;
                out[i] = static_cast<std::uint8_t>(row[i] - ((left + up) >> 1));
            }
            return;
        default:
            for (std::size_t i = 0; i < n; ++i) {
                const int left = i >= kBpp ? row[i - kBpp] : 0;
                const int up = above != nullptr ? above[i] : 0;
                const int corner = (i >= kBpp && above != nullptr) ? above[i - kBpp] : 0;
                out[i] = static_cast<std::uint8_t>(row[i] - paeth(left, up, corner));
            }
            return;
    }
}

// The sum of the filtered bytes as signed magnitudes: libpng's heuristic for "looks smallest".
std::uint64_t row_cost(const std::uint8_t* f, std::size_t n) {
    std::uint64_t sum = 0;
    for (std::size_t i = 0; i < n; ++i) sum += f[i] < 128 ? f[i] : 256u - f[i];
    return sum;
}

// Filters rows [y0, y1) into `out` (1 + row_bytes per row: the filter type, then the bytes).
void filter_rows(const PixelRows& image, PngFilter filter, int y0, int y1, std::uint8_t* out, std::vector<std::uint8_t>& scratch) {
    const std::size_t n = static_cast<std::size_t>(image.width) * kBpp;
    for (int y = y0; y < y1; ++y) {
        const std::uint8_t* row = image.row(y);
        const std::uint8_t* above = y > 0 ? image.row(y - 1) : nullptr;
        std::uint8_t* dst = out + static_cast<std::size_t>(y - y0) * (n + 1);
        int type = 2;
        switch (filter) {
            case PngFilter::none: type = 0; break;
            case PngFilter::sub: type = 1; break;
            case PngFilter::up: type = 2; break;
            case PngFilter::paeth: type = 4; break;
            case PngFilter::adaptive:
            case PngFilter::libpng_default: {
                // Each of the five filters into scratch; keep the one with the smallest cost.
                scratch.resize(5 * n);
                std::uint64_t best = UINT64_MAX;
                for (int t = 0; t < 5; ++t) {
                    filter_row(t, row, above, n, scratch.data() + static_cast<std::size_t>(t) * n);
                    const std::uint64_t cost = row_cost(scratch.data() + static_cast<std::size_t>(t) * n, n);
                    if (cost < best) { best = cost; type = t; }
                }
                dst[0] = static_cast<std::uint8_t>(type);
                std::memcpy(dst + 1, scratch.data() + static_cast<std::size_t>(type) * n, n);
                continue;
            }
        }
        dst[0] = static_cast<std::uint8_t>(type);
        filter_row(type, row, above, n, dst + 1);
    }
}

// ---------------------------------------------------------------------------------------
// Deflate tables (RFC 1951, 3.2.5)
// ---------------------------------------------------------------------------------------

constexpr int kLitLenSymbols = 286;
constexpr int kDistSymbols = 30;
constexpr int kMinMatch = 4;
constexpr int kMaxMatch = 258;
constexpr std::uint32_t kWindow = 32768;

constexpr std::array<std::uint16_t, 29> kLenBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                    31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLenExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                    2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<std::uint16_t, 30> kDistBase = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                                     193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<std::uint8_t, 30> kDistExtra = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6,
                                                     6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
// The order in which the code-length code's lengths are sent.
constexpr std::array<std::uint8_t, 19> kClOrder = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

// Length 3..258 -> length code index 0..28.
constexpr std::array<std::uint8_t, 259> kLenCode = [] {
    std::array<std::uint8_t, 259> t{};
    for (int c = 0; c < 29; ++c) {
        const int last = c + 1 < 29 ? kLenBase[static_cast<std::size_t>(c) + 1] - 1 : 258;
        for (int len = kLenBase[static_cast<std::size_t>(c)]; len <= last && len <= 258; ++len) t[static_cast<std::size_t>(len)] = static_cast<std::uint8_t>(c);
    }
    t[258] = 28;
    return t;
}();

// Distance 1..32768 -> distance code 0..29.
inline int dist_code(std::uint32_t dist) {
    const std::uint32_t x = dist - 1;
    if (x < 4) return static_cast<int>(x);
    const int top = std::bit_width(x) - 1;  // x >= 4: top >= 2
    return 2 * top + static_cast<int>((x >> (top - 1)) & 1u);
}

// ---------------------------------------------------------------------------------------
// Huffman codes
// ---------------------------------------------------------------------------------------

// Code lengths (at most `limit` bits) for `n` symbols with frequencies `freq`; unused symbols get
// 0. At least two symbols always get a code, so every code is complete (some decoders reject
// a code of one symbol).
void huffman_lengths(const std::uint32_t* freq_in, int n, int limit, std::uint8_t* lengths) {
    std::array<std::uint32_t, 288> freq{};
    std::copy_n(freq_in, n, freq.begin());
    int used = 0;
    for (int i = 0; i < n; ++i) used += freq[static_cast<std::size_t>(i)] != 0;
    for (int i = 0; used < 2 && i < n; ++i) {
        if (freq[static_cast<std::size_t>(i)] == 0) { freq[static_cast<std::size_t>(i)] = 1; ++used; }
    }
    // Leaves sorted by (frequency, symbol): deterministic.
    std::array<std::pair<std::uint32_t, int>, 288> leaves{};
    int m = 0;
    for (int i = 0; i < n; ++i) {
        lengths[i] = 0;
        if (freq[static_cast<std::size_t>(i)] != 0) leaves[static_cast<std::size_t>(m++)] = {freq[static_cast<std::size_t>(i)], i};
    }
    std::sort(leaves.begin(), leaves.begin() + m);
    // Two-queue Huffman construction: leaves in order, internal nodes in order of creation.
    std::array<std::uint64_t, 288> weight{};  // internal node weights
    std::array<int, 2 * 288> parent{};        // leaves 0..m-1, internal nodes m..2m-2
    int leaf = 0, inner = 0, made = 0;
    auto take = [&]() -> int {
        if (leaf < m && (inner >= made || leaves[static_cast<std::size_t>(leaf)].first <= weight[static_cast<std::size_t>(inner)])) {
            return leaf++;
        }
        return m + inner++;
    };
    auto weight_of = [&](int node) -> std::uint64_t {
        return node < m ? leaves[static_cast<std::size_t>(node)].first : weight[static_cast<std::size_t>(node - m)];
    };
    while (made < m - 1) {
        const int a = take();
        const int b = take();
        weight[static_cast<std::size_t>(made)] = weight_of(a) + weight_of(b);
        parent[static_cast<std::size_t>(a)] = m + made;
        parent[static_cast<std::size_t>(b)] = m + made;
        ++made;
    }
    // Depths: the root (the last internal node) is 0; parents come after their children.
    std::array<int, 2 * 288> depth{};
    const int root = m + made - 1;
    depth[static_cast<std::size_t>(root)] = 0;
    for (int node = root - 1; node >= 0; --node) depth[static_cast<std::size_t>(node)] = depth[static_cast<std::size_t>(parent[static_cast<std::size_t>(node)])] + 1;
    std::array<int, 2 * 288> count{};  // leaves per depth
    int deepest = 0;
    for (int i = 0; i < m; ++i) {
        ++count[static_cast<std::size_t>(depth[static_cast<std::size_t>(i)])];
        deepest = std::max(deepest, depth[static_cast<std::size_t>(i)]);
    }
    if (deepest > limit) {
        // Too deep: move the overlong leaves up to `limit`, then split shorter leaves until
        // the code is complete again (Kraft sum exactly 1), as miniz does.
        for (int d = limit + 1; d <= deepest; ++d) {
            count[static_cast<std::size_t>(limit)] += count[static_cast<std::size_t>(d)];
            count[static_cast<std::size_t>(d)] = 0;
        }
        std::uint32_t total = 0;
        for (int d = limit; d > 0; --d) total += static_cast<std::uint32_t>(count[static_cast<std::size_t>(d)]) << (limit - d);
        while (total != (1u << limit)) {
            --count[static_cast<std::size_t>(limit)];
            for (int d = limit - 1; d > 0; --d) {
                if (count[static_cast<std::size_t>(d)] != 0) {
                    --count[static_cast<std::size_t>(d)];
                    count[static_cast<std::size_t>(d) + 1] += 2;
                    break;
                }
            }
            --total;
        }
        deepest = limit;
    }
    // The rarest symbols get the longest codes.
    int next = 0;
    for (int d = deepest; d >= 1; --d) {
        for (int k = 0; k < count[static_cast<std::size_t>(d)]; ++k) lengths[leaves[static_cast<std::size_t>(next++)].second] = static_cast<std::uint8_t>(d);
    }
}

// Canonical codes for `lengths`, bit-reversed for deflate's LSB-first bit order.
void canonical_codes(const std::uint8_t* lengths, int n, std::uint16_t* codes) {
    std::array<std::uint16_t, 16> count{};
    for (int i = 0; i < n; ++i) ++count[lengths[i]];
    count[0] = 0;
    std::array<std::uint16_t, 16> next{};
    std::uint16_t code = 0;
    for (int bits = 1; bits < 16; ++bits) {
        code = static_cast<std::uint16_t>((code + count[static_cast<std::size_t>(bits) - 1]) << 1);
        next[static_cast<std::size_t>(bits)] = code;
    }
    for (int i = 0; i < n; ++i) {
        const int len = lengths[i];
        if (len == 0) { codes[i] = 0; continue; }
        const std::uint16_t c = next[static_cast<std::size_t>(len)]++;
        std::uint16_t r = 0;
        for (int b = 0; b < len; ++b) r = static_cast<std::uint16_t>(r | (((c >> b) & 1u) << (len - 1 - b)));
        codes[i] = r;
    }
}

// ---------------------------------------------------------------------------------------
// Bits out
// ---------------------------------------------------------------------------------------

class BitWriter {
public:
    explicit BitWriter(std::uint8_t* out) : out_(out), start_(out) {}
    // Up to 56 bits (no bits set past `count`). Every put stores the whole buffer (its bits
    // past count_ are zero) and keeps only the last partial byte: no branch on whether a
    // word is full, which the codes' varying lengths make unpredictable. The output needs 8
    // bytes of slack.
    void put(std::uint64_t bits, int count) {
        buffer_ |= bits << count_;
        JOSTLE_DEBUG_ASSERT(count >= 0 && count <= 56, "BitWriter::put: at most 56 bits a put");
        count_ += count;  // <= 7 + 56: whole <= 7, so the shift below is < 64
        std::memcpy(out_, &buffer_, 8);  // little-endian (x86, ARM): deflate's byte order
        const int whole = count_ >> 3;
        out_ += whole;
        buffer_ >>= 8 * whole;
        count_ &= 7;
    }
    // Pads to a byte boundary with zero bits and writes out what is buffered.
    void align() {
        while (count_ > 0) {
            *out_++ = static_cast<std::uint8_t>(buffer_);
            buffer_ >>= 8;
            count_ = std::max(count_ - 8, 0);
        }
        buffer_ = 0;
    }
    void bytes(const std::uint8_t* data, std::size_t n) {
        std::memcpy(out_, data, n);
        out_ += n;
    }
    std::size_t size() const { return static_cast<std::size_t>(out_ - start_); }

private:
    std::uint8_t* out_;
    std::uint8_t* start_;
    std::uint64_t buffer_ = 0;
    int count_ = 0;
};

static_assert(std::endian::native == std::endian::little, "BitWriter writes words in little-endian order");

// ---------------------------------------------------------------------------------------
// LZ77
// ---------------------------------------------------------------------------------------

// A run of literals followed by a match (len 0: none, at the end of the strip).
struct Sequence {
    std::uint32_t literals;
    std::uint16_t length;
    std::uint16_t dist;  // 1..32768 stored as dist - 1
};

inline std::uint32_t load32(const std::uint8_t* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}
inline std::uint64_t load64(const std::uint8_t* p) {
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

constexpr int kHashBits = 14;

// How many bytes at a and b agree, up to `limit`.
inline std::size_t common_length(const std::uint8_t* a, const std::uint8_t* b, std::size_t limit) {
    std::size_t n = 0;
#if defined(__SSE2__)
    // Most matches end within 16 bytes: one comparison decides them (fewer mispredicted
    // loop exits than 8 bytes at a time).
    while (n + 16 <= limit) {
        const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + n));
        const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + n));
        const auto differ = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_cmpeq_epi8(x, y))) ^ 0xffffu;
        if (differ != 0) return n + static_cast<std::size_t>(std::countr_zero(differ));
        n += 16;
    }
#endif
    while (n + 8 <= limit) {
        const std::uint64_t x = load64(a + n) ^ load64(b + n);
        if (x != 0) return n + static_cast<std::size_t>(std::countr_zero(x) >> 3);
        n += 8;
    }
    while (n < limit && a[n] == b[n]) ++n;
    return n;
}

struct Tokens {
    std::vector<Sequence> sequences;
    std::array<std::uint32_t, kLitLenSymbols> litlen{};
    std::array<std::uint32_t, kDistSymbols> dist{};
};

// Greedy parse of data[0..n).
void tokenize(const std::uint8_t* data, std::size_t n, Tokens& t) {
    std::vector<std::uint32_t> table(std::size_t{1} << kHashBits, 0);
    std::size_t p = 0;
    std::size_t literal_start = 0;
    std::size_t misses = 0;
    const auto emit = [&](std::size_t at, std::size_t length, std::size_t distance) {
        for (std::size_t i = literal_start; i < at; ++i) ++t.litlen[data[i]];
        ++t.litlen[257u + kLenCode[length]];
        ++t.dist[static_cast<std::size_t>(dist_code(static_cast<std::uint32_t>(distance)))];
        t.sequences.push_back({static_cast<std::uint32_t>(at - literal_start), static_cast<std::uint16_t>(length),
                               static_cast<std::uint16_t>(distance - 1)});
    };
    while (p + kMinMatch <= n) {
        const std::uint32_t v = load32(data + p);
        // The pixel before first (runs of one colour, rows of zeros), else one hash probe,
        // which then remembers this position. Both are looked up at every position and the
        // candidate is picked afterwards (the table keeps its entry when the run test wins):
        // fewer branches whose outcome is as good as random.
        const bool run = p >= kBpp && load32(data + p - kBpp) == v;
        const std::uint32_t h = (v * 2654435761u) >> (32 - kHashBits);
        const std::size_t c = table[h];
        table[h] = run ? static_cast<std::uint32_t>(c) : static_cast<std::uint32_t>(p);
        const bool probed = c < p && p - c <= kWindow && load32(data + c) == v;
        const std::size_t candidate = run ? p - kBpp : probed ? c : SIZE_MAX;
        if (candidate == SIZE_MAX) {
            // No match: step faster through data that keeps missing (noise), as LZ4 does.
            p += 1 + (misses++ >> 4);
            continue;
        }
        misses = 0;
        const std::size_t limit = std::min<std::size_t>(kMaxMatch, n - p);
        const std::size_t length = kMinMatch + common_length(data + candidate + kMinMatch, data + p + kMinMatch, limit - kMinMatch);
        emit(p, length, p - candidate);
        p += length;
        literal_start = p;
    }
    for (std::size_t i = literal_start; i < n; ++i) ++t.litlen[data[i]];
    t.sequences.push_back({static_cast<std::uint32_t>(n - literal_start), 0, 0});
}

// ---------------------------------------------------------------------------------------
// Blocks
// ---------------------------------------------------------------------------------------

struct ClItem {
    std::uint8_t symbol;  // 0..18
    std::uint8_t extra;   // the repeat count's extra bits for 16, 17, 18
};

// The run-length coding of the code lengths (RFC 1951, 3.2.7).
std::vector<ClItem> rle_lengths(const std::uint8_t* lengths, int n) {
    std::vector<ClItem> items;
    int i = 0;
    while (i < n) {
        const std::uint8_t cur = lengths[i];
        int run = 1;
        while (i + run < n && lengths[i + run] == cur) ++run;
        i += run;
        if (cur == 0) {
            while (run >= 11) {
                const int r = std::min(run, 138);
                items.push_back({18, static_cast<std::uint8_t>(r - 11)});
                run -= r;
            }
            if (run >= 3) {
                items.push_back({17, static_cast<std::uint8_t>(run - 3)});
                run = 0;
            }
        } else {
            items.push_back({cur, 0});
            --run;
            while (run >= 3) {
                const int r = std::min(run, 6);
                items.push_back({16, static_cast<std::uint8_t>(r - 3)});
                run -= r;
            }
        }
        for (; run > 0; --run) items.push_back({cur, 0});
    }
    return items;
}

constexpr std::array<int, 19> kClExtraBits = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3, 7};

// Writes data[0..n) as stored blocks; `final` marks the last one.
void write_stored(BitWriter& out, const std::uint8_t* data, std::size_t n, bool final) {
    do {
        const std::size_t piece = std::min<std::size_t>(n, 65535);
        n -= piece;
        out.put(final && n == 0 ? 1u : 0u, 1);
        out.put(0, 2);
        out.align();
        const std::uint8_t header[4] = {static_cast<std::uint8_t>(piece), static_cast<std::uint8_t>(piece >> 8),
                                        static_cast<std::uint8_t>(~piece), static_cast<std::uint8_t>(~piece >> 8)};
        out.bytes(header, 4);
        out.bytes(data, piece);
        data += piece;
    } while (n > 0);
}

// Compresses one strip's filtered bytes as one block (dynamic Huffman, or stored when that
// is no larger), ending on a byte boundary: the final strip's block is marked final, the
// others are followed by an empty stored block.
void compress_strip(const std::uint8_t* data, std::size_t n, bool final, BitWriter& out) {
    Tokens t;
    t.sequences.reserve(n / 16 + 16);
    tokenize(data, n, t);
    t.litlen[256] = 1;

    std::array<std::uint8_t, kLitLenSymbols + kDistSymbols> lengths{};
    std::uint8_t* lit_len = lengths.data();
    std::uint8_t* dist_len = lengths.data() + kLitLenSymbols;
    huffman_lengths(t.litlen.data(), kLitLenSymbols, 15, lit_len);
    huffman_lengths(t.dist.data(), kDistSymbols, 15, dist_len);
    int hlit = kLitLenSymbols;
    while (hlit > 257 && lit_len[hlit - 1] == 0) --hlit;
    int hdist = kDistSymbols;
    while (hdist > 1 && dist_len[hdist - 1] == 0) --hdist;
    // The code lengths, litlen then dist, as one sequence (allowed to run across the two).
    std::array<std::uint8_t, kLitLenSymbols + kDistSymbols> sent{};
    std::copy_n(lit_len, hlit, sent.begin());
    std::copy_n(dist_len, hdist, sent.begin() + hlit);
    const std::vector<ClItem> items = rle_lengths(sent.data(), hlit + hdist);
    std::array<std::uint32_t, 19> cl_freq{};
    for (const ClItem& it : items) ++cl_freq[it.symbol];
    std::array<std::uint8_t, 19> cl_len{};
    huffman_lengths(cl_freq.data(), 19, 7, cl_len.data());
    int hclen = 19;
    while (hclen > 4 && cl_len[kClOrder[static_cast<std::size_t>(hclen) - 1]] == 0) --hclen;

    // Sizes in bits: dynamic against stored.
    std::uint64_t bits = 3 + 5 + 5 + 4 + 3 * static_cast<std::uint64_t>(hclen);
    for (const ClItem& it : items) bits += cl_len[it.symbol] + static_cast<std::uint64_t>(kClExtraBits[it.symbol]);
    for (int s = 0; s < kLitLenSymbols; ++s) {
        bits += std::uint64_t{t.litlen[static_cast<std::size_t>(s)]} *
                (lit_len[s] + (s >= 257 ? kLenExtra[static_cast<std::size_t>(s) - 257] : 0u));
    }
    for (int s = 0; s < kDistSymbols; ++s) {
        bits += std::uint64_t{t.dist[static_cast<std::size_t>(s)]} * (dist_len[s] + std::uint64_t{kDistExtra[static_cast<std::size_t>(s)]});
    }
    const std::uint64_t stored_bits = 8 * (static_cast<std::uint64_t>(n) + 5 * (n / 65535 + 1));
    if (bits >= stored_bits) {
        write_stored(out, data, n, final);
        if (!final) write_stored(out, data, 0, false);
        return;
    }

    std::array<std::uint16_t, kLitLenSymbols> lit_code{};
    std::array<std::uint16_t, kDistSymbols> dist_code_bits{};
    std::array<std::uint16_t, 19> cl_code{};
    canonical_codes(lit_len, kLitLenSymbols, lit_code.data());
    canonical_codes(dist_len, kDistSymbols, dist_code_bits.data());
    canonical_codes(cl_len.data(), 19, cl_code.data());

    out.put(final ? 1u : 0u, 1);
    out.put(2, 2);  // dynamic Huffman
    out.put(static_cast<std::uint32_t>(hlit - 257), 5);
    out.put(static_cast<std::uint32_t>(hdist - 1), 5);
    out.put(static_cast<std::uint32_t>(hclen - 4), 4);
    for (int i = 0; i < hclen; ++i) out.put(cl_len[kClOrder[static_cast<std::size_t>(i)]], 3);
    for (const ClItem& it : items) {
        out.put(cl_code[it.symbol], cl_len[it.symbol]);
        if (kClExtraBits[it.symbol] != 0) out.put(it.extra, kClExtraBits[it.symbol]);
    }
    // Each symbol's code packed with its bit count (code << 8 | count), and for the lengths
    // with the extra bits too: one table load a symbol and one put per three literals or
    // per length and distance (a put carries up to 56 bits).
    std::array<std::uint32_t, 256> literal{};
    for (int b = 0; b < 256; ++b) literal[static_cast<std::size_t>(b)] = (std::uint32_t{lit_code[static_cast<std::size_t>(b)]} << 8) | lit_len[b];
    std::array<std::uint32_t, kMaxMatch + 1> length_bits{};  // <= 15 + 5 bits
    for (int len = 3; len <= kMaxMatch; ++len) {
        const std::size_t lc = kLenCode[static_cast<std::size_t>(len)];
        const std::uint32_t code = lit_code[257 + lc] | (static_cast<std::uint32_t>(len - kLenBase[lc]) << lit_len[257 + lc]);
        length_bits[static_cast<std::size_t>(len)] = (code << 8) | (lit_len[257 + lc] + kLenExtra[lc]);
    }
    // The symbols go through a local copy of the writer: its state stays in registers (the
    // writer's byte stores could alias `out`, so the compiler would keep `out` in memory).
    BitWriter w = out;
    const std::uint8_t* p = data;
    for (const Sequence& s : t.sequences) {
        std::uint32_t i = 0;
        for (; i + 3 <= s.literals; i += 3, p += 3) {  // three literals: <= 45 bits
            const std::uint32_t a = literal[p[0]], b = literal[p[1]], c = literal[p[2]];
            const std::uint32_t ab = (a & 0xffu) + (b & 0xffu);
            w.put((a >> 8) | (std::uint64_t{b >> 8} << (a & 0xffu)) | (std::uint64_t{c >> 8} << ab),
                  static_cast<int>(ab + (c & 0xffu)));
        }
        for (; i < s.literals; ++i) {
            const std::uint32_t l = literal[*p++];
            w.put(l >> 8, static_cast<int>(l & 0xffu));
        }
        if (s.length == 0) continue;
        // The length and the distance together: <= 15 + 5 + 15 + 13 bits.
        const std::uint32_t l = length_bits[s.length];
        const std::uint32_t distance = std::uint32_t{s.dist} + 1;
        const auto dc = static_cast<std::size_t>(dist_code(distance));
        const std::uint64_t d = dist_code_bits[dc] | ((distance - kDistBase[dc]) << dist_len[dc]);
        w.put((l >> 8) | (d << (l & 0xffu)), static_cast<int>((l & 0xffu) + dist_len[dc] + kDistExtra[dc]));
        p += s.length;
    }
    out = w;
    out.put(lit_code[256], lit_len[256]);
    if (!final) {
        // An empty stored block: the strip ends on a byte boundary (zlib's sync flush).
        out.put(0, 3);
        out.align();
        const std::uint8_t empty[4] = {0, 0, 0xff, 0xff};
        out.bytes(empty, 4);
    } else {
        out.align();
    }
}

// ---------------------------------------------------------------------------------------
// The PNG file
// ---------------------------------------------------------------------------------------

void put32be(std::vector<std::uint8_t>& out, std::uint32_t v) {
    const std::uint8_t b[4] = {static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8),
                               static_cast<std::uint8_t>(v)};
    out.insert(out.end(), b, b + 4);
}

// Appends a chunk whose data is already in `out` from `data_at` (after 8 bytes reserved for
// its length and type): fills in the length and type, then appends the CRC.
void close_chunk(std::vector<std::uint8_t>& out, std::size_t data_at, const char* type) {
    const auto length = static_cast<std::uint32_t>(out.size() - data_at);
    std::uint8_t* head = out.data() + data_at - 8;
    head[0] = static_cast<std::uint8_t>(length >> 24);
    head[1] = static_cast<std::uint8_t>(length >> 16);
    head[2] = static_cast<std::uint8_t>(length >> 8);
    head[3] = static_cast<std::uint8_t>(length);
    std::memcpy(head + 4, type, 4);
    const uLong crc = crc32_z(crc32_z(0, nullptr, 0), head + 4, length + 4u);
    put32be(out, static_cast<std::uint32_t>(crc));
}

// Rows per strip: about 256 KiB of pixels, the same for every image of this width.
int strip_rows(int width) { return std::max(1, (256 * 1024) / (width * static_cast<int>(kBpp) + 1)); }

}  // namespace

std::vector<std::uint8_t> encode_png_fast(const PixelRows& image, PngFilter filter, int threads) {
    const std::size_t row_bytes = static_cast<std::size_t>(image.width) * kBpp;
    const int rows_per_strip = strip_rows(image.width);
    const int strips = (image.height + rows_per_strip - 1) / rows_per_strip;

    // Each strip's compressed bytes and the Adler-32 of its filtered bytes.
    struct Strip {
        std::unique_ptr<std::uint8_t[]> bytes;
        std::size_t size = 0;
        uLong adler = 1;
        std::size_t raw = 0;
    };
    std::vector<Strip> done(static_cast<std::size_t>(strips));
    std::atomic<int> next{0};
    const auto work = [&] {
        std::vector<std::uint8_t> filtered;
        std::vector<std::uint8_t> scratch;
        for (int s = next++; s < strips; s = next++) {
            const int y0 = s * rows_per_strip;
            const int y1 = std::min(image.height, y0 + rows_per_strip);
            const std::size_t n = static_cast<std::size_t>(y1 - y0) * (row_bytes + 1);
            filtered.resize(n);
            filter_rows(image, filter, y0, y1, filtered.data(), scratch);
            Strip& strip = done[static_cast<std::size_t>(s)];
            // Dynamic blocks are only written when smaller than stored ones; the slack covers
            // the block headers, the closing empty stored block and the writer's 8-byte stores.
            strip.bytes.reset(new std::uint8_t[n + n / 65535 * 5 + 1024]);
            BitWriter out(strip.bytes.get());
            compress_strip(filtered.data(), n, s + 1 == strips, out);
            strip.size = out.size();
            strip.raw = n;
            strip.adler = adler32(1, filtered.data(), n);
        }
    };
    const int helpers = std::clamp(threads, 1, strips) - 1;
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(helpers));
    for (int i = 0; i < helpers; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();

    std::size_t total = 0;
    for (const Strip& s : done) total += s.size;
    // The signature, then 8 bytes for IHDR's length and type (close_chunk fills them in).
    std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 0, 0, 0, 0, 0};
    out.reserve(total + 128);
    std::size_t at = out.size();
    put32be(out, static_cast<std::uint32_t>(image.width));
    put32be(out, static_cast<std::uint32_t>(image.height));
    const std::uint8_t ihdr_rest[5] = {8, 6, 0, 0, 0};  // 8 bits, RGBA, deflate, adaptive filters, not interlaced
    out.insert(out.end(), ihdr_rest, ihdr_rest + 5);
    close_chunk(out, at, "IHDR");

    out.resize(out.size() + 8);
    at = out.size();
    out.push_back(0x78);  // zlib: deflate, 32 KiB window
    out.push_back(0x01);  // no dictionary, "fastest" level; 0x7801 % 31 == 0
    uLong adler = done.front().adler;
    for (std::size_t i = 0; i < done.size(); ++i) {
        out.insert(out.end(), done[i].bytes.get(), done[i].bytes.get() + done[i].size);
        if (i > 0) adler = adler32_combine(adler, done[i].adler, static_cast<z_off_t>(done[i].raw));
    }
    put32be(out, static_cast<std::uint32_t>(adler));
    JOSTLE_ASSERT(out.size() - at <= 0x7fffffffu, "encode_png: IDAT larger than a PNG chunk can be");
    close_chunk(out, at, "IDAT");

    out.resize(out.size() + 8);
    close_chunk(out, out.size(), "IEND");
    return out;
}

// Adler-32, 16 bytes a step. Over a run of k 16-byte chunks starting from (s1, s2):
//   s1' = s1 + (sum of the bytes)
//   s2' = s2 + 16 k s1 + sum over chunks of (16 * s1 before the chunk, counted from the run's
//         start) + sum of (16 - i) * byte i of each chunk
// all kept in 32-bit lanes, which cannot overflow within kMaxRun bytes (zlib's NMAX bound),
// then reduced mod 65521. The result is zlib's, bit for bit (png_io_test checks it).
std::uint32_t adler32(std::uint32_t adler, const std::uint8_t* data, std::size_t n) {
    constexpr std::uint32_t kBase = 65521;
    constexpr std::size_t kMaxRun = 5552 / 16 * 16;  // NMAX, whole chunks
    std::uint32_t s1 = adler & 0xffffu;
    std::uint32_t s2 = adler >> 16;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    const __m128i weights_lo = _mm_setr_epi16(16, 15, 14, 13, 12, 11, 10, 9);
    const __m128i weights_hi = _mm_setr_epi16(8, 7, 6, 5, 4, 3, 2, 1);
    while (n >= 16) {
        const std::size_t run = std::min(n, kMaxRun) / 16 * 16;
        __m128i sums = zero;      // byte sums, in the low halves of two 64-bit lanes
        __m128i prefix = zero;    // sums before each chunk, added up
        __m128i weighted = zero;  // (16 - i) * byte i
        for (std::size_t k = 0; k < run; k += 16) {
            const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(data + k));
            prefix = _mm_add_epi32(prefix, sums);
            sums = _mm_add_epi32(sums, _mm_sad_epu8(bytes, zero));
            weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpacklo_epi8(bytes, zero), weights_lo));
            weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpackhi_epi8(bytes, zero), weights_hi));
        }
        const auto lanes = [](__m128i v) {
            alignas(16) std::uint32_t x[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(x), v);
            return x[0] + x[1] + x[2] + x[3];
        };
        const std::uint32_t chunks = static_cast<std::uint32_t>(run / 16);
        s2 += 16 * chunks * s1 + 16 * lanes(prefix) + lanes(weighted);
        s1 += lanes(sums);
        s1 %= kBase;
        s2 %= kBase;
        data += run;
        n -= run;
    }
#endif
    while (n > 0) {
        const std::size_t run = std::min(n, kMaxRun);
        for (std::size_t k = 0; k < run; ++k) {
            s1 += data[k];
            s2 += s1;
        }
        s1 %= kBase;
        s2 %= kBase;
        data += run;
        n -= run;
    }
    return (s2 << 16) | s1;
}

}  // namespace jostle::detail
