// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The block kernel, compiled once for the target's baseline and, on x86-64, again for AVX2 and
// AVX-512F, with the variant chosen at the first call from what the CPU reports (GCC's and
// Clang's __builtin_cpu_supports, which also checks that the system saves the wider registers).
// The whole file is compiled with -ffp-contract=off (CMakeLists.txt): AVX-512F brings fused
// multiply-add, and a fused variant would round differently from the scalar kernel.
#include "geometry/RayTriangle.h"

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define THINTOOL_BLOCK_KERNEL_X86 1
#include <immintrin.h>
#endif

namespace thintool {
namespace {

// The kernel every variant compiles: inlined into each, so that each vectorises it for its own
// instruction set. It leaves the hit flags in flags; each variant gathers them into the mask.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline SegmentTriangleBlockHits blockKernel(const Vec3& origin, const Vec3& delta, const TriangleBlock& block,
                                            Real (&flags)[TriangleBlock::kSize]) {
  constexpr int kLanes = TriangleBlock::kSize;
  constexpr Real kParallelCosineSquared = kParallelCosine * kParallelCosine;
  // Locals, and results written to a local object, so that no store in the loop may alias a load:
  // at -O2, GCC vectorises only loops that need no run-time alias check.
  const Real ox = origin.x, oy = origin.y, oz = origin.z;
  const Real dx = delta.x, dy = delta.y, dz = delta.z;
  const Real deltaSquared = dx * dx + dy * dy + dz * dz;
  SegmentTriangleBlockHits out;
  for (int k = 0; k < kLanes; ++k) {
    const Real e1x = block.e1[0][k], e1y = block.e1[1][k], e1z = block.e1[2][k];
    const Real e2x = block.e2[0][k], e2y = block.e2[1][k], e2z = block.e2[2][k];

    // p = delta × e2 and det = e1·p, as the scalar kernel; |e1 × e2|² came with the block.
    const Real px = dy * e2z - dz * e2y;
    const Real py = dz * e2x - dx * e2z;
    const Real pz = dx * e2y - dy * e2x;
    const Real det = e1x * px + e1y * py + e1z * pz;
    const Real parallelBound = kParallelCosineSquared * deltaSquared * block.areaSquared4[k];
    // Lanes that fail the parallel test divide by a zero or tiny det here; their results are
    // discarded below, and IEEE division does not trap.
    const Real invDet = 1 / det;

    const Real sx = ox - block.v0[0][k];
    const Real sy = oy - block.v0[1][k];
    const Real sz = oz - block.v0[2][k];
    const Real u = (sx * px + sy * py + sz * pz) * invDet;
    const Real qx = sy * e1z - sz * e1y;
    const Real qy = sz * e1x - sx * e1z;
    const Real qz = sx * e1y - sy * e1x;
    const Real v = (dx * qx + dy * qy + dz * qz) * invDet;
    const Real t = (e2x * qx + e2y * qy + e2z * qz) * invDet;

    // Acceptance tests, so that NaN anywhere is a miss; & rather than && keeps the loop branch-free.
    const bool hit = (det * det > parallelBound) & (u >= -kBarycentricTolerance) &
                     (u <= 1 + kBarycentricTolerance) & (v >= -kBarycentricTolerance) &
                     (u + v <= 1 + kBarycentricTolerance) & (t >= 0) & (t <= 1);
    out.t[k] = hit ? t : 0;
    out.u[k] = hit ? u : 0;
    out.v[k] = hit ? v : 0;
    flags[k] = hit ? 1 : 0;
  }
  return out;
}

// Hit flags as doubles: SSE2 has no 64-bit integer compare, so a flag of a double's width must be
// a double for the kernel's loop to vectorise without -msse4.2.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline unsigned maskOf(const Real (&flags)[TriangleBlock::kSize]) {
  unsigned mask = 0;
  unsigned bit = 1;
  for (const Real flag : flags) {
    mask |= flag != 0 ? bit : 0U;
    bit <<= 1;
  }
  return mask;
}

using BlockFunction = SegmentTriangleBlockHits (*)(const Vec3&, const Vec3&, const TriangleBlock&);

SegmentTriangleBlockHits portableKernel(const Vec3& origin, const Vec3& delta, const TriangleBlock& block) {
  alignas(64) Real flags[TriangleBlock::kSize];
  SegmentTriangleBlockHits out = blockKernel(origin, delta, block, flags);
  out.mask = maskOf(flags);
  return out;
}

#ifdef THINTOOL_BLOCK_KERNEL_X86
// The flags are two vectors here, and a compare and a move of their sign bits gather each half,
// where the portable gathering takes a score of shuffles.
__attribute__((target("avx2"))) SegmentTriangleBlockHits avx2Kernel(const Vec3& origin, const Vec3& delta,
                                                                    const TriangleBlock& block) {
  alignas(64) Real flags[TriangleBlock::kSize];
  SegmentTriangleBlockHits out = blockKernel(origin, delta, block, flags);
  const __m256d zero = _mm256_setzero_pd();
  const int low = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_load_pd(flags), zero, _CMP_NEQ_OQ));
  const int high = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_load_pd(flags + 4), zero, _CMP_NEQ_OQ));
  out.mask = static_cast<unsigned>(low | (high << 4));
  return out;
}

// One vector of flags, and one compare into a mask register.
__attribute__((target("avx512f"))) SegmentTriangleBlockHits avx512Kernel(const Vec3& origin, const Vec3& delta,
                                                                        const TriangleBlock& block) {
  alignas(64) Real flags[TriangleBlock::kSize];
  SegmentTriangleBlockHits out = blockKernel(origin, delta, block, flags);
  out.mask = _mm512_cmp_pd_mask(_mm512_load_pd(flags), _mm512_setzero_pd(), _CMP_NEQ_OQ);
  return out;
}
#endif

std::vector<BlockKernel> detectKernels() {
  std::vector<BlockKernel> kernels{BlockKernel::Portable};
#ifdef THINTOOL_BLOCK_KERNEL_X86
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2")) kernels.push_back(BlockKernel::Avx2);
  if (__builtin_cpu_supports("avx512f")) kernels.push_back(BlockKernel::Avx512);
#endif
  return kernels;
}

constexpr int kKernelCount = 3;  // BlockKernel's values

// Each kernel's function, the portable one where the CPU does not run it.
struct KernelTable {
  BlockFunction functions[kKernelCount] = {portableKernel, portableKernel, portableKernel};
  BlockFunction best = portableKernel;

  KernelTable() {
    for (const BlockKernel kernel : availableBlockKernels()) {
#ifdef THINTOOL_BLOCK_KERNEL_X86
      if (kernel == BlockKernel::Avx2) functions[static_cast<int>(BlockKernel::Avx2)] = avx2Kernel;
      if (kernel == BlockKernel::Avx512) functions[static_cast<int>(BlockKernel::Avx512)] = avx512Kernel;
#endif
      best = functions[static_cast<int>(kernel)];
    }
  }
};

const KernelTable& kernelTable() {
  static const KernelTable table;
  return table;
}

}  // namespace

const std::vector<BlockKernel>& availableBlockKernels() {
  static const std::vector<BlockKernel> kernels = detectKernels();
  return kernels;
}

const char* blockKernelName(BlockKernel kernel) {
  switch (kernel) {
    case BlockKernel::Avx2:
      return "avx2";
    case BlockKernel::Avx512:
      return "avx512";
    case BlockKernel::Portable:
      break;
  }
  return "portable";
}

SegmentTriangleBlockHits intersectSegmentTriangleBlock(const Vec3& origin, const Vec3& delta,
                                                       const TriangleBlock& block) {
  static const BlockFunction best = kernelTable().best;
  return best(origin, delta, block);
}

SegmentTriangleBlockHits intersectSegmentTriangleBlock(BlockKernel kernel, const Vec3& origin, const Vec3& delta,
                                                       const TriangleBlock& block) {
  const int index = static_cast<int>(kernel);
  const BlockFunction function = index >= 0 && index < kKernelCount ? kernelTable().functions[index] : portableKernel;
  return function(origin, delta, block);
}

}  // namespace thintool
