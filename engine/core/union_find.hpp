// Disjoint sets over 0..n-1: which items a chain of links joins (blocks by
// contacts, faces by shared edges, welded design nodes). Each set's root is
// its smallest item, whatever the order of the joins.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace ashlar {

class UnionFind {
public:
  explicit UnionFind(std::size_t count) : parent_(count) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int root(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // True when a and b were in different sets.
  bool join(int a, int b) {
    a = root(a);
    b = root(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

private:
  std::vector<int> parent_;
};

}  // namespace ashlar
