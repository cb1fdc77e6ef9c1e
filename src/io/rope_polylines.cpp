#include "boomdyn/rope_polylines.hpp"

#include "boomdyn/constraint_item.hpp"
#include "boomdyn/elastic_rope.hpp"
#include "boomdyn/rope.hpp"
#include "xdmf_text.hpp"


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

std::string ropesXdmfGrid(const std::string &h5, std::size_t k, double time, std::size_t points, std::size_t segments)
{
  return xdmf::polylineGridBegin("ropes", time, segments, points, h5 + ":/paraview/rope_segments",
                                 h5 + ":/paraview/" + std::to_string(k) + "/rope_points") +
         "   </Grid>\n";
}

void writeRopesXdmf(const std::string &path, const std::string &title, const std::string &grids)
{
  xdmf::writeFileReplacing(path, xdmf::collectionBegin(title + " ropes") + grids + xdmf::collectionEnd());
}

} // namespace boomdyn
