// The event method's exponentials exp(M h0 / 2^j), one per mode and step level, kept within a
// byte budget: past it the least recently used one is dropped (and recomputed if it is needed
// again). Unbounded, 200 half-wave rectifiers on one source held 3.4 GB of them.
#pragma once

#include <cstddef>
#include <functional>
#include <list>
#include <unordered_map>
#include <utility>

#include <Eigen/Dense>

namespace lcs {

class ExponentialCache {
 public:
  explicit ExponentialCache(std::size_t budget_bytes) : budget_(budget_bytes) {}

  // The matrix for (owner, level), computed by `compute` when it is not held. The reference is
  // valid until the next call.
  const Eigen::MatrixXd& get(const void* owner, int level, const std::function<Eigen::MatrixXd()>& compute) {
    const Key key{owner, level};
    auto it = entries_.find(key);
    if (it != entries_.end()) {
      order_.splice(order_.begin(), order_, it->second.position);
      return it->second.matrix;
    }
    Eigen::MatrixXd matrix = compute();
    const std::size_t size = bytes(matrix);
    // The one being added always stays, even alone above the budget.
    while (held_ + size > budget_ && !order_.empty()) {
      auto last = entries_.find(order_.back());
      held_ -= bytes(last->second.matrix);
      entries_.erase(last);
      order_.pop_back();
      ++evictions_;
    }
    order_.push_front(key);
    held_ += size;
    peak_ = std::max(peak_, held_);
    return entries_.emplace(key, Entry{std::move(matrix), order_.begin()}).first->second.matrix;
  }

  // The matrix for (owner, level) if it is held (then it becomes the most recently used), else
  // null. The pointer is valid until the next get or drop.
  const Eigen::MatrixXd* find(const void* owner, int level) {
    auto it = entries_.find(Key{owner, level});
    if (it == entries_.end()) return nullptr;
    order_.splice(order_.begin(), order_, it->second.position);
    return &it->second.matrix;
  }

  // Drops every matrix of `owner` (a mode that is itself dropped: its address may be reused).
  void drop(const void* owner) {
    for (auto it = order_.begin(); it != order_.end();) {
      if (it->owner != owner) {
        ++it;
        continue;
      }
      auto entry = entries_.find(*it);
      held_ -= bytes(entry->second.matrix);
      entries_.erase(entry);
      it = order_.erase(it);
    }
  }

  void clear() {
    entries_.clear();
    order_.clear();
    held_ = 0;
  }

  std::size_t budget() const { return budget_; }
  std::size_t peak_bytes() const { return peak_; }
  long evictions() const { return evictions_; }

 private:
  struct Key {
    const void* owner;
    int level;
    bool operator==(const Key& o) const { return owner == o.owner && level == o.level; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<const void*>()(k.owner) * 131 + static_cast<std::size_t>(k.level);
    }
  };
  struct Entry {
    Eigen::MatrixXd matrix;
    std::list<Key>::iterator position;
  };
  static std::size_t bytes(const Eigen::MatrixXd& m) {
    return static_cast<std::size_t>(m.size()) * sizeof(double);
  }

  std::size_t budget_;
  std::size_t held_ = 0, peak_ = 0;
  long evictions_ = 0;
  std::list<Key> order_;  // most recently used first
  std::unordered_map<Key, Entry, KeyHash> entries_;
};

}  // namespace lcs
