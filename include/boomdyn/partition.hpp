// Quality of a distribution of the work items over P ranks: the contiguous
// split boomdyn uses (unknowns in equal contiguous blocks, each item on the
// rank owning its first unknown) against a METIS k-way partition of the item
// graph (items adjacent when they share an unknown). Reported by
// `boomdyn SCENE -boom_partition_report P` (docs/performance.md, "Several
// ranks").
#pragma once

#include "boomdyn/model.hpp"

#include <string>
#include <vector>

namespace boomdyn {

struct PartitionQuality {
  std::string method;
  std::vector<int> itemsPerPart;   // work items (elements, constraints, forces) per part
  std::vector<int> unknownsPerPart; // unknowns owned per part (for METIS: by the part of their first item)
  int interfaceUnknowns = 0;       // unknowns touched by items of more than one part (the Schur complement size)
  int cutEdges = 0;                // item pairs in different parts that share an unknown
  double imbalance = 0;            // largest part's items / mean
};

// The item of index k goes to part[k]. Unknowns: model coordinates and multiplier rows.
PartitionQuality evaluatePartition(const Model &model, const std::vector<int> &part, int parts, const std::string &method);
std::vector<int> contiguousPartition(const Model &model, int parts);
std::vector<int> metisPartition(const Model &model, int parts);

} // namespace boomdyn
