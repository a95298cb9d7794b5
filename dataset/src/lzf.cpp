#include "ladarsim/dataset/lzf.h"

namespace ladarsim {

std::optional<std::size_t> lzf_decompress(std::span<const unsigned char> in, std::span<unsigned char> out) {
    std::size_t ip = 0, op = 0;
    while (ip < in.size()) {
        const unsigned ctrl = in[ip++];
        if (ctrl < 32) {
            const std::size_t run = ctrl + 1;
            if (run > in.size() - ip || run > out.size() - op) return std::nullopt;
            for (std::size_t k = 0; k < run; ++k) out[op++] = in[ip++];
            continue;
        }
        std::size_t length = ctrl >> 5;
        if (length == 7) {
            if (ip >= in.size()) return std::nullopt;
            length += in[ip++];
        }
        if (ip >= in.size()) return std::nullopt;
        const std::size_t back = ((ctrl & 31u) << 8) + in[ip++] + 1;
        length += 2;
        if (back > op || length > out.size() - op) return std::nullopt;
        // Byte by byte: the source may overlap what this chunk writes.
        for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - back];
    }
    return op;
}

}  // namespace ladarsim
