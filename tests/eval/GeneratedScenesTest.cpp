// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// ThinTool on random scenes: seeds 1 to 300 in blocks of 50, and the seeds that once failed
// (eval/generated/regressions.txt), each run with ThinTool's default algorithm and judged by the
// ground truth alone (eval/SceneJudge.h). A failing seed is reported with the command that shows
// it step by step.

#include <Runner.h>
#include <SceneGenerator.h>
#include <SceneJudge.h>

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace thintool::eval {
namespace {

const std::string kScenes = THINTOOL_EVAL_SCENES;

void expectNoFailures(const std::vector<std::uint64_t>& seeds) {
  int failed = 0;
  for (std::uint64_t seed : seeds) {
    Verdict verdict;
    std::string description;
    try {
      const SceneSpec scene = generateScene(seed, kScenes);
      description = describeScene(scene);
      verdict = judge(runScene(scene));
    } catch (const Error& e) {
      verdict = refusedVerdict(e.what());
    }
    if (!verdict.failed) continue;
    ++failed;
    ADD_FAILURE() << "seed " << seed << ": " << joinReasons(verdict) << "\n  " << description
                  << "\n  reproduce: build/eval/thintool_generated --seed " << seed << " --algorithm swept --verbose";
  }
  EXPECT_EQ(failed, 0) << "of " << seeds.size() << " seeds";
}

std::vector<std::uint64_t> block(std::uint64_t first, std::uint64_t last) {
  std::vector<std::uint64_t> seeds;
  for (std::uint64_t s = first; s <= last; ++s) seeds.push_back(s);
  return seeds;
}

TEST(GeneratedScenes, Seeds1To50) { expectNoFailures(block(1, 50)); }
TEST(GeneratedScenes, Seeds51To100) { expectNoFailures(block(51, 100)); }
TEST(GeneratedScenes, Seeds101To150) { expectNoFailures(block(101, 150)); }
TEST(GeneratedScenes, Seeds151To200) { expectNoFailures(block(151, 200)); }
TEST(GeneratedScenes, Seeds201To250) { expectNoFailures(block(201, 250)); }
TEST(GeneratedScenes, Seeds251To300) { expectNoFailures(block(251, 300)); }

TEST(GeneratedScenes, Regressions) {
  expectNoFailures(readSeedFile(std::string(THINTOOL_EVAL_GENERATED) + "/regressions.txt"));
}

}  // namespace
}  // namespace thintool::eval
