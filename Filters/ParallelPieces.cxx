#include "ParallelPieces.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace tsynth
{

namespace
{

// Each rank reports its progress in steps of this share of the run.
constexpr double kRankProgressStep = 0.1;

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

int rankCount()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c != nullptr ? std::max(1, c->GetNumberOfProcesses()) : 1;
}

int thisRank()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c != nullptr ? c->GetLocalProcessId() : 0;
}

std::vector<std::string> allGatherBytes(const std::string& mine)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (c == nullptr || c->GetNumberOfProcesses() <= 1)
  {
    return { mine };
  }
  return allGatherBytes(c, mine);
}

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
  // Each rank says how far it is, a line every kRankProgressStep, on its own standard output
  // (mpiexec shows every rank's): the filter's progress bar only ever shows rank 0's.
  const std::string who = "rank " + std::to_string(options.sharing.rank) + " of " +
    std::to_string(options.sharing.ranks) + ": ";
  auto said = std::make_shared<int>(-1);
  const ProgressReport filterProgress = options.progress;
  options.progress = [filterProgress, who, said](double fraction, const std::string& stage)
  {
    if (filterProgress)
    {
      filterProgress(fraction, stage);
    }
    const int step = static_cast<int>(fraction / kRankProgressStep);
    if (step > *said)
    {
      *said = step;
      // One line in one write, so that the ranks' lines do not interleave.
      std::cout << who + stage + ", " + std::to_string(static_cast<int>(100.0 * fraction)) + "%\n"
                << std::flush;
    }
  };
}

void reportRankWork(const SynthesisOptions& options, const SynthesisResult& result)
{
  if (options.sharing.ranks <= 1)
  {
    return;
  }
  double seconds = 0.0;
  double cpu = 0.0;
  std::size_t fills = 0;
  for (const TileTiming& t : result.tiles)
  {
    seconds += t.seconds;
    cpu += t.cpuSeconds;
    fills += t.fill ? 1 : 0;
  }
  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "rank " << options.sharing.rank << " of "
       << options.sharing.ranks << ": " << result.tiles.size() - fills << " feature and " << fills
       << " fill tile passes in " << seconds << " s (CPU " << cpu << " s), waited "
       << result.waitedSeconds << " s for the other ranks\n";
  std::cout << line.str() << std::flush; // one write: the ranks' lines do not interleave
}

bool keepRequestedExtent(vtkInformation* outInfo, vtkImageData* image)
{
  if (outInfo == nullptr || image == nullptr || image->GetNumberOfPoints() == 0 ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    return false;
  }
  int asked[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
  int held[6];
  image->GetExtent(held);
  if (asked[0] > held[0] || asked[1] < held[1] || asked[2] > held[2] || asked[3] < held[3])
  {
    image->Crop(asked);
    return true;
  }
  return false;
}

bool holdsFirstPiece(vtkInformation* outInfo)
{
  return outInfo == nullptr ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) ||
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) <= 0;
}

} // namespace tsynth
