#include "ParallelPieces.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <string>
#include <vector>

namespace tsynth
{

namespace
{

// Every rank's bytes, in rank order, through the controller's collectives.
std::vector<std::string> allGatherBytes(vtkMultiProcessController* c, const std::string& mine)
{
  const int ranks = c->GetNumberOfProcesses();
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  c->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
  for (std::size_t r = 1; r < offsets.size(); ++r)
  {
    offsets[r] = offsets[r - 1] + lengths[r - 1];
  }
  std::vector<char> all(static_cast<std::size_t>(offsets.back() + lengths.back()));
  c->AllGatherV(mine.data(), all.data(), length, lengths.data(), offsets.data());
  std::vector<std::string> parts;
  for (std::size_t r = 0; r < offsets.size(); ++r)
  {
    parts.emplace_back(all.data() + offsets[r], static_cast<std::size_t>(lengths[r]));
  }
  return parts;
}

} // namespace

void shareTilesAmongRanks(SynthesisOptions& options)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (c == nullptr || c->GetNumberOfProcesses() <= 1 || options.tileSize <= 0)
  {
    return;
  }
  options.sharing.rank = c->GetLocalProcessId();
  options.sharing.ranks = c->GetNumberOfProcesses();
  options.sharing.allGather = [c](const std::string& mine) { return allGatherBytes(c, mine); };
}

void keepRequestedExtent(vtkInformation* outInfo, vtkImageData* image)
{
  if (outInfo == nullptr || image == nullptr || image->GetNumberOfPoints() == 0 ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    return;
  }
  int asked[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
  int held[6];
  image->GetExtent(held);
  if (asked[0] > held[0] || asked[1] < held[1] || asked[2] > held[2] || asked[3] < held[3])
  {
    image->Crop(asked);
  }
}

bool holdsFirstPiece(vtkInformation* outInfo)
{
  return outInfo == nullptr ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) ||
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) <= 0;
}

} // namespace tsynth
