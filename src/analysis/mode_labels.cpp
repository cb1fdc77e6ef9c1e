#include "boomdyn/mode_labels.hpp"

#include "boomdyn/eigen_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace boomdyn {

PetscErrorCode modeEnergyShares(Assembler &assembler, double t, Vec q, Vec lambda, Vec mode, EnergyShares *shares,
                                double *sigma)
{
  PetscHandle<Vec> x;
  PetscFunctionBeginUser;
  PetscCall(assembler.createVector(x.address()));
  PetscCall(pencilState(assembler, q, lambda, x, sigma));
  AssemblyContext ctx;
  ctx.t = t;
  ctx.sigma = *sigma;
  ModeEnergy energy;
  PetscCall(assembler.modeEnergy(ctx, x, mode, &energy));
  // The shares of the total 1/2 s^T K s (= omega^2/2 s^T M s on a mode).
  double total = 0;
  for (double e : energy.kind) total += e;
  for (int k = 0; k < kModeEnergyKinds; ++k) (*shares)[k] = total != 0 ? energy.kind[k] / total : 0.0;
  PetscFunctionReturn(0);
}

std::vector<std::string> modeEnergyKindNames()
{
  std::vector<std::string> names;
  for (int k = 0; k < kModeEnergyKinds; ++k) names.push_back(modeEnergyKindName(k));
  return names;
}

std::string modeLabel(const EnergyShares &shares)
{
  const int k = static_cast<int>(std::max_element(shares.begin(), shares.end()) - shares.begin());
  char text[64];
  std::snprintf(text, sizeof text, "%s %.2f", modeEnergyKindName(k), shares[k]);
  return text;
}

} // namespace boomdyn
