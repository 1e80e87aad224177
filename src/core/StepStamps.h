// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Which step wrote each item of a memory that spans steps: one stamp per item and one step
/// counter, so that a reader sees only what the previous step (or the current one) wrote, and
/// forgetting everything costs nothing, however large the memory. Swept detection's sides, the
/// sweep's last positions and the force model's rates each keep their memory this way.

#include <thintool/core/Math.h>

#include <cstdint>
#include <vector>

namespace thintool {

class StepStamps {
 public:
  /// Sized to count items; all unstamped when the count changes, kept otherwise.
  void resize(Index count) {
    if (m_stamps.size() != count) m_stamps.assign(count, 0);
  }
  /// Sized to count items, all unstamped.
  void reset(Index count) { m_stamps.assign(count, 0); }
  Index size() const { return static_cast<Index>(m_stamps.size()); }

  /// Starts a step: what the step before stamped is now the previous step's.
  void beginStep() { ++m_step; }
  /// Nothing stamped so far counts as this step's or the previous step's any more.
  void forget() { m_step += 2; }

  void stamp(Index item) { m_stamps[item] = m_step; }
  bool stampedThisStep(Index item) const { return m_stamps[item] == m_step; }
  bool stampedLastStep(Index item) const { return m_stamps[item] + 1 == m_step; }
  /// In this step or the one before.
  bool stampedRecently(Index item) const { return stampedThisStep(item) || stampedLastStep(item); }

 private:
  std::vector<std::uint32_t> m_stamps;
  // Starts two past the unstamped 0, so that no item counts as stamped before its first stamp.
  std::uint32_t m_step = 2;
};

}  // namespace thintool
