#include "boomdyn/slider_tracker.hpp"

#include "boomdyn/model.hpp"

#include <cmath>
#include <sstream>

namespace boomdyn {

PetscErrorCode SliderTracker::setUp(Vec layout)
{
  PetscFunctionBeginUser;
  std::vector<PetscInt> idx;
  for (const PostStepHook &h : assembler_.model().postStepHooks()) idx.insert(idx.end(), h.watched.begin(), h.watched.end());
  // Every rank receives every watched value, so that all ranks take the same decisions.
  IS is;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(idx.size()), idx.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(idx.size()), slacks_.address()));
  PetscCall(VecScatterCreate(layout, is, slacks_, nullptr, scatter_.address()));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

PetscErrorCode SliderTracker::update(Vec x, double t, bool *relocated, std::string *offTrack)
{
  const PetscScalar *values;
  PetscFunctionBeginUser;
  *relocated = false;
  offTrack->clear();
  if (!active()) PetscFunctionReturn(0);
  PetscCall(VecScatterBegin(scatter_, x, slacks_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter_, x, slacks_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(slacks_, &values));
  std::size_t offset = 0;
  for (const PostStepHook &h : assembler_.model().postStepHooks()) {
    bool changed = false;
    PetscCall(h.afterStep(values + offset, t, &changed, offTrack));
    offset += h.watched.size();
    if (!offTrack->empty()) break;
    *relocated = *relocated || changed;
  }
  PetscCall(VecRestoreArrayRead(slacks_, &values));
  if (*relocated && offTrack->empty()) PetscCall(assembler_.rebuildPattern());
  PetscFunctionReturn(0);
}

std::vector<double> SliderTracker::locations() const
{
  std::vector<double> s;
  for (const PostStepHook &h : assembler_.model().postStepHooks()) s.push_back(h.location());
  return s;
}

PetscErrorCode SliderTracker::setLocations(const std::vector<double> &s)
{
  PetscFunctionBeginUser;
  const auto &hooks = assembler_.model().postStepHooks();
  PetscCheck(s.size() == hooks.size(), assembler_.comm(), PETSC_ERR_FILE_UNEXPECTED,
             "restart file has %zu sliding joint locations, the scene %zu", s.size(), hooks.size());
  for (std::size_t k = 0; k < hooks.size(); ++k) hooks[k].setLocation(s[k]);
  if (!hooks.empty()) PetscCall(assembler_.rebuildPattern());
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
