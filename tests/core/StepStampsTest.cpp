// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The memory that spans steps: an item stamped in one step is the previous step's in the next,
// gone in the one after, and gone at once when the memory forgets.

#include "core/StepStamps.h"

#include <gtest/gtest.h>

namespace thintool {
namespace {

TEST(StepStamps, NothingCountsAsStampedBeforeItsFirstStamp) {
  StepStamps stamps;
  stamps.reset(3);
  for (Index item = 0; item < 3; ++item) {
    EXPECT_FALSE(stamps.stampedThisStep(item));
    EXPECT_FALSE(stamps.stampedLastStep(item));
  }
  stamps.beginStep();
  EXPECT_FALSE(stamps.stampedLastStep(0));
  EXPECT_FALSE(stamps.stampedRecently(0));
}

TEST(StepStamps, AStampIsThisStepsThenThePreviousStepsThenGone) {
  StepStamps stamps;
  stamps.reset(2);
  stamps.beginStep();
  stamps.stamp(1);
  EXPECT_TRUE(stamps.stampedThisStep(1));
  EXPECT_TRUE(stamps.stampedRecently(1));
  EXPECT_FALSE(stamps.stampedRecently(0));
  stamps.beginStep();
  EXPECT_FALSE(stamps.stampedThisStep(1));
  EXPECT_TRUE(stamps.stampedLastStep(1));
  EXPECT_TRUE(stamps.stampedRecently(1));
  stamps.beginStep();
  EXPECT_FALSE(stamps.stampedRecently(1));
}

TEST(StepStamps, ForgettingDropsEveryStampAndLaterStampsCountAgain) {
  StepStamps stamps;
  stamps.reset(2);
  stamps.beginStep();
  stamps.stamp(0);
  stamps.forget();
  EXPECT_FALSE(stamps.stampedRecently(0));
  stamps.beginStep();
  EXPECT_FALSE(stamps.stampedLastStep(0));
  stamps.stamp(1);
  stamps.beginStep();
  EXPECT_TRUE(stamps.stampedLastStep(1));
}

TEST(StepStamps, ResizeKeepsTheStampsUnlessTheCountChanges) {
  StepStamps stamps;
  stamps.reset(2);
  stamps.beginStep();
  stamps.stamp(0);
  stamps.resize(2);
  EXPECT_TRUE(stamps.stampedThisStep(0));
  stamps.resize(3);
  EXPECT_EQ(stamps.size(), 3u);
  EXPECT_FALSE(stamps.stampedThisStep(0));
}

}  // namespace
}  // namespace thintool
