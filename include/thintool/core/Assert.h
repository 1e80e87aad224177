// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// Checks of ThinTool's internal invariants: what its own code guarantees to itself (a patch's
/// arrays agree, an index is in range), never what a user passes in, which is refused with a
/// thintool::Error at registration or skipped and counted while stepping. As Box2D's b2Assert,
/// they are compiled in only where asked for: THINTOOL_ENABLE_ASSERTS (CMake's THINTOOL_ASSERTS
/// option, on in Debug builds and in the test script's sanitizer stage), and a failed one calls a
/// handler the program can set.

#include <thintool/core/Api.h>

namespace thintool {

/// Called with the failed condition's text and where it is. The default handler prints them to
/// standard error and aborts. A handler that returns lets the step go on past the failed check.
using AssertHandler = void (*)(const char* condition, const char* file, int line);

/// Sets the handler failed checks call (nullptr: the default) and returns the one it replaces.
/// Not thread-safe: set it before stepping.
THINTOOL_API AssertHandler setAssertHandler(AssertHandler handler);

/// Whether the library itself was built with its checks (THINTOOL_ASSERTS).
THINTOOL_API bool libraryChecksAsserts();

namespace detail {
/// Calls the handler set by setAssertHandler.
THINTOOL_API void assertFailed(const char* condition, const char* file, int line);
}  // namespace detail

}  // namespace thintool

#if defined(THINTOOL_ENABLE_ASSERTS)
#define THINTOOL_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::thintool::detail::assertFailed(#condition, __FILE__, __LINE__))
#else
// Not evaluated (sizeof): no code, and no warning about names only a check uses.
#define THINTOOL_ASSERT(condition) static_cast<void>(sizeof(!(condition)))
#endif
