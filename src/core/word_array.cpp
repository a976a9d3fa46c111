#include "luxtrace/core/word_array.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <utility>

namespace luxtrace {

WordArray::WordArray(std::size_t words) : size_(words) {
    if (words == 0) return;
    constexpr std::size_t kPage = 4096;
    const std::size_t length = (words * sizeof(std::uint64_t) + kPage - 1) / kPage * kPage;
    // A private anonymous mapping: page-aligned, and zero until written.
    void* p = ::mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    words_ = static_cast<std::uint64_t*>(p);
    mapped_bytes_ = length;
}

WordArray::~WordArray() { release(); }

void WordArray::release() noexcept {
    if (mapped_bytes_ > 0) ::munmap(words_, mapped_bytes_);
    words_ = nullptr;
    size_ = mapped_bytes_ = 0;
}

WordArray::WordArray(const WordArray& other) : WordArray(other.size_) {
    std::copy(other.begin(), other.end(), begin());
}

WordArray& WordArray::operator=(const WordArray& other) {
    if (this != &other) *this = WordArray(other);
    return *this;
}

WordArray::WordArray(WordArray&& other) noexcept
    : words_(std::exchange(other.words_, nullptr)), size_(std::exchange(other.size_, 0)),
      mapped_bytes_(std::exchange(other.mapped_bytes_, 0)) {}

WordArray& WordArray::operator=(WordArray&& other) noexcept {
    if (this != &other) {
        release();
        words_ = std::exchange(other.words_, nullptr);
        size_ = std::exchange(other.size_, 0);
        mapped_bytes_ = std::exchange(other.mapped_bytes_, 0);
    }
    return *this;
}

}  // namespace luxtrace
