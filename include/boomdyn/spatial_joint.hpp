// The rows of the spatial joints and drives, on the spatial body interface
// (spatial_body.hpp), so that they hold on rigid bodies and beams alike:
//
//   position rows (3):  r_a(s_a) - r_b(s_b) = 0, or r_a(s_a) - p = 0 (ground)
//   offset rows (1 each): (r_a(s_a) - r_b(s_b)) . T_b c - base - f(t) = 0
//   dot rows (1 each):  u_a . v_b(t) = 0
//
// where u_a = T_a u' is a vector fixed in the section triad T_a of body a at
// s_a, and v_b(t) = T_b (-sin theta(t) n1' + cos theta(t) n2') one fixed in
// the triad of body b at s_b, or in the ground (T_b = I). A constant theta = 0
// gives the fixed vector n2'. A spherical joint is the position rows alone;
// a revolute joint adds two dot rows (the hinge axis of a normal to two
// vectors across the axis of b); a clamp three (the triads stay aligned); an
// angle drive is one dot row whose theta(t) turns the direction j(theta) in
// the plane (n1, n2) across the axis, so that the direction u_a of body a
// stays along i(theta) = cos theta n1 + sin theta n2.
//
// An offset row holds the component of the separation r_a - r_b along a
// vector c fixed in the triad of b (or the ground) at base + f(t): a
// cylindrical joint replaces the position rows by two offset rows across
// its axis (the point of a slides along a line fixed in b) and keeps the
// revolute joint's two dot rows; a prismatic joint adds the dot row that
// stops the rotation about the axis; a slide drive is an offset row along
// the axis with f(t) the prescribed displacement.
#pragma once

#include "boomdyn/constraint.hpp"
#include "boomdyn/spatial_body.hpp"
#include "boomdyn/time_function.hpp"

#include <vector>

namespace boomdyn {

// One end of a spatial joint: a material point of a body, or the ground
// (body null, point fixed).
struct SpatialEnd {
  const SpatialBody *body = nullptr;
  double s = 0;
  SpatialLocation loc;
  Vec3 point = Vec3::Zero(); // ground ends: the ground point
  static SpatialEnd onBody(const SpatialBody &body, double s)
  {
    SpatialEnd e;
    e.body = &body, e.s = s, e.loc = body.locate(s);
    return e;
  }
  static SpatialEnd ground(const Vec3 &point)
  {
    SpatialEnd e;
    e.point = point;
    return e;
  }
};

struct SpatialDotRow {
  Vec3 u;               // in a's section axes
  Vec3 n1, n2;          // in b's section axes (ground: global axes)
  TimeFunction theta;   // constant 0 unless the row is a drive
  const char *unit = "rad";
};

struct SpatialOffsetRow {
  Vec3 c;                // in b's section axes (ground: global axes)
  double base = 0;       // the value of the separation's component at f = 0
  TimeFunction shift;    // f(t): constant 0 unless the row is a drive
};

class SpatialJoint : public Constraint {
public:
  // Rows in order: position (3, if `position`), `offsets`, `rows`. `driven`:
  // some theta(t) or f(t) is not constant.
  SpatialJoint(std::string name, SpatialEnd a, SpatialEnd b, bool position, std::vector<SpatialOffsetRow> offsets,
               std::vector<SpatialDotRow> rows, bool driven = false);
  SpatialJoint(std::string name, SpatialEnd a, SpatialEnd b, bool position, std::vector<SpatialDotRow> rows,
               bool driven = false)
    : SpatialJoint(std::move(name), std::move(a), std::move(b), position, {}, std::move(rows), driven)
  {
  }
  std::string name() const override { return name_; }
  int numRows() const override
  {
    return (position_ ? 3 : 0) + static_cast<int>(offsets_.size() + rows_.size());
  }
  void coordinates(std::vector<PetscInt> &dofs) const override;
  void evaluate(double t, const double *q, const double *v, const double *w, ConstraintEval &out) const override;
  bool dependsOnTime() const override { return driven_; }
  void velocityBreakpoints(std::vector<double> &out) const override;
  void accelerationBreakpoints(std::vector<double> &out) const override;
  const char *rowUnit(int row) const override;

private:
  std::string name_;
  SpatialEnd a_, b_;
  bool position_;
  std::vector<SpatialOffsetRow> offsets_;
  std::vector<SpatialDotRow> rows_;
  bool driven_;
};

// Two unit vectors that make (n1, n2, axis/|axis|) a right-handed
// orthonormal frame, n1 along the part of `hint` normal to the axis (or any
// normal when hint is parallel to it).
void frameAcross(const Vec3 &axis, const Vec3 &hint, Vec3 &n1, Vec3 &n2);

} // namespace boomdyn
