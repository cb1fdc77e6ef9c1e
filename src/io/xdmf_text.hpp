// XDMF text shared by the results file's two descriptions (private to
// src/io): RUN.xmf (booms, results_writer.cpp) and RUN.ropes.xmf (ropes,
// rope_polylines.cpp). Both are temporal collections of polyline grids whose
// arrays live in the HDF5 results file, and both are rewritten whole at every
// snapshot.
#pragma once

#include "boomdyn/output_file.hpp"

#include <cstddef>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace boomdyn::xdmf {

inline std::string collectionBegin(const std::string &name)
{
  return "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n  <Grid Name=\"" + name +
         "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
}

inline std::string collectionEnd() { return "  </Grid>\n </Domain>\n</Xdmf>\n"; }

// The opening of one time's grid: its time, the polyline topology (the
// segments' node pairs at segmentsRef) and the node coordinates at
// pointsRef ("file.h5:/path"); the caller adds attributes and "   </Grid>\n".
inline std::string polylineGridBegin(const std::string &name, double time, std::size_t segments, std::size_t points,
                                     const std::string &segmentsRef, const std::string &pointsRef)
{
  char t[64];
  std::snprintf(t, sizeof t, "%.17g", time);
  const std::string ns = std::to_string(segments), np = std::to_string(points);
  return "   <Grid Name=\"" + name + "\" GridType=\"Uniform\">\n    <Time Value=\"" + t + "\"/>\n" +
         "    <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"" + ns + "\">\n" +
         "     <DataItem Dimensions=\"" + ns + " 2\" NumberType=\"Int\" Format=\"HDF\">" + segmentsRef +
         "</DataItem>\n    </Topology>\n" + "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" + np +
         " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + pointsRef + "</DataItem>\n    </Geometry>\n";
}

// A field at the nodes of a grid: a scalar (points values) or a 3-vector
// (points x 3) at dataRef ("file.h5:/path").
inline std::string nodeAttribute(const std::string &name, bool vector, const std::string &points,
                                 const std::string &dataRef)
{
  return "    <Attribute Name=\"" + name + "\" AttributeType=\"" + (vector ? "Vector" : "Scalar") +
         "\" Center=\"Node\">\n     <DataItem Dimensions=\"" + points + (vector ? " 3" : "") +
         "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + dataRef + "</DataItem>\n    </Attribute>\n";
}

// Writes text to path through a temporary file, so that a failed write (a
// full disk) keeps the previous file instead of leaving an empty one.
inline void writeFileReplacing(const std::string &path, const std::string &text)
{
  // Never a rename onto a device, FIFO, socket or folder (nor opening a FIFO
  // as the temporary: that would block); a symbolic link is written through.
  const std::string target = placementPath(path), tmp = target + ".tmp";
  refuseSpecialFile(path, "XDMF file");
  refuseSpecialFile(tmp, "XDMF file's temporary");
  std::ofstream out(tmp);
  out << text;
  out.close();
  if (!out) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write '" + path + "' (a full disk?)");
  }
  std::rename(tmp.c_str(), target.c_str());
}

} // namespace boomdyn::xdmf
