// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// THINTOOL_API marks what ThinTool's shared libraries export: the types and functions a program
/// uses (thintool/thintool.h, the haptic layer's headers). The shared builds hide every other
/// symbol (CMake's CXX_VISIBILITY_PRESET hidden), so that the stages' internals are no part of the
/// binary interface. A class marked exports its members, its vtable and its type information, which
/// a program needs to catch thintool::Error or derive from haptics::Device.

#if defined(__GNUC__) || defined(__clang__)
#define THINTOOL_API __attribute__((visibility("default")))
#else
#define THINTOOL_API
#endif
