#include "chunk_filters.hpp"

#include <zlib.h>

#include <stdexcept>

namespace luxtrace::hdf5 {

void shuffle_bytes(std::span<const unsigned char> in, std::size_t element_size, unsigned char* out) {
    const std::size_t n = element_size > 1 ? in.size() / element_size : 0;
    for (std::size_t k = 0; k < element_size && n > 0; ++k)
        for (std::size_t i = 0; i < n; ++i) out[k * n + i] = in[i * element_size + k];
    for (std::size_t b = n * element_size; b < in.size(); ++b) out[b] = in[b];
}

std::uint32_t fletcher32(std::span<const unsigned char> bytes) {
    std::uint32_t sum1 = 0, sum2 = 0;
    const unsigned char* p = bytes.data();
    std::size_t words = bytes.size() / 2;
    while (words > 0) {
        // 360 words keep both sums below 2^32 before they are folded.
        std::size_t run = words > 360 ? 360 : words;
        words -= run;
        for (; run > 0; --run, p += 2) {
            sum1 += (std::uint32_t{p[0]} << 8) | p[1];
            sum2 += sum1;
        }
        sum1 = (sum1 & 0xffff) + (sum1 >> 16);
        sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    }
    if (bytes.size() % 2 != 0) {
        sum1 += std::uint32_t{*p} << 8;
        sum2 += sum1;
        sum1 = (sum1 & 0xffff) + (sum1 >> 16);
        sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    }
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    return (sum2 << 16) | sum1;
}

std::vector<unsigned char> filtered_chunk(std::span<const unsigned char> chunk, std::size_t element_size, int level) {
    std::vector<unsigned char> shuffled(chunk.size());
    shuffle_bytes(chunk, element_size, shuffled.data());
    uLongf size = compressBound(static_cast<uLong>(chunk.size()));
    std::vector<unsigned char> out(size + 4);
    if (compress2(out.data(), &size, shuffled.data(), static_cast<uLong>(chunk.size()), level) != Z_OK)
        throw std::runtime_error("zlib: compressing a dataset chunk failed");
    const std::uint32_t sum = fletcher32({out.data(), size});
    for (int b = 0; b < 4; ++b) out[size + static_cast<std::size_t>(b)] = static_cast<unsigned char>(sum >> (8 * b));
    out.resize(size + 4);
    return out;
}

}  // namespace luxtrace::hdf5
