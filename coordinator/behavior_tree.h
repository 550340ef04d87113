#pragma once
// A small behaviour-tree core, in the manner of BehaviorTree.CPP as Nav2 uses it (Colledanchise
// and Ögren, "Behavior Trees in Robotics and AI", 2018), written anew because BehaviorTree.CPP
// is not in Debian. The tree is data, its state is a value, and every step is a pure function
// of (tree, state, event): the coordinator's mission logic is tested without a bus or a clock.
//
//   sequence  runs its children in order; fails as soon as one fails, succeeds when all have.
//             With memory: a child that succeeded is not run again (Nav2's PipelineSequence
//             re-ticks earlier children; a miner never re-does a finished cut).
//   fallback  runs its children in order until one succeeds; fails when all have failed.
//   parallel  runs all its children at once; fails as soon as one fails (the others are
//             halted), succeeds when all have succeeded.
//   retry     runs its one child again after a failure, at most `max_attempts` times in all.
//   action    a leaf the caller executes: Tick lists it to start; the caller reports its end
//             with Finish. What it does is the caller's (the action's `ref` says which).
//
// Halt (pause, abort, a lost process) puts every running node below a node back to idle and
// lists the actions to stop; a later Tick starts them afresh where the tree stood (finished
// children keep their result), without counting an attempt.

#include <cstdint>
#include <string>
#include <vector>

namespace minenav {

enum class BtNodeType { kSequence, kFallback, kParallel, kRetry, kAction };
enum class BtStatus { kIdle, kRunning, kSuccess, kFailure };

const char* ToString(BtNodeType t);
const char* ToString(BtStatus s);

struct BtNode {
  BtNodeType type = BtNodeType::kAction;
  std::string name;           // one line for people (the mission status shows it)
  int parent = -1;            // index in BehaviorTree::nodes, -1 for the root
  std::vector<int> children;  // in order
  int max_attempts = 1;       // retry: attempts in all (>= 1)
  int64_t ref = -1;           // action: what the caller executes (an index into its own table)
};

class BehaviorTree {
 public:
  // The root is node 0; Add(-1, ...) makes it (once).
  int Add(int parent, BtNodeType type, std::string name, int64_t ref = -1, int max_attempts = 1);
  int AddSequence(int parent, std::string name) { return Add(parent, BtNodeType::kSequence, std::move(name)); }
  int AddFallback(int parent, std::string name) { return Add(parent, BtNodeType::kFallback, std::move(name)); }
  int AddParallel(int parent, std::string name) { return Add(parent, BtNodeType::kParallel, std::move(name)); }
  int AddRetry(int parent, std::string name, int max_attempts) {
    return Add(parent, BtNodeType::kRetry, std::move(name), -1, max_attempts);
  }
  int AddAction(int parent, std::string name, int64_t ref) {
    return Add(parent, BtNodeType::kAction, std::move(name), ref);
  }

  const std::vector<BtNode>& nodes() const { return nodes_; }
  const BtNode& node(int i) const { return nodes_.at(static_cast<size_t>(i)); }
  int size() const { return static_cast<int>(nodes_.size()); }
  // "" when every composite has children, a retry exactly one, an action none; else one line.
  std::string Validate() const;

 private:
  std::vector<BtNode> nodes_;
};

struct BtState {
  std::vector<BtStatus> status;       // per node
  std::vector<int> attempts;          // retry: failures of its child so far
  std::vector<std::string> reason;    // per node: why it failed ("" otherwise)
};

// Every node idle. Grows with the tree: a node added after the state was made starts idle.
BtState InitialState(const BehaviorTree& tree);

struct BtStep {
  BtState state;
  std::vector<int> start;  // action nodes that became running: the caller starts them
  std::vector<int> halt;   // action nodes that were running and are idle now: the caller stops them
};

// Runs the tree from the root: composites decide which children run; an idle action that
// should run becomes running and is listed in `start`. Running actions stay running until
// Finish. The root's status is step.state.status[0].
BtStep Tick(const BehaviorTree& tree, BtState state);

// The end of a running action (success or failure with a one-line reason). Not running:
// ignored (a late or repeated report). Tick afterwards to carry the result up the tree.
BtState Finish(const BehaviorTree& tree, BtState state, int action, bool success, const std::string& reason = "");

// Every running node below and including `node` back to idle; the running actions listed in
// `halt`. Finished nodes keep their result.
BtStep Halt(const BehaviorTree& tree, BtState state, int node = 0);

// The running actions, in tree order.
std::vector<int> RunningActions(const BehaviorTree& tree, const BtState& state);
// The failure reason of the deepest failed node under `node` (the first in tree order), or "".
std::string FailureReason(const BehaviorTree& tree, const BtState& state, int node = 0);

}  // namespace minenav
