#include "boomdyn/partition.hpp"

#include <metis.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <stdexcept>

namespace boomdyn {

namespace {

// All unknowns (coordinates, then multiplier rows) each item touches.
std::vector<std::vector<PetscInt>> itemUnknowns(const Model &model)
{
  std::vector<std::vector<PetscInt>> lists;
  std::vector<PetscInt> coords, rows;
  for (const auto &item : model.items()) {
    item->coordinates(coords);
    item->multiplierRows(rows);
    coords.insert(coords.end(), rows.begin(), rows.end());
    lists.push_back(coords);
  }
  return lists;
}

// Items that share an unknown with item k, for every k (CSR).
void itemGraph(const std::vector<std::vector<PetscInt>> &lists, PetscInt unknowns, std::vector<idx_t> &xadj,
               std::vector<idx_t> &adjncy)
{
  std::vector<std::vector<int>> itemsOf(unknowns);
  for (std::size_t k = 0; k < lists.size(); ++k)
    for (PetscInt u : lists[k]) itemsOf[u].push_back(static_cast<int>(k));
  xadj.assign(1, 0);
  adjncy.clear();
  for (std::size_t k = 0; k < lists.size(); ++k) {
    std::set<int> neighbours;
    for (PetscInt u : lists[k])
      for (int other : itemsOf[u])
        if (other != static_cast<int>(k)) neighbours.insert(other);
    adjncy.insert(adjncy.end(), neighbours.begin(), neighbours.end());
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
  }
}

} // namespace

std::vector<int> contiguousPartition(const Model &model, int parts)
{
  // PETSC_DECIDE: n / P unknowns per rank, the remainder to the first ranks.
  const PetscInt n = model.size();
  std::vector<PetscInt> start(parts + 1, 0);
  for (int p = 0; p < parts; ++p) start[p + 1] = start[p] + n / parts + (p < n % parts ? 1 : 0);
  std::vector<int> part;
  std::vector<PetscInt> coords;
  for (const auto &item : model.items()) {
    item->coordinates(coords);
    part.push_back(static_cast<int>(std::upper_bound(start.begin(), start.end(), coords[0]) - start.begin()) - 1);
  }
  return part;
}

std::vector<int> metisPartition(const Model &model, int parts)
{
  const auto lists = itemUnknowns(model);
  std::vector<idx_t> xadj, adjncy;
  itemGraph(lists, model.size(), xadj, adjncy);
  idx_t nvtxs = static_cast<idx_t>(lists.size()), ncon = 1, nparts = parts, objval = 0;
  std::vector<idx_t> part(nvtxs, 0);
  if (parts > 1 && nvtxs > 0) {
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1; // reproducible
    const int status = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr,
                                           &nparts, nullptr, nullptr, options, &objval, part.data());
    if (status != METIS_OK) throw std::runtime_error("METIS_PartGraphKway failed (status " + std::to_string(status) + ")");
  }
  return std::vector<int>(part.begin(), part.end());
}

PartitionQuality evaluatePartition(const Model &model, const std::vector<int> &part, int parts, const std::string &method)
{
  const auto lists = itemUnknowns(model);
  PartitionQuality q;
  q.method = method;
  q.itemsPerPart.assign(parts, 0);
  q.unknownsPerPart.assign(parts, 0);
  std::vector<int> firstPart(model.size(), -1);
  std::vector<char> shared(model.size(), 0);
  for (std::size_t k = 0; k < lists.size(); ++k) {
    ++q.itemsPerPart[part[k]];
    for (PetscInt u : lists[k]) {
      if (firstPart[u] < 0) firstPart[u] = part[k];
      else if (firstPart[u] != part[k]) shared[u] = 1;
    }
  }
  for (PetscInt u = 0; u < model.size(); ++u) {
    if (firstPart[u] >= 0) ++q.unknownsPerPart[firstPart[u]];
    q.interfaceUnknowns += shared[u];
  }
  std::vector<idx_t> xadj, adjncy;
  itemGraph(lists, model.size(), xadj, adjncy);
  for (std::size_t k = 0; k < lists.size(); ++k)
    for (idx_t e = xadj[k]; e < xadj[k + 1]; ++e)
      if (static_cast<std::size_t>(adjncy[e]) > k && part[adjncy[e]] != part[k]) ++q.cutEdges;
  const double mean = static_cast<double>(lists.size()) / parts;
  q.imbalance = *std::max_element(q.itemsPerPart.begin(), q.itemsPerPart.end()) / mean;
  return q;
}

} // namespace boomdyn
