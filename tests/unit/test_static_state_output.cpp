// A static run's /state snapshots (docs/output.md): their time is the load
// factor, and they follow output.state_interval (in load factor) like a
// dynamic run's follow it in time: the first and the last load increment
// when the interval is 0, and every interval in between. Read back with the
// plain HDF5 C API. (Issue 40: one row, the final state, with time 0.)
#include "boomdyn/monitors.hpp"
#include "support.hpp"

#include <hdf5.h>

#include <filesystem>

using namespace boomdyn;
using namespace boomdyn::testing;

namespace {

// The /state/time dataset and the row count of /state/q, after a static
// run of a cantilever in `steps` load increments with the given interval.
std::vector<double> staticStateTimes(int steps, double interval, std::size_t *qRows)
{
  const std::string text = R"(
name: static-states
analysis: static
gravity: [0, -9.81]
bodies:
  - {name: boom, length: 2.0, elements: 4, section: {EA: 8.5e8, EI: 4.95e6, rhoA: 31.84}}
constraints:
  - {type: clamp, body: boom, at: start}
loads:
  - {type: point_force, name: tip, body: boom, at: end, force: [0, -10000]}
static: {load_steps: )" + std::to_string(steps) + R"(}
output: {state_interval: )" + std::to_string(interval) + R"(}
)";
  const Scene scene = parseScene(text, "static-states.yaml");
  const std::filesystem::path dir = std::filesystem::path(BOOMDYN_BINARY_DIR) / "test_output" / "static_states";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / ("states_" + std::to_string(steps) + "_" + std::to_string(interval) + ".h5")).string();
  {
    Simulation sim(scene, PETSC_COMM_WORLD, testOptions());
    check(sim.setUp());
    sim.addMonitor(std::make_unique<ResultsOutput>(sim, path, true, RunInfo{}, scene.output.state_interval));
    check(sim.run());
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  std::vector<double> times;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(file, 0) << path;
  if (file < 0) return times;
  auto rows = [&](const char *name) {
    const hid_t set = H5Dopen2(file, name, H5P_DEFAULT), space = H5Dget_space(set);
    hsize_t dims[2] = {0, 0};
    H5Sget_simple_extent_dims(space, dims, nullptr);
    H5Sclose(space);
    return std::make_pair(set, dims[0]);
  };
  auto [timeSet, n] = rows("/state/time");
  times.resize(n);
  if (n > 0) H5Dread(timeSet, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times.data());
  H5Dclose(timeSet);
  auto [qSet, m] = rows("/state/q");
  *qRows = m;
  H5Dclose(qSet);
  H5Fclose(file);
  return times;
}

} // namespace

TEST(StaticStateOutput, SnapshotsAtTheLoadFactorsOfTheInterval)
{
  struct Case {
    int steps;
    double interval;
    std::vector<double> expected; // load factors of the snapshots
  };
  // Ten increments of 0.1 reach 1 - 1e-16 (the solver's own sum): compared to 1e-12.
  const Case cases[] = {{1, 0.0, {1.0}},
                        {10, 0.0, {0.1, 1.0}},
                        {10, 0.25, {0.1, 0.3, 0.5, 0.8, 1.0}},
                        {4, 0.5, {0.25, 0.5, 1.0}}};
  for (const Case &c : cases) {
    std::size_t qRows = 0;
    const std::vector<double> times = staticStateTimes(c.steps, c.interval, &qRows);
    std::string got;
    for (double t : times) got += std::to_string(t) + " ";
    PetscPrintf(PETSC_COMM_WORLD, "  %d load steps, state_interval %g: /state/time = %s\n", c.steps, c.interval,
                got.c_str());
    ASSERT_EQ(times.size(), c.expected.size()) << c.steps << " steps, interval " << c.interval << ": " << got;
    EXPECT_EQ(qRows, times.size());
    for (std::size_t k = 0; k < times.size(); ++k) EXPECT_NEAR(times[k], c.expected[k], 1e-12) << "row " << k;
  }
}
