// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// A Novint Falcon through libnifalcon, built only where libnifalcon is found. The firmware file
// is Novint's and is not shipped: the user names theirs (novint.bin from Novint's driver package).

#include <thintool/haptics/Device.h>

#include <memory>
#include <string>

namespace thintool::examples {

/// Opens Falcon number index, loads the firmware if it has none and homes it (FalconSession);
/// throws thintool::Error on failure.
std::unique_ptr<haptics::Device> openFalcon(int index, const std::string& firmwareFile);

}  // namespace thintool::examples
