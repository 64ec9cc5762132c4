// Disjoint sets over 0..n-1: which items a chain of links joins (blocks by
// contacts, faces by shared edges).
#pragma once

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
  void join(int a, int b) { parent_[root(a)] = root(b); }

private:
  std::vector<int> parent_;
};

}  // namespace ashlar
