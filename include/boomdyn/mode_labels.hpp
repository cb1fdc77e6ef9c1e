// Energy-split labels of modes (docs/model.md §5, "Mode labels"): the share
// of a mode's strain energy 1/2 s^T K s in each kind (WorkItem::modeEnergy:
// axial, in-plane and out-of-plane bending, torsion of beams; springs,
// ropes, contacts, hydraulic cylinders, friction; the geometric rest), K
// being the eigen-analysis' stiffness at the state. The label is the
// largest share's kind with its share, e.g. "torsion 0.99".
#pragma once

#include "boomdyn/assembler.hpp"

#include <array>
#include <string>
#include <vector>

namespace boomdyn {

// Shares in the order of ModeEnergyKind; they sum to 1 (a negative share:
// that kind softens the mode, e.g. the geometric part of a compressed boom).
using EnergyShares = std::array<double, kModeEnergyKinds>;

// The shares of a mode (layout of x; its multiplier part ignored) at the
// pencil's state (t, q, lambda as for solveModes). sigma: the pencil's
// constraint scale (pencilState); 0 on entry: computed and returned, so that
// the modes of one state share it. Collective; all ranks get the shares.
PetscErrorCode modeEnergyShares(Assembler &assembler, double t, Vec q, Vec lambda, Vec mode, EnergyShares *shares,
                                double *sigma);

// The kinds' names in the order of the shares (modeEnergyKindName).
std::vector<std::string> modeEnergyKindNames();

// "kind share" of the largest share (two decimals), e.g. "bending_in_plane 1.00".
std::string modeLabel(const EnergyShares &shares);

} // namespace boomdyn
