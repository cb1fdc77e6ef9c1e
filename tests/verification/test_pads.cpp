// Compliant slide pads with clearance at sliding joints (docs/model.md §2.1,
// pad variant): the rigid limit against the bilateral joint, and a beam on
// two pads loaded transversely through zero against statics.
#include "support.hpp"

#include "boomdyn/pad_contact.hpp"

#include <cmath>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// Tip sensor and modes of a static run with its modal analysis.
class StaticModesRecorder : public Monitor {
public:
  StaticModesRecorder(Simulation &sim, double &tip, std::vector<double> &hz) : sim_(sim), tip_(tip), hz_(hz) {}
  PetscErrorCode modes(double, const ModalResult &m) override
  {
    hz_ = m.frequencyHz;
    return 0;
  }
  PetscErrorCode finish(const RunState &s, const RunOutcome &outcome) override
  {
    std::vector<SensorReading> r;
    PetscFunctionBeginUser;
    PetscCheck(outcome.completed(), PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "static run failed");
    PetscCall(sim_.sensors().read(s.q, s.v, r));
    tip_ = r.empty() ? 0.0 : r[0].position.y();
    PetscCallMPI(MPI_Bcast(&tip_, 1, MPI_DOUBLE, 0, sim_.comm()));
    PetscFunctionReturn(0);
  }

private:
  Simulation &sim_;
  double &tip_;
  std::vector<double> &hz_;
};

// The three-boom telescope of test_telescope_statics (retracted), static
// under gravity and a tip load, with its four sliding joints rigid or padded.
Scene telescope(const std::string &pad)
{
  std::string s = R"(name: telescope-pads
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: boom1, length: 2.0, elements: 8, origin: [0, 0], section: {E: 2.1e11, rho: 7850, A: 6.944e-3, I: 6.395214e-5}}
  - {name: boom2, length: 2.0, elements: 8, origin: [0.25, 0], section: {E: 2.1e11, rho: 7850, A: 5.264e-3, I: 3.720306e-5}}
  - {name: boom3, length: 2.0, elements: 8, origin: [0.5, 0], section: {E: 2.1e11, rho: 7850, A: 3.816e-3, I: 1.986431e-5}}
constraints:
  - {type: clamp, name: base, body: boom1, at: start}
  - {type: sliding_joint, name: j1, body: boom1, at: end, track: boom2PAD}
  - {type: sliding_joint, name: j2, body: boom2, at: start, track: boom1PAD}
  - {type: sliding_joint, name: j3, body: boom2, at: end, track: boom3PAD}
  - {type: sliding_joint, name: j4, body: boom3, at: start, track: boom2PAD}
  - {type: extraction_drive, name: extraction, joint: j2, displacement: 0}
  - {type: rope, name: rope, from: boom1, from_at: start, pulley: boom2, pulley_at: end, to: boom3, to_at: start}
loads:
  - {type: point_force, name: tip_load, body: boom3, at: end, force: [0, -1000]}
static: {load_steps: 1}
modal: {count: 3}
output:
  sensors:
    - {name: tip, body: boom3, at: end}
)";
  for (std::size_t at = s.find("PAD"); at != std::string::npos; at = s.find("PAD"))
    s.replace(at, 3, pad.empty() ? "" : ", pad: " + pad);
  return parseScene(s, "telescope-pads.yaml");
}

void staticWithModes(const Scene &scene, double &tip, std::vector<double> &hz)
{
  SimulationOptions o = testOptions();
  o.modal = true;
  Simulation sim(scene, PETSC_COMM_WORLD, o);
  check(sim.setUp());
  sim.addMonitor(std::make_unique<StaticModesRecorder>(sim, tip, hz));
  check(sim.run());
}

} // namespace

TEST(Pads, StiffPadsWithoutClearanceReproduceTheBilateralJoint)
{
  double tipRigid = 0, tipPad = 0;
  std::vector<double> hzRigid, hzPad;
  staticWithModes(telescope(""), tipRigid, hzRigid);
  staticWithModes(telescope("{stiffness: 1.0e12, clearance: 0}"), tipPad, hzPad);
  ASSERT_FALSE(hzRigid.empty());
  ASSERT_FALSE(hzPad.empty());
  const double dTip = std::abs(tipPad - tipRigid) / std::abs(tipRigid);
  const double dHz = std::abs(hzPad[0] - hzRigid[0]) / hzRigid[0];
  PetscPrintf(PETSC_COMM_WORLD,
              "  telescope, rigid joints: tip %.9e m, f1 %.6f Hz; pads k = 1e12 N/m, g = 0: tip %.9e m, f1 %.6f Hz; "
              "relative differences %.2e (tip), %.2e (f1)\n",
              tipRigid, hzRigid[0], tipPad, hzPad[0], dTip, dHz);
  EXPECT_LT(dTip, 1e-4);
  EXPECT_LT(dHz, 1e-4);
  // Softer pads lower the frequency and increase the deflection.
  double tipSoft = 0;
  std::vector<double> hzSoft;
  staticWithModes(telescope("{stiffness: 1.0e7}"), tipSoft, hzSoft);
  PetscPrintf(PETSC_COMM_WORLD, "  pads k = 1e7 N/m: tip %.6e m, f1 %.6f Hz\n", tipSoft, hzSoft.at(0));
  EXPECT_LT(tipSoft, tipRigid);
  EXPECT_LT(hzSoft.at(0), hzRigid[0]);
}
