#pragma once
// What HDF5's filter pipeline makes of one chunk of a luxtrace dataset (shuffle, deflate,
// Fletcher-32, in that order: hdf5_file.cpp's write_dataset), done outside HDF5 so that
// the chunks of a large map are compressed on every core and then handed to HDF5 as they
// are (H5Dwrite_chunk). Internal to src/io; no HDF5 header here.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace luxtrace::hdf5 {

// The shuffle filter: byte k of every element together, k = 0 .. element_size - 1; a
// tail shorter than an element stays where it is.
void shuffle_bytes(std::span<const unsigned char> in, std::size_t element_size, unsigned char* out);

// HDF5's Fletcher-32: the sums run over 16-bit words read most significant byte first
// (an odd last byte as the high byte of a word), folded every 360 words.
std::uint32_t fletcher32(std::span<const unsigned char> bytes);

// The stored bytes of one chunk: shuffled, zlib-compressed at `level` (what HDF5's
// deflate filter writes), then the checksum of those bytes appended little-endian.
std::vector<unsigned char> filtered_chunk(std::span<const unsigned char> chunk, std::size_t element_size, int level);

}  // namespace luxtrace::hdf5
