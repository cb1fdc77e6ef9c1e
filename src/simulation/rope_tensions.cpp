#include "boomdyn/rope_tensions.hpp"

#include "boomdyn/rope.hpp"

#include <algorithm>

namespace boomdyn {

RopeTensions::RopeTensions(const Model &model)
{
  for (const ConstraintItem *c : model.constraints())
    if (dynamic_cast<const Rope *>(&c->constraint())) rows_.push_back({c->name(), c->firstRow() - model.numCoordinates()});
}

PetscErrorCode RopeTensions::update(MPI_Comm comm, double t, const std::vector<double> &multipliers,
                                    std::vector<double> &tensions)
{
  PetscFunctionBeginUser;
  tensions.clear();
  bool slack = false;
  std::string which;
  for (const auto &[name, row] : rows_)
    if (!multipliers.empty()) {
      tensions.push_back(-multipliers[row]);
      if (tensions.back() < 0 && !slack) slack = true, which = name;
    }
  int flag = slack;
  PetscCallMPI(MPI_Bcast(&flag, 1, MPI_INT, 0, comm));
  if (flag && slackSteps_++ == 0)
    PetscCall(PetscPrintf(comm, "warning: rope '%s' would have to push at t = %g s (tension %g N): the rope "
                          "is slack there; counted in /summary/slack_rope_steps\n", which.c_str(), t,
                          tensions.empty() ? 0.0 : *std::min_element(tensions.begin(), tensions.end())));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
