// Feature graphs as vtkPolyData (DESIGN.md data model) and poly-lines from vtkPolyData.
#pragma once

#include "Features/FeatureGraph.h"
#include "Features/Sketch.h"
#include "Synthesis/Setup.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace tsynth
{

// Lines in metres (x = origin + column * cellX), one poly-line cell per chain,
// nodes first so a node is one shared point, and one vertex cell per node
// (before the lines; ChainId -1). Point data: NodeKind (0 path,
// 1 end, 2 branch), Degree, Elevation, BFSRank (-1 off nodes), ComponentId, and
// ElevationConstraint when any chain has one; cell data: FeatureType (+1 ridge,
// -1 valley), ChainId; field data: BFSOrder (node point ids), CellSize, GridSize
// (the graph's width and height in cells).
void featureGraphToPolyData(const FeatureGraph& graph,
  vtkPolyData* out,
  double originX = 0.0,
  double originY = 0.0);

// One vertex per control point: point data NodeId, ChainId, AngleDeg, Reached.
void controlPointsToPolyData(const FeatureGraph& graph,
  vtkPolyData* out,
  double originX = 0.0,
  double originY = 0.0);

// Poly-line cells in metres -> poly-lines in cells. FeatureType from cell data
// (missing: ridges, and `warning` says so), Elevation from point data if present.
std::vector<Polyline> polyDataToPolylines(const vtkPolyData* input,
  double cellX,
  double cellY,
  double originX,
  double originY,
  std::string* warning = nullptr);

// A poly-line sketch as the set-up takes it: points in metres in the raster frame
// exactly as stored (no origin is subtracted), FeatureType and Elevation as for
// polyDataToPolylines; its frame GridSize x CellSize from field data when both
// are there (a feature tree written by featureGraphToPolyData).
PolylineSketch polyDataToPolylineSketch(const vtkPolyData* input, std::string* warning = nullptr);

// Reads a .vtp file into `out`. Throws tsynth::Error if it is missing, unreadable
// or damaged: a data array of no known type or of more than 1024 components, a
// compressed array whose header gives sizes the file cannot hold, a cell
// referring to a point the file does not have (VTK's reader would crash, hang
// or allocate gigabytes on these).
void readPolyDataFile(const std::string& path, vtkPolyData* out);

// Writes a .vtp with inline binary data (readable by this machine's ParaView);
// complete or not at all. Throws tsynth::Error.
void writePolyDataFile(const std::string& path, vtkPolyData* data);

} // namespace tsynth
