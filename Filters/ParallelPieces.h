// The Terrain Synthesis filter on ParaView's MPI engine (pvbatch, pvserver): the
// ranks share a tiled synthesis, and each rank's outputs hold only its piece.
#pragma once

#include "Synthesis/Synthesiser.h"

#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkInformation;

namespace tsynth
{

// The processes under ParaView's global controller and this one's rank (1 and
// 0 without a controller).
int rankCount();
int thisRank();

// Every process's bytes, in rank order; a collective: every process calls it.
std::vector<std::string> allGatherBytes(const std::string& mine);

// With several processes under ParaView's global controller and tiles asked
// for, lets them share the tiles (SynthesisOptions::sharing); otherwise
// leaves the options as they are (each process synthesises the whole). Each
// sharing rank then also prints its progress ("rank 1 of 2: fill, 40%").
void shareTilesAmongRanks(SynthesisOptions& options);

// After a shared synthesis, the rank's one line of what it did: "rank 1 of 2:
// 9 feature and 9 fill tile passes in 12.30 s (CPU 12.10 s), waited 2.10 s for
// the other ranks".
void reportRankWork(const SynthesisOptions& options, const SynthesisResult& result);

// Crops an image output to the extent the pipeline asked of it (its piece),
// when smaller than what it holds; true if it did.
bool keepRequestedExtent(vtkInformation* outInfo, vtkImageData* image);

// Whether the pipeline asked this output for its first piece (or asked for
// none): outputs that are not split by extent (tables, lines) are given by
// the first piece alone, so that ParaView does not gather one copy per rank.
bool holdsFirstPiece(vtkInformation* outInfo);

} // namespace tsynth
