// Shared pieces of the micro-benchmarks: a representative dynamic assembly
// context, models built through the library's own scene → Model path, and
// the values a work item sees at a deformed state (gathered once, outside
// the timed loops).
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/scene_reader.hpp"
#include "boomdyn/work_item.hpp"

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace boomdyn::bench {

// Generalized-α iteration at h = 1e-3 (beta' = 1/(beta h^2), gamma' = gamma/(beta h),
// backward Euler for first-order states), multipliers scaled.
inline AssemblyContext dynamicContext()
{
  AssemblyContext ctx;
  ctx.t = 0.1;
  const double h = 1e-3, beta = 0.3025, gamma = 0.6;
  ctx.kin.cQ = 1.0;
  ctx.kin.cV = gamma / (beta * h);
  ctx.kin.cA = 1.0 / (beta * h * h);
  ctx.kin.cZ = 1.0 / h;
  ctx.sigma = 1e6;
  return ctx;
}

// A global state x = [q | lambda] and its rates: the model's initial
// coordinates with a small pseudo-random deformation (`size`, 1e-3 by
// default: a few per mille of the entries' scale on elements of 0.1 m),
// random velocities and accelerations, nonzero multipliers.
struct GlobalState {
  std::vector<double> q, v, a, x; // q, v, a: coordinates; x: whole unknown vector (multipliers at the end)
};

inline GlobalState deformedState(const Model &model, unsigned seed = 1, double size = 1e-3)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  GlobalState s;
  s.q = model.initialCoordinates();
  const std::size_t nq = s.q.size();
  for (double &qi : s.q) qi += size * u(rng);
  // Keep the slack coordinates of sliding joints where they were (inside their element).
  const std::vector<double> q0 = model.initialCoordinates();
  for (const auto &j : model.slidingJoints()) s.q[j->slackIndex()] = q0[j->slackIndex()] + 1e-4;
  s.v.resize(nq), s.a.resize(nq);
  for (std::size_t i = 0; i < nq; ++i) s.v[i] = 0.05 * u(rng), s.a[i] = u(rng);
  s.x.assign(model.size(), 0.0);
  for (std::size_t i = 0; i < nq; ++i) s.x[i] = s.q[i];
  for (PetscInt i = model.numCoordinates(); i < model.size(); ++i) s.x[i] = 1e-3 * (1.5 + u(rng));
  return s;
}

// The values one work item sees (coordinates, then multiplier rows), in the
// layout of ItemValues, plus residual and Jacobian buffers of its size.
struct ItemBuffers {
  const WorkItem *item = nullptr;
  std::vector<double> q, v, a, lambda, residual, J;
  ItemValues values() const
  {
    ItemValues in;
    in.q = q.data(), in.v = v.data(), in.a = a.data(), in.lambda = lambda.data();
    return in;
  }
  int size() const { return static_cast<int>(residual.size()); }
};

inline ItemBuffers gatherItem(const WorkItem &item, const GlobalState &s)
{
  ItemBuffers b;
  b.item = &item;
  std::vector<PetscInt> dofs, rows;
  item.coordinates(dofs);
  item.multiplierRows(rows);
  for (PetscInt d : dofs) b.q.push_back(s.q[d]), b.v.push_back(s.v[d]), b.a.push_back(s.a[d]);
  for (PetscInt r : rows) b.lambda.push_back(s.x[r]);
  if (b.lambda.empty()) b.lambda.push_back(0.0); // a valid pointer for items without rows
  const std::size_t n = dofs.size() + rows.size();
  b.residual.assign(n, 0.0);
  b.J.assign(n * n, 0.0);
  return b;
}

inline Scene sceneFromFile(const std::string &relativePath)
{
  return readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/" + relativePath);
}

} // namespace boomdyn::bench
