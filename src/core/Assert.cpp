// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/core/Assert.h>

#include <cstdio>
#include <cstdlib>

namespace thintool {

namespace {

void abortWithMessage(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: ThinTool's internal check failed: %s\n", file, line, condition);
  std::abort();
}

AssertHandler g_handler = abortWithMessage;

}  // namespace

AssertHandler setAssertHandler(AssertHandler handler) {
  const AssertHandler previous = g_handler;
  g_handler = handler != nullptr ? handler : abortWithMessage;
  return previous;
}

bool libraryChecksAsserts() {
#if defined(THINTOOL_ENABLE_ASSERTS)
  return true;
#else
  return false;
#endif
}

namespace detail {

void assertFailed(const char* condition, const char* file, int line) { g_handler(condition, file, line); }

}  // namespace detail

}  // namespace thintool
