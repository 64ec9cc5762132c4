// A sparse pattern rebuilt from another's entries (permuted, or a part of
// it), each entry remembering which of the other's values it takes: how
// core/sparse_cholesky.cpp and core/split_cholesky.cpp hand the caller's
// values to the CHOLMOD systems they factor (a copy per factorisation, by
// index, with no search).
#pragma once

#include <array>
#include <vector>

namespace ashlar {

// A pattern in compressed columns (rows ascending in each column) with,
// for each entry, the index of the value it takes in another pattern.
struct SourcedPattern {
  std::vector<int> column_starts, row_indices, sources;
};

// Entry {column, row, source} triples of an n x n pattern into compressed
// columns: bucketed by column, then each column sorted by row.
SourcedPattern compress_columns(int n, const std::vector<std::array<int, 3>>& entries);

}  // namespace ashlar
