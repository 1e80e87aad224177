// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The stretches of a haptic trace in which the device stood still, for the demos that measure
/// what the hand felt while it held the tool still. Not part of the library.

#include <thintool/core/Math.h>

#include <cstddef>
#include <vector>

namespace thintool::scenes {

/// Calls measure(settled, last) for each stretch of trace (samples with a time in s and a device
/// point in m) in which the device point moved at most 1 µm from one sample to the next, lasting
/// at least settle + minimum seconds: settled is its first sample at least settle seconds in,
/// last its last sample.
template <class Sample, class Measure>
void forEachStillStretch(const std::vector<Sample>& trace, double settle, double minimum, Measure measure) {
  std::size_t first = 0;
  for (std::size_t i = 1; i <= trace.size(); ++i) {
    if (i < trace.size() && length(trace[i].device - trace[i - 1].device) <= 1e-6) continue;
    const std::size_t last = i - 1;
    if (last > first && trace[last].time - trace[first].time >= settle + minimum) {
      std::size_t settled = first;
      while (trace[settled].time < trace[first].time + settle) ++settled;
      measure(settled, last);
    }
    first = i;
  }
}

}  // namespace thintool::scenes
