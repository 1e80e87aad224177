// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Counts allocations, for the checks that ThinTool's per-step path allocates nothing: every
/// operator new of the program (CountingAllocator.cpp replaces them, so link that file only into
/// an executable of its own) and, once installCountingBulletAllocator() has run, every allocation
/// through Bullet's btAlignedAlloc, which calls malloc directly.

namespace thintool::test {

/// Allocations so far.
long allocationCount();

/// Routes Bullet's btAlignedAlloc through the count.
void installCountingBulletAllocator();

}  // namespace thintool::test
