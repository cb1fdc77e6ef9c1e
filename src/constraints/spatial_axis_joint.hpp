// The geometry shared by the spatial joints about an axis (revolute_joint,
// cylindrical_joint, prismatic_joint): the two ends, the axis and two
// directions across it at t = 0, and the rows of spatial_joint.hpp built
// from them, so that every joint type states only which rows it takes.
#pragma once

#include "boomdyn/component_spec.hpp"
#include "boomdyn/physics_type.hpp"
#include "boomdyn/spatial_joint.hpp"

#include <optional>

namespace boomdyn {

class ModelBuilder;

struct AxisJointFrame {
  SpatialEnd a, other;           // body (at) and the other body (other_at) or the ground
  Vec3 axis, n1, n2;             // right-handed (n1, n2, axis), global axes at t = 0
  Mat3 Ta, Tb;                   // initial triads of the two ends (ground: identity)
  Vec3 ra = Vec3::Zero(), rb = Vec3::Zero(); // initial positions of the two ends
};

// From the keys body, at, other, other_at, axis and (ground ends) point; a
// ground end without `point` lies where the material point of `body` starts.
// n1 is the part of the section x axis of `body` across the axis.
AxisJointFrame axisJointFrame(const ComponentSpec &spec, const ModelBuilder &builder);

// The two dot rows that keep the axis common: the axis fixed in a stays
// normal to n1 and n2 fixed in the other end.
std::vector<SpatialDotRow> axisAlignmentRows(const AxisJointFrame &f);
// The dot row that stops the rotation about the axis: n1 fixed in a stays
// normal to n2 fixed in the other end.
SpatialDotRow axisRollRow(const AxisJointFrame &f);
// The offset row that holds the separation's component along `direction`
// (global at t = 0, fixed in the other end) at its initial value plus f(t).
SpatialOffsetRow axisOffsetRow(const AxisJointFrame &f, const Vec3 &direction,
                               const TimeFunction &shift = TimeFunction::constant(0.0));

// The type of a joint whose point slides along the axis (cylindrical_joint,
// and with `roll` prismatic_joint): two offset rows across the axis, the
// optional slide drive (key `slide`) along it, the two alignment rows and
// with `roll` the roll row, in that order.
PhysicsType axisSliderType(const std::string &type, const std::string &summary, bool roll);

// The check of `axis` shared by the types: not the zero vector.
std::optional<SpecIssue> checkJointAxis(const ComponentSpec &spec, const Scene &scene);

} // namespace boomdyn
