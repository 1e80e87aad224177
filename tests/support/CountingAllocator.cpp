// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "CountingAllocator.h"

#include <LinearMath/btAlignedAllocator.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {

// Single-threaded where it is read; atomic so that a stray thread cannot corrupt it.
std::atomic<long> allocations{0};

void* countedMalloc(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size);
}
void countedFree(void* memory) { std::free(memory); }

}  // namespace

namespace thintool::test {

long allocationCount() { return allocations.load(std::memory_order_relaxed); }

void installCountingBulletAllocator() { btAlignedAllocSetCustom(&countedMalloc, &countedFree); }

}  // namespace thintool::test

// GCC takes the replacement operators' free() of what their malloc() returned for a mismatch.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* memory = std::malloc(size == 0 ? 1 : size)) {
    return memory;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(alignment);
  if (void* memory = std::aligned_alloc(a, (size + a - 1) / a * a)) {
    return memory;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t alignment) { return operator new(size, alignment); }
void operator delete(void* memory, std::align_val_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::align_val_t) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t, std::align_val_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t, std::align_val_t) noexcept { std::free(memory); }
