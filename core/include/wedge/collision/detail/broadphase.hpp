// The broad phase: a dynamic AABB tree in n-D (after Box2D's b2DynamicTree). Each proxy (one bounded
// shape of a body) is a leaf holding a fat box, its tight box grown by a margin and stretched along its
// predicted displacement; a proxy is re-inserted only when its tight box leaves the fat box, so a body
// resting or moving slowly costs one containment test per step. A leaf is inserted beside the sibling
// that adds the least cost (aabb.hpp's cost(), found exactly by branch and bound), and AVL-style
// rotations keep the tree's height logarithmic. Nodes live in a pool with a free list: once the pool,
// the move buffer and the pair and search buffers have grown, updates allocate nothing.
//
// Pairs: update_pairs() queries the tree only with the proxies that were created or re-inserted since
// the last call (the move buffer), keeps the pairs between unmoved proxies from the last call (their fat
// boxes have not changed) and returns the complete current set, sorted. The result is a function of the
// fat boxes and user ids alone: it does not depend on the tree's shape, node indices or pointer values.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "wedge/collision/aabb.hpp"
#include "wedge/ga/types.hpp"

namespace wedge {

struct BroadPhaseSettings {
  // m: a proxy's fat box is its tight box grown by this on every side.
  double margin = 0.05;
  // The fat box also reaches this many times the given displacement ahead (dimensionless; the
  // displacement is what the body is expected to move before the next update, e.g. v h).
  double displacement_multiplier = 2.0;
  // A proxy whose tight box is still inside its fat box is re-inserted anyway when the fat box no
  // longer fits inside the new fat box grown by this many margins (dimensionless): the fat box of a
  // body that moved fast and stopped shrinks back.
  double shrink_margins = 4.0;
};

template <int N>
class BroadPhase {
 public:
  // A pair of user ids, first < second.
  using Pair = std::pair<std::uint32_t, std::uint32_t>;
  static constexpr int kNull = -1;

  // Throws wedge::Error for negative or non-finite settings.
  explicit BroadPhase(const BroadPhaseSettings& settings = {});

  const BroadPhaseSettings& settings() const { return settings_; }

  // Adds a proxy for the tight box `box` (valid(), else wedge::Error) and returns its id (>= 0). Ids of
  // destroyed proxies are reused. Proxies with equal user ids (several shapes of one body) are never
  // paired with each other.
  int create_proxy(const Aabb<N>& box, std::uint32_t user_id);
  // Throws wedge::Error for an id that is not a live proxy.
  void destroy_proxy(int proxy);
  // Gives the proxy its new tight box and its expected displacement until the next update (m). Returns
  // true if the proxy was re-inserted with a new fat box (box ± margin, stretched by
  // displacement_multiplier * displacement), false if the old fat box still holds it (and is not more
  // than shrink_margins margins too large). Throws wedge::Error for an invalid id, box or displacement.
  bool move_proxy(int proxy, const Aabb<N>& box, const Vec<N>& displacement);

  // Brings pairs() up to date: every pair of distinct user ids that have proxies with overlapping fat
  // boxes, each with first < second, sorted ascending, without duplicates. Only proxies created or
  // re-inserted since the last call query the tree. Returns false, having done nothing, when no proxy
  // was created, re-inserted or destroyed since the last call (the list is the last one: a resting
  // scene's step). Allocates nothing once its buffers have grown.
  bool update_pairs();
  const std::vector<Pair>& pairs() const { return user_pairs_; }
  // update_pairs(), then `out` = pairs().
  void update_pairs(std::vector<Pair>& out) {
    update_pairs();
    out = user_pairs_;
  }

  // Calls callback(proxy) for every proxy whose fat box overlaps `box`, in an order fixed by the tree.
  // If the callback returns bool, false stops the query.
  template <class F>
  void query(const Aabb<N>& box, F&& callback) const {
    query_impl(box, callback, nullptr);
  }

  std::uint32_t user_id(int proxy) const;
  const Aabb<N>& fat_box(int proxy) const;
  int proxy_count() const { return proxy_count_; }
  // The tree's height: 0 for a single leaf, -1 when empty.
  int height() const { return root_ == kNull ? -1 : nodes_[root_].height; }
  // Box-versus-node overlap tests made by the last update_pairs (the cost the sub-quadratic bound is
  // about), and how many proxies queried the tree in it.
  std::int64_t node_overlap_tests() const { return node_overlap_tests_; }
  int queried_proxies() const { return queried_proxies_; }

  // Checks the tree's invariants (parent links, heights, every internal box exactly the union of its
  // children's, leaf and free counts) and throws wedge::Error naming the first violation.
  void validate() const;

 private:
  struct Node {
    Aabb<N> box;
    int parent = kNull;  // the next free node while on the free list
    int child1 = kNull;
    int child2 = kNull;
    int height = -1;  // 0 for a leaf, -1 for a free node
    std::uint32_t user_id = 0;
    int move_slot = -1;  // a leaf's index in move_buffer_, or -1
    bool leaf() const { return child1 == kNull; }
  };
  // A pair of proxies, ordered and keyed by user id: the persistent pair list.
  struct ProxyPair {
    std::uint32_t user_a, user_b;  // user_a < user_b
    int proxy_a, proxy_b;          // the proxies of user_a and user_b
    bool operator<(const ProxyPair& o) const {
      if (user_a != o.user_a) return user_a < o.user_a;
      if (user_b != o.user_b) return user_b < o.user_b;
      if (proxy_a != o.proxy_a) return proxy_a < o.proxy_a;
      return proxy_b < o.proxy_b;
    }
  };

  // A depth-first stack: inline for any tree of sane height (an AVL-balanced tree of 2^32 leaves is
  // under 48 high), spilling to the heap only beyond.
  class Stack {
   public:
    void push(int i) {
      if (size_ < int(inline_.size())) {
        inline_[size_] = i;
      } else {
        spill_.push_back(i);
      }
      ++size_;
    }
    int pop() {
      --size_;
      if (size_ < int(inline_.size())) return inline_[size_];
      const int i = spill_.back();
      spill_.pop_back();
      return i;
    }
    bool empty() const { return size_ == 0; }

   private:
    std::array<int, 128> inline_{};
    std::vector<int> spill_;
    int size_ = 0;
  };

  template <class F>
  void query_impl(const Aabb<N>& box, F& callback, std::int64_t* tests) const {
    if (root_ == kNull) return;
    Stack stack;
    stack.push(root_);
    while (!stack.empty()) {
      const int i = stack.pop();
      const Node& n = nodes_[i];
      if (tests) ++*tests;
      if (!overlaps(n.box, box)) continue;
      if (n.leaf()) {
        if constexpr (std::is_same_v<std::invoke_result_t<F&, int>, bool>) {
          if (!callback(i)) return;
        } else {
          callback(i);
        }
      } else {
        // child2 first, so child1's subtree is visited first.
        stack.push(n.child2);
        stack.push(n.child1);
      }
    }
  }

  int allocate_node();
  void free_node(int i);
  void insert_leaf(int leaf);
  void remove_leaf(int leaf);
  // Points `parent`'s link to old_child at new_child (the root if parent is kNull).
  void replace_child(int parent, int old_child, int new_child);
  // Recomputes heights and boxes from `start` up to the root, rotating where unbalanced.
  void refit_upwards(int start);
  int balance(int a);
  void require_proxy(int proxy, const char* what) const;
  void buffer_move(int proxy);
  Aabb<N> fat_box_for(const Aabb<N>& box, const Vec<N>& displacement) const;

  BroadPhaseSettings settings_;
  std::vector<Node> nodes_;
  int root_ = kNull;
  int free_list_ = kNull;
  int proxy_count_ = 0;
  std::vector<int> move_buffer_;  // proxies created or re-inserted since update_pairs; kNull if destroyed
  std::vector<ProxyPair> pairs_;  // every overlapping proxy pair as of the last update_pairs, sorted
  std::vector<Pair> user_pairs_;  // pairs_' user ids, without duplicates (pairs())
  bool destroyed_ = false;        // a proxy was destroyed since update_pairs
  std::vector<ProxyPair> new_pairs_;
  std::vector<ProxyPair> merged_;
  struct Candidate {
    int node;
    double inherited;  // the growth of the node's ancestors if the leaf is inserted below them
    double direct;     // cost(merged(node's box, leaf's box))
  };
  std::vector<Candidate> insert_stack_;  // insert_leaf's branch-and-bound stack, kept to avoid allocation
  std::int64_t node_overlap_tests_ = 0;
  int queried_proxies_ = 0;
};

}  // namespace wedge
