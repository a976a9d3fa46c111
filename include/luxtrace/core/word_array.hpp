#pragma once
// A fixed-size array of 64-bit words, zero at birth, in memory of its own.
//
// The tally store of a million-triangle scene is 80 MB, much of which a closed room never
// touches (the back sides, the repeats). A std::vector writes every zero itself, so every
// page is faulted in and stays resident. This array maps its memory straight from the
// kernel, whose fresh pages read as zero: words never written cost no memory and no time.
// It is page-aligned, so the store's 32-byte count blocks never straddle a cache line.
// (Transparent huge pages were tried for the scattered arrivals: no gain measured on the
// million-triangle room, and more memory resident; docs/PERFORMANCE.md.)
#include <cstddef>
#include <cstdint>
#include <span>

namespace luxtrace {

class WordArray {
public:
    WordArray() = default;
    explicit WordArray(std::size_t words);
    ~WordArray();
    WordArray(const WordArray& other);
    WordArray& operator=(const WordArray& other);
    WordArray(WordArray&& other) noexcept;
    WordArray& operator=(WordArray&& other) noexcept;

    std::size_t size() const { return size_; }
    std::uint64_t* data() { return words_; }
    const std::uint64_t* data() const { return words_; }
    std::uint64_t& operator[](std::size_t i) { return words_[i]; }
    const std::uint64_t& operator[](std::size_t i) const { return words_[i]; }
    std::uint64_t* begin() { return words_; }
    std::uint64_t* end() { return words_ + size_; }
    const std::uint64_t* begin() const { return words_; }
    const std::uint64_t* end() const { return words_ + size_; }
    std::span<std::uint64_t> span() { return {words_, size_}; }
    std::span<const std::uint64_t> span() const { return {words_, size_}; }

private:
    void release() noexcept;
    std::uint64_t* words_ = nullptr;
    std::size_t size_ = 0;
    std::size_t mapped_bytes_ = 0;  // 0: no mapping of its own (empty)
};

}  // namespace luxtrace
