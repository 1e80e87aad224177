// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// Plots for the examples, through gnuplot when it is installed (Debian: gnuplot-nox). The script
// is always written next to the data, so a plot can be redone or restyled by hand.

#include <string>

namespace thintool::examples {

/// Writes script to scriptPath and runs gnuplot on it. Returns false, with the reason in
/// whyNot, when gnuplot is missing or fails.
bool runGnuplot(const std::string& scriptPath, const std::string& script, std::string& whyNot);

}  // namespace thintool::examples
