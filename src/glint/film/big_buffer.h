#pragma once
// An allocator for the large per-pixel planes (the film, its AOVs): blocks of 2 MiB and more are
// 2 MiB-aligned and marked for transparent huge pages (madvise), so that filling a 1080p film
// (25 MB) takes a dozen page faults instead of some six thousand. On the project machine (a VM,
// where a page fault costs microseconds) huge pages for every allocation (glibc's hugetlb tunable)
// took a 1080p Figure 14 render from 321 ms to 245 ms whole process (docs/benchmarks.md); this
// allocator gives them to the film alone. Smaller blocks come from the usual allocator.
#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace glint {

template <typename T>
struct BigAllocator {
    using value_type = T;
    static constexpr std::size_t kHugePage = std::size_t{2} << 20;

    BigAllocator() = default;
    template <typename U>
    constexpr BigAllocator(const BigAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T) / 2) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kHugePage) return std::allocator<T>{}.allocate(n);
        const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (!p) throw std::bad_alloc();
        ::madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without THP the pages are just small
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < kHugePage) {
            std::allocator<T>{}.deallocate(p, n);
        } else {
            std::free(p);
        }
    }
    template <typename U>
    bool operator==(const BigAllocator<U>&) const noexcept { return true; }
};

/// A vector whose large buffers take huge pages.
template <typename T>
using BigVector = std::vector<T, BigAllocator<T>>;

/// n values of a trivial type, left uninitialised (so that the first write, by whichever thread
/// makes it, is the page's first touch), on huge pages when large: for planes that are written
/// whole before they are read, like the 8-bit image of a one-sample render.
template <typename T>
class BigBuffer {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);

public:
    explicit BigBuffer(std::size_t n) : data_(BigAllocator<T>{}.allocate(n)), size_(n) {}
    BigBuffer(const BigBuffer&) = delete;
    BigBuffer& operator=(const BigBuffer&) = delete;
    ~BigBuffer() { BigAllocator<T>{}.deallocate(data_, size_); }
    T* data() { return data_; }
    const T* data() const { return data_; }
    std::size_t size() const { return size_; }

private:
    T* data_;
    std::size_t size_;
};

}  // namespace glint
