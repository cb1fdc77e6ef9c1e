// Partition quality (boomdyn -boom_partition_report): a single boom is a
// chain, cut once per extra part by either method; on the paper telescope a
// METIS partition of the work-item graph cuts fewer couplings and balances
// better than the contiguous split boomdyn uses.
#include "boomdyn/partition.hpp"
#include "boomdyn/scene_reader.hpp"

#include <gtest/gtest.h>

using namespace boomdyn;

TEST(Partition, ChainIsCutOncePerExtraPartByBothMethods)
{
  Scene scene = readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/benchmarks/scenes/long_boom.yaml");
  scene.bodies[0].elements = 1000;
  const Model model(scene);
  for (int parts : {2, 3, 4}) {
    const PartitionQuality contiguous = evaluatePartition(model, contiguousPartition(model, parts), parts, "contiguous");
    const PartitionQuality metis = evaluatePartition(model, metisPartition(model, parts), parts, "metis");
    // Elements share a node (4 unknowns) with their neighbour: one cut, 4 shared unknowns.
    EXPECT_EQ(contiguous.cutEdges, parts - 1) << parts;
    EXPECT_EQ(contiguous.interfaceUnknowns, 4 * (parts - 1)) << parts;
    EXPECT_EQ(metis.interfaceUnknowns, 4 * (parts - 1)) << parts;
    EXPECT_LT(contiguous.imbalance, 1.01);
    EXPECT_LT(metis.imbalance, 1.05);
    int items = 0;
    for (int n : metis.itemsPerPart) items += n;
    EXPECT_EQ(items, static_cast<int>(model.items().size()));
  }
}

TEST(Partition, MetisCutsFewerCouplingsOfTheTelescope)
{
  const Model model(readSceneFile(std::string(BOOMDYN_SOURCE_DIR) + "/inputs/paper_extraction_single_calibration.yaml"));
  const PartitionQuality contiguous = evaluatePartition(model, contiguousPartition(model, 2), 2, "contiguous");
  const PartitionQuality metis = evaluatePartition(model, metisPartition(model, 2), 2, "metis");
  std::printf("  telescope, 2 parts: contiguous %d interface unknowns, %d cut edges, imbalance %.3f; "
              "METIS %d, %d, %.3f\n", contiguous.interfaceUnknowns, contiguous.cutEdges, contiguous.imbalance,
              metis.interfaceUnknowns, metis.cutEdges, metis.imbalance);
  EXPECT_LT(metis.cutEdges, contiguous.cutEdges);
  EXPECT_LE(metis.interfaceUnknowns, contiguous.interfaceUnknowns);
  EXPECT_LT(metis.imbalance, contiguous.imbalance);
}
