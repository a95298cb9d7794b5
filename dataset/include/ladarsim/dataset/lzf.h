#pragma once
// LZF decompression (Marc Lehmann's liblzf), the compression of PCD's DATA binary_compressed.
#include <cstddef>
#include <optional>
#include <span>

namespace ladarsim {

/// Decompresses the LZF stream `in` into `out`. The stream is a sequence of chunks, each led by a
/// control byte c: c < 32 copies the next c + 1 bytes as they are; otherwise the top three bits
/// are a length L (7: add the next byte) and the chunk copies L + 2 bytes from
/// ((c & 31) << 8) + next byte + 1 bytes back in the output (overlapping copies repeat a run).
/// Returns the bytes written, or nothing when the stream is corrupt (a chunk reaching beyond the
/// input, or back before the start of the output) or would overflow `out`.
std::optional<std::size_t> lzf_decompress(std::span<const unsigned char> in, std::span<unsigned char> out);

}  // namespace ladarsim
