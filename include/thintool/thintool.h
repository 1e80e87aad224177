// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Everything a Bullet application needs to use ThinTool.

#include <thintool/bullet/Clamp.h>
#include <thintool/bullet/CollisionConfiguration.h>
#include <thintool/bullet/Convert.h>
#include <thintool/bullet/SoftBodySolver.h>
#include <thintool/bullet/Tool.h>
#include <thintool/bullet/ToolOptions.h>
#include <thintool/core/Assert.h>
#include <thintool/core/Error.h>
