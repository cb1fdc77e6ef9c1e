// The step controller's checkpoint (saveStepper/restoreStepper) through a
// real checkpoint file: every field comes back exactly, under the keys that
// checkpoints have always used (files written before the TS rewrite load).
#include "boomdyn/checkpoint.hpp"
#include "boomdyn/time_stepper.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace boomdyn;

TEST(StepperCheckpoint, EveryFieldComesBackExactly)
{
  const std::string dir = std::string(BOOMDYN_BINARY_DIR) + "/test_output";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/stepper_checkpoint.chk.h5";
  StepperState saved;
  saved.h = 1.0 / 3.0 * 1e-3; // not representable in decimal: a text round trip would show
  saved.successesSinceCut = 3;
  saved.steps = 123457;
  saved.rejected = 17;
  saved.newtonIterations = 370001;
  CheckpointWriter w(PETSC_COMM_WORLD);
  ASSERT_EQ(saveStepper(w, saved), 0);
  ASSERT_EQ(w.write(path, "name: stepper-test\n"), 0);

  CheckpointReader r(PETSC_COMM_WORLD);
  ASSERT_EQ(r.read(path), 0);
  // The keys run.cpp has written since checkpoints exist.
  EXPECT_EQ(r.scalar("stepper.h"), saved.h);
  EXPECT_EQ(r.scalar("stepper.steps"), 123457.0);
  StepperState back;
  ASSERT_EQ(restoreStepper(r, &back), 0);
  EXPECT_EQ(back.h, saved.h);
  EXPECT_EQ(back.successesSinceCut, saved.successesSinceCut);
  EXPECT_EQ(back.steps, saved.steps);
  EXPECT_EQ(back.rejected, saved.rejected);
  EXPECT_EQ(back.newtonIterations, saved.newtonIterations);
}
