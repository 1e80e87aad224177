// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The internal checks: the handler a failed one calls, the default that aborts, and a check the
// library makes on what its stages are given.

// This file's own checks are always compiled in, whatever the library was built with.
#define THINTOOL_ENABLE_ASSERTS
#include <thintool/core/Assert.h>

#include "response/Response.h"

#include <gtest/gtest.h>

#include <string>

namespace thintool {
namespace {

struct Failure {
  int count = 0;
  std::string condition;
  std::string file;
  int line = 0;
};
Failure g_failure;

void recordFailure(const char* condition, const char* file, int line) {
  ++g_failure.count;
  g_failure.condition = condition;
  g_failure.file = file;
  g_failure.line = line;
}

// Sets the recording handler for one test and puts the previous one back after it.
struct RecordingHandler {
  AssertHandler previous;
  RecordingHandler() : previous(setAssertHandler(recordFailure)) { g_failure = Failure{}; }
  ~RecordingHandler() { setAssertHandler(previous); }
  RecordingHandler(const RecordingHandler&) = delete;
  RecordingHandler& operator=(const RecordingHandler&) = delete;
};

TEST(Assert, AFailedCheckCallsTheHandlerWithItsConditionAndPlace) {
  RecordingHandler handler;
  const int two = 2;
  THINTOOL_ASSERT(two + 1 == 3);
  EXPECT_EQ(g_failure.count, 0) << "a check that holds calls nothing";
  // clang-format off
  THINTOOL_ASSERT(two + 2 == 5); const int line = __LINE__;
  // clang-format on
  EXPECT_EQ(g_failure.count, 1);
  EXPECT_EQ(g_failure.condition, "two + 2 == 5");
  EXPECT_NE(g_failure.file.find("AssertTest.cpp"), std::string::npos) << g_failure.file;
  EXPECT_EQ(g_failure.line, line);
}

TEST(Assert, SettingAHandlerReturnsTheOneItReplaces) {
  const AssertHandler original = setAssertHandler(recordFailure);
  EXPECT_EQ(setAssertHandler(nullptr), recordFailure);
  EXPECT_EQ(setAssertHandler(original), original) << "nullptr puts the default back";
}

TEST(AssertDeathTest, TheDefaultHandlerAbortsWithTheCondition) {
  EXPECT_DEATH(THINTOOL_ASSERT(sizeof(int) == 0), "internal check failed: sizeof\\(int\\) == 0");
}

// A patch whose face has no id: the glue never gathers one, and the response's check says so when
// the library was built with its checks; built without them, the check costs nothing and says
// nothing.
TEST(Assert, TheResponseChecksThePatchItIsGivenWhenTheLibraryWasBuiltWithChecks) {
  RecordingHandler handler;
  SoftPatch patch;
  for (int k = 0; k < 3; ++k) {
    patch.positions.push_back({Real(k), 0, 0});
    patch.previousPositions.push_back({Real(k), 0, 0});
    patch.inverseMasses.push_back(1);
    patch.nodeIds.push_back(static_cast<Index>(k));
  }
  patch.faces.push_back({0, 1, 2});
  ASSERT_FALSE(patch.consistent());
  const ToolModel model = buildToolModel(makeBoxMesh({0.1, 0.01, 0.1}), ToolModelSettings{});
  ResponseResult result;
  computeResponse({model, Pose{}, Pose{}, 0.01, 0.001}, patch, {}, ResponseSettings{}, result);
  EXPECT_EQ(g_failure.count, libraryChecksAsserts() ? 1 : 0);
  if (libraryChecksAsserts()) {
    EXPECT_EQ(g_failure.condition, "patch.consistent()");
  }
  patch.faceIds.push_back(0);
  EXPECT_TRUE(patch.consistent());
  patch.faces.push_back({0, 1, 3});
  patch.faceIds.push_back(1);
  EXPECT_FALSE(patch.consistent()) << "a face's vertex out of range";
}

}  // namespace
}  // namespace thintool
