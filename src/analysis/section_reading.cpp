#include "boomdyn/section_reading.hpp"

#include "boomdyn/spatial_beam_kinematics.hpp"

namespace boomdyn {

double sectionTwist(const Mat3 &initial, const Mat3 &current)
{
  // The smallest rotation from the initial axis to the current one takes
  // the initial triad to the zero-twist triad: the beam element's node
  // triad with the initial triad as its reference (spatial_beam_kinematics.hpp).
  return spatial_beam::twistFor(spatial_beam::NodeFrame{initial.col(0), initial.col(1)}, current.col(0), current.col(1));
}

SectionReading readSection(const SpatialBody &body, const SpatialLocation &loc, double s, const double *q,
                           const double *v)
{
  SpatialSample p;
  body.sample(loc, s, q, p);
  const Eigen::Map<const Eigen::VectorXd> rate(v, loc.count);
  SectionReading out;
  out.position = p.r;
  out.velocity = p.r_q.leftCols(loc.count) * rate;
  out.triad = p.triad;
  for (int k = 0; k < 3; ++k)
    out.angularVelocity += 0.5 * p.triad.col(k).cross(p.d_q[k].leftCols(loc.count) * rate);
  out.twist = sectionTwist(body.initialTriad(s), p.triad);
  out.strains = body.sectionStrains(loc, q);
  return out;
}

} // namespace boomdyn
