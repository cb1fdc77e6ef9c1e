#include "boomdyn/slider_tracker.hpp"

#include "boomdyn/model.hpp"

#include <cmath>
#include <sstream>

namespace boomdyn {

SliderTracker::~SliderTracker()
{
  if (scatter_) (void)VecScatterDestroy(&scatter_);
  if (slacks_) (void)VecDestroy(&slacks_);
}

PetscErrorCode SliderTracker::setUp(Vec layout)
{
  PetscFunctionBeginUser;
  std::vector<PetscInt> idx;
  for (const auto &j : assembler_.model().slidingJoints()) idx.push_back(j->slackIndex());
  // Every rank receives every slack value, so that all ranks take the same decisions.
  IS is;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(idx.size()), idx.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(idx.size()), &slacks_));
  PetscCall(VecScatterCreate(layout, is, slacks_, nullptr, &scatter_));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

PetscErrorCode SliderTracker::update(Vec x, double t, bool *relocated, std::string *offTrack)
{
  const PetscScalar *s;
  PetscFunctionBeginUser;
  *relocated = false;
  offTrack->clear();
  if (!active()) PetscFunctionReturn(0);
  PetscCall(VecScatterBegin(scatter_, x, slacks_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter_, x, slacks_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(slacks_, &s));
  const auto &joints = assembler_.model().slidingJoints();
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (!joints[k]->onTrack(s[k])) {
      std::ostringstream os;
      os << "sliding joint '" << joints[k]->name() << "' left its track '" << joints[k]->track().name()
         << "' at t = " << t << " s (s = " << s[k] << " m, track length " << joints[k]->track().length() << " m)";
      *offTrack = os.str();
      break;
    }
    if (joints[k]->relocate(s[k])) {
      *relocated = true;
      PetscCall(PetscInfo(nullptr, "t = %g s: sliding joint '%s' moves to element %d of '%s' (s = %.12g m)\n", t,
                          joints[k]->name().c_str(), joints[k]->trackLocation().element, joints[k]->track().name().c_str(), s[k]));
    }
  }
  PetscCall(VecRestoreArrayRead(slacks_, &s));
  if (*relocated && offTrack->empty()) PetscCall(assembler_.rebuildPattern());
  PetscFunctionReturn(0);
}

std::vector<double> SliderTracker::locations() const
{
  std::vector<double> s;
  for (const auto &j : assembler_.model().slidingJoints()) s.push_back(j->trackLocation().s);
  return s;
}

PetscErrorCode SliderTracker::setLocations(const std::vector<double> &s)
{
  PetscFunctionBeginUser;
  const auto &joints = assembler_.model().slidingJoints();
  PetscCheck(s.size() == joints.size(), assembler_.comm(), PETSC_ERR_FILE_UNEXPECTED,
             "restart file has %zu sliding joint locations, the scene %zu", s.size(), joints.size());
  for (std::size_t k = 0; k < joints.size(); ++k) joints[k]->setTrackLocation(s[k]);
  if (!joints.empty()) PetscCall(assembler_.rebuildPattern());
  PetscFunctionReturn(0);
}

std::string contactsNearTrackEnds(const Model &model, const std::vector<double> &slacks, double margin)
{
  std::ostringstream os;
  const auto &joints = model.slidingJoints();
  for (std::size_t k = 0; k < joints.size() && k < slacks.size(); ++k) {
    const double length = joints[k]->track().length(), s = slacks[k];
    const double gap = std::min(std::abs(s), std::abs(length - s));
    if (gap > margin * length) continue;
    os << (os.tellp() > 0 ? "; " : "") << "sliding joint '" << joints[k]->name() << "' at s = " << s << " m, " << gap
       << " m from the " << (std::abs(s) < std::abs(length - s) ? "start" : "end") << " of its track '"
       << joints[k]->track().name() << "' (" << length << " m)";
  }
  return os.str();
}

} // namespace boomdyn
