#include "coordinator/behavior_tree.h"

#include <stdexcept>
#include <utility>

namespace minenav {
namespace {

size_t U(int i) { return static_cast<size_t>(i); }

// Grows the state to the tree (nodes grafted after the state was made start idle).
void Fit(const BehaviorTree& tree, BtState& s) {
  const size_t n = U(tree.size());
  if (s.status.size() < n) s.status.resize(n, BtStatus::kIdle);
  if (s.attempts.size() < n) s.attempts.resize(n, 0);
  if (s.reason.size() < n) s.reason.resize(n);
}

void SetStatus(BtState& s, int node, BtStatus status, const std::string& reason = "") {
  s.status[U(node)] = status;
  s.reason[U(node)] = status == BtStatus::kFailure ? reason : "";
}

// Back to idle below and including `node`: running actions are listed in `halted`; finished
// nodes are reset too when `forget_results` (a retry starts its child afresh).
void Reset(const BehaviorTree& tree, BtState& s, int node, bool forget_results, std::vector<int>& halted) {
  const BtNode& n = tree.node(node);
  const BtStatus st = s.status[U(node)];
  if (n.type == BtNodeType::kAction && st == BtStatus::kRunning) halted.push_back(node);
  if (st == BtStatus::kRunning || forget_results) {
    SetStatus(s, node, BtStatus::kIdle);
    if (forget_results) s.attempts[U(node)] = 0;
  }
  for (const int c : n.children) Reset(tree, s, c, forget_results, halted);
}

std::string ChildReason(const BtState& s, int child, const std::string& name) {
  const std::string& r = s.reason[U(child)];
  return r.empty() ? name + " failed" : r;
}

BtStatus TickNode(const BehaviorTree& tree, BtState& s, int node, BtStep& step);

BtStatus TickSequence(const BehaviorTree& tree, BtState& s, int node, BtStep& step) {
  const BtNode& n = tree.node(node);
  for (const int c : n.children) {
    if (s.status[U(c)] == BtStatus::kSuccess) continue;
    const BtStatus r = TickNode(tree, s, c, step);
    if (r == BtStatus::kSuccess) continue;
    if (r == BtStatus::kFailure) SetStatus(s, node, BtStatus::kFailure, ChildReason(s, c, tree.node(c).name));
    else SetStatus(s, node, BtStatus::kRunning);
    return s.status[U(node)];
  }
  SetStatus(s, node, BtStatus::kSuccess);
  return BtStatus::kSuccess;
}

BtStatus TickFallback(const BehaviorTree& tree, BtState& s, int node, BtStep& step) {
  const BtNode& n = tree.node(node);
  std::string last_reason;
  for (const int c : n.children) {
    if (s.status[U(c)] == BtStatus::kFailure) {
      last_reason = ChildReason(s, c, tree.node(c).name);
      continue;
    }
    const BtStatus r = TickNode(tree, s, c, step);
    if (r == BtStatus::kFailure) {
      last_reason = ChildReason(s, c, tree.node(c).name);
      continue;
    }
    SetStatus(s, node, r);
    return r;
  }
  SetStatus(s, node, BtStatus::kFailure, last_reason);
  return BtStatus::kFailure;
}

BtStatus TickParallel(const BehaviorTree& tree, BtState& s, int node, BtStep& step) {
  const BtNode& n = tree.node(node);
  bool all_done = true;
  for (const int c : n.children) {
    if (s.status[U(c)] == BtStatus::kSuccess) continue;
    const BtStatus r = TickNode(tree, s, c, step);
    if (r == BtStatus::kFailure) {
      const std::string why = ChildReason(s, c, tree.node(c).name);
      for (const int other : n.children) Reset(tree, s, other, false, step.halt);
      SetStatus(s, c, BtStatus::kFailure, why);
      SetStatus(s, node, BtStatus::kFailure, why);
      return BtStatus::kFailure;
    }
    if (r != BtStatus::kSuccess) all_done = false;
  }
  SetStatus(s, node, all_done ? BtStatus::kSuccess : BtStatus::kRunning);
  return s.status[U(node)];
}

BtStatus TickRetry(const BehaviorTree& tree, BtState& s, int node, BtStep& step) {
  const BtNode& n = tree.node(node);
  const int child = n.children.front();
  for (;;) {
    const BtStatus r = TickNode(tree, s, child, step);
    if (r != BtStatus::kFailure) {
      SetStatus(s, node, r);
      return r;
    }
    const int failures = ++s.attempts[U(node)];
    if (failures >= n.max_attempts) {
      SetStatus(s, node, BtStatus::kFailure,
                ChildReason(s, child, tree.node(child).name) + " (after " + std::to_string(failures) + " attempt" +
                    (failures == 1 ? "" : "s") + ")");
      return BtStatus::kFailure;
    }
    Reset(tree, s, child, true, step.halt);  // the child afresh; its failures are counted here
  }
}

BtStatus TickNode(const BehaviorTree& tree, BtState& s, int node, BtStep& step) {
  const BtStatus current = s.status[U(node)];
  if (current == BtStatus::kSuccess || current == BtStatus::kFailure) return current;
  switch (tree.node(node).type) {
    case BtNodeType::kSequence: return TickSequence(tree, s, node, step);
    case BtNodeType::kFallback: return TickFallback(tree, s, node, step);
    case BtNodeType::kParallel: return TickParallel(tree, s, node, step);
    case BtNodeType::kRetry: return TickRetry(tree, s, node, step);
    case BtNodeType::kAction:
      if (current == BtStatus::kIdle) {
        SetStatus(s, node, BtStatus::kRunning);
        step.start.push_back(node);
      }
      return BtStatus::kRunning;
  }
  return current;
}

void CollectRunning(const BehaviorTree& tree, const BtState& s, int node, std::vector<int>& out) {
  const BtNode& n = tree.node(node);
  if (n.type == BtNodeType::kAction && s.status[U(node)] == BtStatus::kRunning) out.push_back(node);
  for (const int c : n.children) CollectRunning(tree, s, c, out);
}

}  // namespace

const char* ToString(BtNodeType t) {
  switch (t) {
    case BtNodeType::kSequence: return "sequence";
    case BtNodeType::kFallback: return "fallback";
    case BtNodeType::kParallel: return "parallel";
    case BtNodeType::kRetry: return "retry";
    case BtNodeType::kAction: return "action";
  }
  return "unknown";
}

const char* ToString(BtStatus s) {
  switch (s) {
    case BtStatus::kIdle: return "idle";
    case BtStatus::kRunning: return "running";
    case BtStatus::kSuccess: return "success";
    case BtStatus::kFailure: return "failure";
  }
  return "unknown";
}

int BehaviorTree::Add(int parent, BtNodeType type, std::string name, int64_t ref, int max_attempts) {
  if (parent < 0 && !nodes_.empty()) throw std::invalid_argument("the behaviour tree has a root already");
  if (parent >= size()) throw std::invalid_argument("no node " + std::to_string(parent) + " to add a child to");
  if (max_attempts < 1) throw std::invalid_argument("a retry needs at least one attempt");
  BtNode n;
  n.type = type;
  n.name = std::move(name);
  n.parent = parent;
  n.ref = ref;
  n.max_attempts = max_attempts;
  nodes_.push_back(std::move(n));
  const int id = size() - 1;
  if (parent >= 0) nodes_[U(parent)].children.push_back(id);
  return id;
}

std::string BehaviorTree::Validate() const {
  if (nodes_.empty()) return "the behaviour tree is empty";
  for (int i = 0; i < size(); ++i) {
    const BtNode& n = nodes_[U(i)];
    const size_t c = n.children.size();
    const std::string what = "node " + std::to_string(i) + " (" + ToString(n.type) + " '" + n.name + "')";
    if (n.type == BtNodeType::kAction && c != 0) return what + " is an action with children";
    if (n.type == BtNodeType::kRetry && c != 1) return what + " needs exactly one child";
    if ((n.type == BtNodeType::kSequence || n.type == BtNodeType::kFallback || n.type == BtNodeType::kParallel) &&
        c == 0)
      return what + " has no children";
  }
  return "";
}

BtState InitialState(const BehaviorTree& tree) {
  BtState s;
  Fit(tree, s);
  return s;
}

BtStep Tick(const BehaviorTree& tree, BtState state) {
  BtStep step;
  step.state = std::move(state);
  Fit(tree, step.state);
  if (tree.size() > 0) TickNode(tree, step.state, 0, step);
  return step;
}

BtState Finish(const BehaviorTree& tree, BtState state, int action, bool success, const std::string& reason) {
  Fit(tree, state);
  if (action < 0 || action >= tree.size() || tree.node(action).type != BtNodeType::kAction) return state;
  if (state.status[U(action)] != BtStatus::kRunning) return state;
  SetStatus(state, action, success ? BtStatus::kSuccess : BtStatus::kFailure,
            reason.empty() ? tree.node(action).name + " failed" : reason);
  return state;
}

BtStep Halt(const BehaviorTree& tree, BtState state, int node) {
  BtStep step;
  step.state = std::move(state);
  Fit(tree, step.state);
  if (node >= 0 && node < tree.size()) Reset(tree, step.state, node, false, step.halt);
  return step;
}

std::vector<int> RunningActions(const BehaviorTree& tree, const BtState& state) {
  std::vector<int> out;
  if (tree.size() > 0 && state.status.size() >= U(tree.size())) CollectRunning(tree, state, 0, out);
  return out;
}

std::string FailureReason(const BehaviorTree& tree, const BtState& state, int node) {
  if (node < 0 || node >= tree.size() || state.status.size() < U(tree.size())) return "";
  for (const int c : tree.node(node).children) {
    const std::string r = FailureReason(tree, state, c);
    if (!r.empty()) return r;
  }
  return state.status[U(node)] == BtStatus::kFailure ? state.reason[U(node)] : "";
}

}  // namespace minenav
