// Ropes drawn for ParaView (docs/output.md "/paraview"): every rope (the
// inextensible `rope` constraints and the `elastic_rope` force elements) as
// a polyline from its first end over its pulleys to its far end, through
// the material points of its RopePath. Written beside the booms at every
// state snapshot (/paraview/<k>/rope_points, /paraview/rope_segments) and
// described by a second XDMF file beside the booms' one, RUN.ropes.xmf (a
// separate file, so that readers that take one temporal collection per
// file, like meshio's, still read the booms from RUN.xmf).
#pragma once

#include "boomdyn/model.hpp"
#include "boomdyn/rope_path.hpp"

#include <string>
#include <vector>

namespace boomdyn {

struct DrawnRope {
  std::string name;
  std::vector<RopePath::Point> points; // first end, pulleys, far end
};

// The ropes of a model, in the order of its items.
std::vector<DrawnRope> drawnRopes(const Model &model);

// Positions x, y, 0 of every rope point (rope after rope) at the global
// coordinates q, and the segments between consecutive points of a rope.
void ropePolylines(const std::vector<DrawnRope> &ropes, const std::vector<double> &q, std::vector<double> &points,
                   std::vector<int> &segments);

// The XDMF grid of the rope polylines of snapshot k at `time` (h5: the
// results file's name relative to the XDMF file).
std::string ropesXdmfGrid(const std::string &h5, std::size_t k, double time, std::size_t points, std::size_t segments);
// Writes the XDMF file `path`: the temporal collection of the grids given
// (ropesXdmfGrid, snapshot after snapshot). Throws std::runtime_error when
// it cannot be written.
void writeRopesXdmf(const std::string &path, const std::string &title, const std::string &grids);

} // namespace boomdyn
