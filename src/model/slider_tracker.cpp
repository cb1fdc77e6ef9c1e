#include "boomdyn/slider_tracker.hpp"

#include "boomdyn/model.hpp"

#include <cmath>
#include <sstream>

namespace boomdyn {

namespace {

// The hooks with changesChartOnly == chartOnly, on the watched values of x
// (scattered to every rank into slacks).
PetscErrorCode runHooks(const std::vector<PostStepHook> &hooks, VecScatter scatter, Vec slacks, Vec x, double t,
                        bool chartOnly, bool *changed, std::string *stop)
{
  const PetscScalar *values;
  PetscFunctionBeginUser;
  *changed = false;
  stop->clear();
  if (hooks.empty()) PetscFunctionReturn(0);
  PetscCall(VecScatterBegin(scatter, x, slacks, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, x, slacks, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(slacks, &values));
  std::size_t offset = 0;
  for (const PostStepHook &h : hooks) {
    bool hookChanged = false;
    if (h.changesChartOnly == chartOnly) PetscCall(h.afterStep(values + offset, t, &hookChanged, stop));
    offset += h.watched.size();
    if (!stop->empty()) break;
    *changed = *changed || hookChanged;
  }
  PetscCall(VecRestoreArrayRead(slacks, &values));
  PetscFunctionReturn(0);
}

} // namespace

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
  PetscFunctionBeginUser;
  PetscCall(runHooks(assembler_.model().postStepHooks(), scatter_, slacks_, x, t, false, relocated, offTrack));
  if (*relocated && offTrack->empty()) PetscCall(assembler_.rebuildPattern());
  PetscFunctionReturn(0);
}

PetscErrorCode SliderTracker::rechart(Vec x, double t)
{
  bool unusedChanged;
  std::string unusedStop; // a change of chart never stops a run
  PetscFunctionBeginUser;
  PetscCall(runHooks(assembler_.model().postStepHooks(), scatter_, slacks_, x, t, true, &unusedChanged, &unusedStop));
  PetscFunctionReturn(0);
}

std::vector<double> SliderTracker::locations() const
{
  std::vector<double> s;
  for (const PostStepHook &h : assembler_.model().postStepHooks())
    if (h.location) s.push_back(h.location());
  return s;
}

PetscErrorCode SliderTracker::setLocations(const std::vector<double> &s)
{
  PetscFunctionBeginUser;
  std::vector<const PostStepHook *> located;
  for (const PostStepHook &h : assembler_.model().postStepHooks())
    if (h.location) located.push_back(&h);
  PetscCheck(s.size() == located.size(), assembler_.comm(), PETSC_ERR_FILE_UNEXPECTED,
             "restart file has %zu sliding joint locations, the scene %zu", s.size(), located.size());
  for (std::size_t k = 0; k < located.size(); ++k) located[k]->setLocation(s[k]);
  if (!located.empty()) PetscCall(assembler_.rebuildPattern());
  PetscFunctionReturn(0);
}

std::vector<double> SliderTracker::states() const
{
  std::vector<double> values;
  for (const PostStepHook &h : assembler_.model().postStepHooks())
    if (h.state) {
      const std::vector<double> v = h.state();
      values.insert(values.end(), v.begin(), v.end());
    }
  return values;
}

PetscErrorCode SliderTracker::setStates(const std::vector<double> &values)
{
  PetscFunctionBeginUser;
  PetscCheck(values.size() == states().size(), assembler_.comm(), PETSC_ERR_FILE_UNEXPECTED,
             "restart file has %zu numbers of post-step state (beam node references), the scene %zu", values.size(),
             states().size());
  std::size_t offset = 0;
  for (const PostStepHook &h : assembler_.model().postStepHooks())
    if (h.state) {
      const std::size_t n = h.state().size();
      h.setState(values.data() + offset);
      offset += n;
    }
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
