#include "boomdyn/rope_tensions.hpp"


#include <algorithm>

namespace boomdyn {

RopeTensions::RopeTensions(const Model &model)
{
  // The channels of group "rope" that its type adds when it is built (rope_type.cpp).
  for (const OutputChannel &ch : model.outputChannels())
    if (ch.group == "rope") ropes_.push_back(ch);
}

PetscErrorCode RopeTensions::update(MPI_Comm comm, double t, const std::vector<double> &multipliers,
                                    std::vector<double> &tensions)
{
  PetscFunctionBeginUser;
  tensions.clear();
  bool slack = false;
  std::string which;
  for (const OutputChannel &rope : ropes_)
    if (!multipliers.empty()) {
      tensions.push_back(rope.factor * multipliers[rope.index]);
      if (tensions.back() < 0 && !slack) slack = true, which = rope.name;
    }
  int flag = slack;
  PetscCallMPI(MPI_Bcast(&flag, 1, MPI_INT, 0, comm));
  if (flag && slackSteps_++ == 0)
    PetscCall(PetscPrintf(comm, "note: rope '%s' carries %g N < 0 at t = %g s: the inextensible rope stands for an "
                          "extension/retraction rope pair, and here the retraction rope pulls (the extension rope is "
                          "slack); such steps are counted in /summary/slack_rope_steps\n", which.c_str(),
                          tensions.empty() ? 0.0 : *std::min_element(tensions.begin(), tensions.end()), t));
  PetscFunctionReturn(0);
}

} // namespace boomdyn
