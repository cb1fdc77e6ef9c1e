#include "boomdyn/rope_polylines.hpp"

#include "boomdyn/constraint_item.hpp"
#include "boomdyn/elastic_rope.hpp"
#include "boomdyn/rope.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace boomdyn {

std::vector<DrawnRope> drawnRopes(const Model &model)
{
  std::vector<DrawnRope> out;
  for (const auto &item : model.items()) {
    if (const auto *elastic = dynamic_cast<const ElasticRope *>(item.get()))
      out.push_back({elastic->name(), elastic->path().points()});
    else if (const auto *c = dynamic_cast<const ConstraintItem *>(item.get()))
      if (const auto *rope = dynamic_cast<const Rope *>(&c->constraint()))
        out.push_back({rope->name(), rope->path().points()});
  }
  return out;
}

void ropePolylines(const std::vector<DrawnRope> &ropes, const std::vector<double> &q, std::vector<double> &points,
                   std::vector<int> &segments)
{
  points.clear();
  segments.clear();
  for (const DrawnRope &rope : ropes) {
    const int first = static_cast<int>(points.size() / 3);
    for (std::size_t k = 0; k < rope.points.size(); ++k) {
      const RopePath::Point &p = rope.points[k];
      const CenterlineLocation loc = p.body->locate(p.s);
      double vals[8];
      for (int i = 0; i < loc.count; ++i) vals[i] = q[loc.dofs[i]];
      CenterlineSample sample;
      p.body->sample(loc, p.s, vals, sample);
      points.insert(points.end(), {sample.r[0].x(), sample.r[0].y(), 0.0});
      if (k > 0) segments.insert(segments.end(), {first + (int)k - 1, first + (int)k});
    }
  }
}

void writeRopesXdmf(const std::string &path, const std::string &h5, const std::string &title,
                    const std::vector<double> &times, std::size_t points, std::size_t segments)
{
  const std::string np = std::to_string(points), ns = std::to_string(segments);
  std::ofstream out(path + ".tmp");
  out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
      << "  <Grid Name=\"" << title << " ropes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    char time[64];
    std::snprintf(time, sizeof time, "%.17g", times[k]);
    out << "   <Grid Name=\"ropes\" GridType=\"Uniform\">\n    <Time Value=\"" << time << "\"/>\n"
        << "    <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"" << ns << "\">\n"
        << "     <DataItem Dimensions=\"" << ns << " 2\" NumberType=\"Int\" Format=\"HDF\">" << h5
        << ":/paraview/rope_segments</DataItem>\n    </Topology>\n"
        << "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << np
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5 << ":/paraview/" << k
        << "/rope_points</DataItem>\n    </Geometry>\n   </Grid>\n";
  }
  out << "  </Grid>\n </Domain>\n</Xdmf>\n";
  out.close();
  // A failed write (a full disk) keeps the previous file, not an empty one.
  if (!out) {
    std::remove((path + ".tmp").c_str());
    throw std::runtime_error("cannot write '" + path + "' (a full disk?)");
  }
  std::rename((path + ".tmp").c_str(), path.c_str());
}

} // namespace boomdyn
