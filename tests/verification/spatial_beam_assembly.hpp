// A small dense assembly of spatial beam elements (docs/model.md §1.7) for the
// verification tests: a straight cantilever along x, clamped at node 0 by
// removing the node's position, the lateral components of its slope and its
// twist (the clamp fixes the tangent's direction, not its length, as the
// planar clamp: fixing |r'| too would hold the axial strain at the root at
// zero and cost the axial modes their convergence), with the nodes' reference triads kept by
// the beam and rebased after every load step (what a spatial body will do).
// The pipeline tests later repeat these cases through scenes.
#pragma once

#include "boomdyn/spatial_beam_element.hpp"

#include <Eigen/Dense>

#include <vector>

namespace boomdyn::spatial_beam::verification {

struct Cantilever {
  Section sec;
  double L = 1.0;
  int elements = 1;
  std::vector<NodeFrame> frames; // one per node
  Eigen::VectorXd q;             // 7 per node

  // Along the first column of triad (the x axis by default), node references
  // equal to triad. clampStretch: the clamp fixes the whole slope r'_0 (for a
  // beam not along x, where fixing only its direction would not be linear).
  bool clampStretch = false;
  Cantilever(const Section &s, double length, int n, const Mat3 &triad = Mat3::Identity(), bool clampWholeSlope = false)
      : sec(s), L(length), elements(n), frames(n + 1, NodeFrame{triad.col(0), triad.col(1)}), clampStretch(clampWholeSlope)
  {
    sec.length = length;
    q.setZero(kNodeCoordinates * (n + 1));
    for (int a = 0; a <= n; ++a) {
      q.segment<3>(kNodeCoordinates * a) = (length * a / n) * triad.col(0);
      q.segment<3>(kNodeCoordinates * a + 3) = triad.col(0);
    }
  }
  double l() const { return L / elements; }
  int size() const { return static_cast<int>(q.size()); }
  // Coordinates left by the clamp: node 0's slope along x and every other node's.
  std::vector<int> freeIndices() const
  {
    std::vector<int> free;
    if (!clampStretch) free.push_back(slopeIndex(0));
    for (int i = kNodeCoordinates; i < size(); ++i) free.push_back(i);
    return free;
  }
  Geometry geometry(int i) const { return {l(), {frames[i], frames[i + 1]}}; }
  Vec14 element(int i) const { return q.segment<kCoordinates>(kNodeCoordinates * i); }

  // Internal force and tangent over all coordinates.
  void internal(Eigen::VectorXd &f, Eigen::MatrixXd &K) const
  {
    f.setZero(size());
    K.setZero(size(), size());
    for (int i = 0; i < elements; ++i) {
      Vec14 fe;
      Mat14 Ke;
      internalForce(sec, geometry(i), element(i), fe, &Ke);
      f.segment<kCoordinates>(kNodeCoordinates * i) += fe;
      K.block<kCoordinates, kCoordinates>(kNodeCoordinates * i, kNodeCoordinates * i) += Ke;
    }
  }
  Eigen::MatrixXd mass() const
  {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(size(), size());
    for (int i = 0; i < elements; ++i)
      M.block<kCoordinates, kCoordinates>(kNodeCoordinates * i, kNodeCoordinates * i) += massMatrix(sec, l());
    return M;
  }
  // Reference triads onto the current tangents (the same twists, the same state).
  void rebase()
  {
    for (int a = 0; a <= elements; ++a) frames[a] = rebasedNodeFrame(frames[a], q.segment<3>(kNodeCoordinates * a + 3));
  }
  Vec3 tip() const { return q.segment<3>(kNodeCoordinates * elements); }
};

// The tip moment's generalized force and its derivative (sectionMomentForce).
inline void tipMoment(const Cantilever &b, const Vec3 &M, Vec14 &Q, Mat14 &dQ)
{
  const int last = b.elements - 1;
  sectionMomentForce(b.geometry(last), b.element(last), 1.0, M, Q, &dQ);
}

// Static equilibrium under a tip moment growing linearly to M in `steps`
// load steps, Newton on the free coordinates, references rebased after each
// step. Returns false if a step does not converge.
inline bool solveTipMoment(Cantilever &b, const Vec3 &M, int steps)
{
  const std::vector<int> free = b.freeIndices();
  const int tipOffset = kNodeCoordinates * (b.elements - 1);
  for (int s = 1; s <= steps; ++s) {
    const Vec3 Ms = M * (double(s) / steps);
    bool converged = false;
    for (int it = 0; it < 30 && !converged; ++it) {
      Eigen::VectorXd f;
      Eigen::MatrixXd K;
      b.internal(f, K);
      Vec14 Q;
      Mat14 dQ;
      tipMoment(b, Ms, Q, dQ);
      f.segment<kCoordinates>(tipOffset) -= Q;
      K.block<kCoordinates, kCoordinates>(tipOffset, tipOffset) -= dQ;
      const Eigen::MatrixXd Kf = K(free, free);
      const Eigen::VectorXd ff = f(free);
      const Eigen::VectorXd dq = Kf.partialPivLu().solve(-ff);
      b.q(free) += dq;
      converged = dq.norm() < 1e-13 * (1.0 + b.q.norm());
    }
    if (!converged) return false;
    b.rebase();
  }
  return true;
}

} // namespace boomdyn::spatial_beam::verification
