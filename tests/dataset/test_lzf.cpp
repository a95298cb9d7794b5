// LZF decompression: streams assembled by hand from the format's two kinds of chunk, and PCL's
// own compressor (an independent implementation) on data with and without repeats.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <pcl/io/lzf.h>

#include "ladarsim/dataset/lzf.h"

using ladarsim::lzf_decompress;

namespace {

std::vector<unsigned char> bytes(std::initializer_list<int> values) {
    std::vector<unsigned char> out;
    for (int v : values) out.push_back(static_cast<unsigned char>(v));
    return out;
}

std::string decompressed(const std::vector<unsigned char>& stream, std::size_t capacity) {
    std::vector<unsigned char> out(capacity);
    const auto n = lzf_decompress(stream, out);
    if (!n) return "(corrupt)";
    return std::string(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(*n));
}

}  // namespace

TEST_CASE("hand-assembled chunks: literal runs and back references, overlapping ones repeating a run", "[lzf]") {
    // Literal run of 3 (control 2), then a back reference of length 3 + 2 = 5 (control 3 << 5)
    // reaching 0 + 1 bytes back: "abc" then five copies of the byte before, "ccccc".
    CHECK(decompressed(bytes({2, 'a', 'b', 'c', 3 << 5, 0}), 16) == "abcccccc");
    // Reaching 3 back repeats the whole "abc"; length 7 + 4 + 2 = 13 takes the extra length byte.
    CHECK(decompressed(bytes({2, 'a', 'b', 'c', 7 << 5, 4, 2}), 32) == "abc" + std::string("abcabcabcabca"));
    // A reference 257 bytes back puts 1 in the control byte's low bits: (1 << 8) + 0 + 1.
    std::vector<unsigned char> stream;
    std::string expected;
    for (int i = 0; i < 257; i += 32) {  // literal runs hold at most 32 bytes
        const int n = std::min(32, 257 - i);
        stream.push_back(static_cast<unsigned char>(n - 1));
        for (int k = 0; k < n; ++k) {
            const char c = static_cast<char>('A' + (i + k) % 26);
            stream.push_back(static_cast<unsigned char>(c));
            expected += c;
        }
    }
    stream.push_back((1 << 5) | 1);  // length 1 + 2 = 3
    stream.push_back(0);
    expected += expected.substr(0, 3);
    CHECK(decompressed(stream, 300) == expected);
}

TEST_CASE("corrupt streams and small outputs are refused, not read or written past", "[lzf]") {
    CHECK(decompressed(bytes({3 << 5, 0}), 16) == "(corrupt)");           // refers before the start
    CHECK(decompressed(bytes({4, 'a', 'b'}), 16) == "(corrupt)");         // literal run past the input
    CHECK(decompressed(bytes({0, 'a', 7 << 5}), 16) == "(corrupt)");      // no length byte
    CHECK(decompressed(bytes({0, 'a', 1 << 5}), 16) == "(corrupt)");      // no distance byte
    CHECK(decompressed(bytes({2, 'a', 'b', 'c'}), 2) == "(corrupt)");     // output too small
    CHECK(decompressed(bytes({0, 'a', 7 << 5, 200, 0}), 100) == "(corrupt)");
    CHECK(decompressed({}, 4).empty());
}

TEST_CASE("PCL's compressor: random bytes, runs and a sensor-like ramp all come back exactly", "[lzf]") {
    std::mt19937 rng(3);
    std::vector<std::vector<unsigned char>> inputs(3);
    for (int i = 0; i < 5000; ++i) {
        inputs[0].push_back(static_cast<unsigned char>(rng()));
        inputs[1].push_back(static_cast<unsigned char>(i / 700));
        inputs[2].push_back(static_cast<unsigned char>((i * 7) % 256 == 0 ? rng() : i % 13));
    }
    for (const auto& input : inputs) {
        std::vector<unsigned char> compressed(input.size() * 2 + 16);
        const unsigned n = pcl::lzfCompress(input.data(), static_cast<unsigned>(input.size()), compressed.data(),
                                            static_cast<unsigned>(compressed.size()));
        REQUIRE(n > 0);
        compressed.resize(n);
        std::vector<unsigned char> out(input.size());
        CHECK(lzf_decompress(compressed, out) == input.size());
        CHECK(out == input);
    }
}
