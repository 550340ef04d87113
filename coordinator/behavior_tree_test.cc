#include "coordinator/behavior_tree.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace minenav {
namespace {

using ::testing::Test;

BtStatus Root(const BtState& s) { return s.status[0]; }

TEST(BehaviorTreeTest, SequenceRunsItsChildrenInOrderAndSucceedsWhenAllHave) {
  BehaviorTree t;
  const int root = t.AddSequence(-1, "root");
  const int a = t.AddAction(root, "a", 0);
  const int b = t.AddAction(root, "b", 1);
  ASSERT_EQ(t.Validate(), "");
  BtStep s = Tick(t, InitialState(t));
  EXPECT_EQ(s.start, std::vector<int>({a}));
  EXPECT_EQ(Root(s.state), BtStatus::kRunning);
  s = Tick(t, s.state);  // nothing new while a runs
  EXPECT_TRUE(s.start.empty());
  s = Tick(t, Finish(t, s.state, a, true));
  EXPECT_EQ(s.start, std::vector<int>({b}));
  s = Tick(t, Finish(t, s.state, b, true));
  EXPECT_TRUE(s.start.empty());
  EXPECT_EQ(Root(s.state), BtStatus::kSuccess);
}

TEST(BehaviorTreeTest, SequenceFailsAtTheFirstFailureWithItsReason) {
  BehaviorTree t;
  const int root = t.AddSequence(-1, "root");
  const int a = t.AddAction(root, "a", 0);
  t.AddAction(root, "b", 1);
  BtStep s = Tick(t, InitialState(t));
  s = Tick(t, Finish(t, s.state, a, false, "no path to the face"));
  EXPECT_TRUE(s.start.empty()) << "b must not start";
  EXPECT_EQ(Root(s.state), BtStatus::kFailure);
  EXPECT_EQ(s.state.reason[0], "no path to the face");
  EXPECT_EQ(FailureReason(t, s.state), "no path to the face");
}

TEST(BehaviorTreeTest, FallbackTriesTheNextChildAfterAFailure) {
  BehaviorTree t;
  const int root = t.AddFallback(-1, "root");
  const int a = t.AddAction(root, "a", 0);
  const int b = t.AddAction(root, "b", 1);
  const int c = t.AddAction(root, "c", 2);
  BtStep s = Tick(t, InitialState(t));
  EXPECT_EQ(s.start, std::vector<int>({a}));
  s = Tick(t, Finish(t, s.state, a, false, "a broke"));
  EXPECT_EQ(s.start, std::vector<int>({b}));
  s = Tick(t, Finish(t, s.state, b, true));
  EXPECT_EQ(Root(s.state), BtStatus::kSuccess);
  EXPECT_EQ(s.state.status[static_cast<size_t>(c)], BtStatus::kIdle);

  BtStep f = Tick(t, InitialState(t));
  f = Tick(t, Finish(t, f.state, a, false, "a broke"));
  f = Tick(t, Finish(t, f.state, b, false, "b broke"));
  f = Tick(t, Finish(t, f.state, c, false, "c broke"));
  EXPECT_EQ(Root(f.state), BtStatus::kFailure);
  EXPECT_EQ(f.state.reason[0], "c broke");
}

TEST(BehaviorTreeTest, ParallelStartsAllAndHaltsTheOthersWhenOneFails) {
  BehaviorTree t;
  const int root = t.AddParallel(-1, "root");
  const int a = t.AddAction(root, "a", 0);
  const int b = t.AddAction(root, "b", 1);
  const int c = t.AddAction(root, "c", 2);
  BtStep s = Tick(t, InitialState(t));
  EXPECT_EQ(s.start, std::vector<int>({a, b, c}));
  s = Tick(t, Finish(t, s.state, a, true));
  EXPECT_EQ(Root(s.state), BtStatus::kRunning);
  s = Tick(t, Finish(t, s.state, b, false, "boom stuck"));
  EXPECT_EQ(Root(s.state), BtStatus::kFailure);
  EXPECT_EQ(s.halt, std::vector<int>({c}));
  EXPECT_EQ(s.state.reason[0], "boom stuck");

  BtStep ok = Tick(t, InitialState(t));
  for (const int n : {c, a, b}) ok = Tick(t, Finish(t, ok.state, n, true));
  EXPECT_EQ(Root(ok.state), BtStatus::kSuccess);
}

TEST(BehaviorTreeTest, RetryRestartsItsChildUpToTheAttemptsAndSaysHowMany) {
  BehaviorTree t;
  const int root = t.AddRetry(-1, "retry", 3);
  const int seq = t.AddSequence(root, "drive");
  const int plan = t.AddAction(seq, "plan", 0);
  const int go = t.AddAction(seq, "go", 1);
  BtStep s = Tick(t, InitialState(t));
  s = Tick(t, Finish(t, s.state, plan, true));
  EXPECT_EQ(s.start, std::vector<int>({go}));
  s = Tick(t, Finish(t, s.state, go, false, "blocked"));
  // The whole child afresh: plan runs again.
  EXPECT_EQ(s.start, std::vector<int>({plan}));
  EXPECT_EQ(s.state.status[static_cast<size_t>(go)], BtStatus::kIdle);
  s = Tick(t, Finish(t, s.state, plan, false, "no path"));
  EXPECT_EQ(s.start, std::vector<int>({plan}));
  s = Tick(t, Finish(t, s.state, plan, false, "no path"));
  EXPECT_TRUE(s.start.empty());
  EXPECT_EQ(Root(s.state), BtStatus::kFailure);
  EXPECT_EQ(s.state.reason[0], "no path (after 3 attempts)");

  BtStep ok = Tick(t, InitialState(t));
  ok = Tick(t, Finish(t, ok.state, plan, false, "no path"));
  ok = Tick(t, Finish(t, ok.state, plan, true));
  ok = Tick(t, Finish(t, ok.state, go, true));
  EXPECT_EQ(Root(ok.state), BtStatus::kSuccess);
}

TEST(BehaviorTreeTest, HaltStopsWhatRunsKeepsWhatFinishedAndCostsNoAttempt) {
  BehaviorTree t;
  const int root = t.AddSequence(-1, "root");
  const int a = t.AddAction(root, "a", 0);
  const int retry = t.AddRetry(root, "retry b", 2);
  const int b = t.AddAction(retry, "b", 1);
  BtStep s = Tick(t, InitialState(t));
  s = Tick(t, Finish(t, s.state, a, true));
  ASSERT_EQ(s.start, std::vector<int>({b}));
  BtStep h = Halt(t, s.state);
  EXPECT_EQ(h.halt, std::vector<int>({b}));
  EXPECT_EQ(h.state.status[static_cast<size_t>(a)], BtStatus::kSuccess);
  EXPECT_EQ(h.state.status[static_cast<size_t>(b)], BtStatus::kIdle);
  EXPECT_TRUE(RunningActions(t, h.state).empty());
  // A report of the halted action arriving late changes nothing.
  BtState late = Finish(t, h.state, b, false, "late");
  EXPECT_EQ(late.status[static_cast<size_t>(b)], BtStatus::kIdle);
  // Resumed: b afresh, a not again; both of b's attempts are still there.
  s = Tick(t, late);
  EXPECT_EQ(s.start, std::vector<int>({b}));
  s = Tick(t, Finish(t, s.state, b, false, "x"));
  EXPECT_EQ(s.start, std::vector<int>({b})) << "the halt must not have used an attempt";
  s = Tick(t, Finish(t, s.state, b, true));
  EXPECT_EQ(Root(s.state), BtStatus::kSuccess);
}

TEST(BehaviorTreeTest, NodesGraftedLaterStartIdleAndRun) {
  BehaviorTree t;
  const int root = t.AddSequence(-1, "mission");
  const int plan = t.AddAction(root, "plan", 0);
  BtStep s = Tick(t, InitialState(t));
  // The plan's answer adds the subtasks before the plan action is reported done.
  const int seq = t.AddSequence(root, "subtasks");
  const int cut = t.AddAction(seq, "cut", 1);
  s = Tick(t, Finish(t, s.state, plan, true));
  EXPECT_EQ(s.start, std::vector<int>({cut}));
  s = Tick(t, Finish(t, s.state, cut, true));
  EXPECT_EQ(Root(s.state), BtStatus::kSuccess);
}

TEST(BehaviorTreeTest, ValidateNamesTheBadNode) {
  BehaviorTree empty;
  EXPECT_NE(empty.Validate(), "");
  BehaviorTree t;
  const int root = t.AddSequence(-1, "root");
  EXPECT_NE(t.Validate().find("has no children"), std::string::npos);
  const int r = t.AddRetry(root, "r", 2);
  t.AddAction(r, "a", 0);
  EXPECT_EQ(t.Validate(), "");
  t.AddAction(r, "b", 1);
  EXPECT_NE(t.Validate().find("needs exactly one child"), std::string::npos);
  EXPECT_THROW(t.Add(-1, BtNodeType::kSequence, "second root"), std::invalid_argument);
  EXPECT_THROW(t.AddRetry(root, "none", 0), std::invalid_argument);
}

// ----------------------------------------------------------------------------------------
// Random trees of sequences, fallbacks, retries and actions, each action with a scripted list
// of outcomes (one per run), against a reference interpreter written the plain recursive way
// (run a node to its end before the next): the same root result and the same order of action
// runs. The core is event-driven (Tick / Finish); the reference is synchronous.

struct RandomTree {
  BehaviorTree tree;
  std::map<int, std::vector<bool>> outcomes;  // per action: the outcome of each run
};

void Grow(RandomTree& rt, int parent, int depth, std::mt19937& rng) {
  std::uniform_int_distribution<int> kind(0, 3), count(1, 3), attempts(1, 3), coin(0, 1);
  const int k = depth >= 3 ? 3 : kind(rng);
  if (k == 3) {
    const int node = rt.tree.AddAction(parent, "act", 0);
    std::vector<bool> o;
    for (int i = 0; i < 12; ++i) o.push_back(coin(rng) == 1);
    rt.outcomes[node] = o;
    return;
  }
  if (k == 2) {
    const int node = rt.tree.AddRetry(parent, "retry", attempts(rng));
    Grow(rt, node, depth + 1, rng);
    return;
  }
  const int node = k == 0 ? rt.tree.AddSequence(parent, "seq") : rt.tree.AddFallback(parent, "fb");
  for (int i = count(rng); i > 0; --i) Grow(rt, node, depth + 1, rng);
}

bool Reference(const RandomTree& rt, int node, std::map<int, int>& runs, std::vector<int>& order) {
  const BtNode& n = rt.tree.node(node);
  switch (n.type) {
    case BtNodeType::kAction: {
      order.push_back(node);
      return rt.outcomes.at(node).at(static_cast<size_t>(runs[node]++));
    }
    case BtNodeType::kSequence:
      for (const int c : n.children)
        if (!Reference(rt, c, runs, order)) return false;
      return true;
    case BtNodeType::kFallback:
      for (const int c : n.children)
        if (Reference(rt, c, runs, order)) return true;
      return false;
    case BtNodeType::kRetry:
      for (int i = 0; i < n.max_attempts; ++i)
        if (Reference(rt, n.children.front(), runs, order)) return true;
      return false;
    case BtNodeType::kParallel: break;
  }
  ADD_FAILURE() << "no parallel in the random trees";
  return false;
}

TEST(BehaviorTreeTest, RandomTreesAgreeWithAPlainRecursiveInterpreter) {
  std::mt19937 rng(20261202);
  for (int trial = 0; trial < 2000; ++trial) {
    RandomTree rt;
    const int root = rt.tree.AddSequence(-1, "root");
    Grow(rt, root, 1, rng);
    Grow(rt, root, 1, rng);
    ASSERT_EQ(rt.tree.Validate(), "");
    std::map<int, int> ref_runs;
    std::vector<int> ref_order;
    const bool expected = Reference(rt, 0, ref_runs, ref_order);

    std::map<int, int> runs;
    std::vector<int> order;
    BtStep s = Tick(rt.tree, InitialState(rt.tree));
    for (int guard = 0; guard < 1000 && Root(s.state) == BtStatus::kRunning; ++guard) {
      ASSERT_EQ(s.start.size(), 1u) << "sequences and fallbacks run one action at a time";
      const int a = s.start.front();
      order.push_back(a);
      const bool ok = rt.outcomes.at(a).at(static_cast<size_t>(runs[a]++));
      s = Tick(rt.tree, Finish(rt.tree, s.state, a, ok, "x"));
    }
    ASSERT_NE(Root(s.state), BtStatus::kRunning) << "trial " << trial;
    EXPECT_EQ(Root(s.state) == BtStatus::kSuccess, expected) << "trial " << trial;
    EXPECT_EQ(order, ref_order) << "trial " << trial;
  }
}

}  // namespace
}  // namespace minenav
