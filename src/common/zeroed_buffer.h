#pragma once
// A byte buffer that is zero from the start without the container writing a byte: its allocator
// takes the memory from calloc, and its construct without arguments leaves what it is given.
// A large calloc comes from fresh anonymous pages, which the kernel maps only when first written,
// so a page-cache texture of 48 x 48 frames (170 MB at 136^2 texels a frame) costs the frames a
// run fills, not the cache it could fill: the 31 configurations of a `vt eval` each hold one.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace vt {

template <class T>
struct ZeroedAllocator {
  // Default-initialising such an element writes nothing, so calloc's zeros stay what it reads.
  static_assert(std::is_trivially_default_constructible_v<T>);
  using value_type = T;

  ZeroedAllocator() = default;
  template <class U>
  ZeroedAllocator(const ZeroedAllocator<U>& /*other*/) noexcept {}  // NOLINT: rebinding converts

  T* allocate(std::size_t n) {
    if (n == 0) n = 1;  // calloc(0) may return null, which is not an allocation failure
    void* memory = std::calloc(n, sizeof(T));
    if (memory == nullptr) throw std::bad_alloc();
    return static_cast<T*>(memory);
  }
  void deallocate(T* p, std::size_t /*n*/) noexcept { std::free(p); }

  // Value-initialisation (vector(n), resize(n)) leaves calloc's zeros as they are; explicit
  // values are constructed as usual.
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <class U>
  bool operator==(const ZeroedAllocator<U>& /*other*/) const noexcept {
    return true;
  }
};

// Bytes that read as zero until written.
using ZeroedBytes = std::vector<uint8_t, ZeroedAllocator<uint8_t>>;
using ZeroedBlocks = std::vector<std::byte, ZeroedAllocator<std::byte>>;  // compressed texels

}  // namespace vt
