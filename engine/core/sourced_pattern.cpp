#include "core/sourced_pattern.hpp"

#include <algorithm>
#include <utility>

namespace ashlar {

SourcedPattern compress_columns(int n, const std::vector<std::array<int, 3>>& entries) {
  SourcedPattern out;
  out.column_starts.assign(n + 1, 0);
  for (const auto& entry : entries) ++out.column_starts[entry[0] + 1];
  for (int j = 0; j < n; ++j) out.column_starts[j + 1] += out.column_starts[j];
  std::vector<std::pair<int, int>> placed(entries.size());  // (row, source)
  std::vector<int> next(out.column_starts.begin(), out.column_starts.end() - 1);
  for (const auto& [column, row, source] : entries) placed[next[column]++] = {row, source};
  out.row_indices.resize(entries.size());
  out.sources.resize(entries.size());
  for (int j = 0; j < n; ++j) {
    std::sort(placed.begin() + out.column_starts[j], placed.begin() + out.column_starts[j + 1]);
  }
  for (size_t k = 0; k < placed.size(); ++k) {
    out.row_indices[k] = placed[k].first;
    out.sources[k] = placed[k].second;
  }
  return out;
}

}  // namespace ashlar
