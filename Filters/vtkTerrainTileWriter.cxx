#include "vtkTerrainTileWriter.h"

#include "ParallelPieces.h"
#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/OutputFile.h"
#include "Core/TileExport.h"

#include <vtkErrorCode.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <exception>
#include <iomanip>
#include <new>
#include <optional>
#include <sstream>

vtkStandardNewMacro(vtkTerrainTileWriter);

namespace
{

// The tile grid over the whole extent of the writer's input, if its file name
// and tile size make one (else nullopt: the write will say why).
std::optional<tsynth::TileGrid> gridOver(const int whole[6], const char* fileName, int tileSize)
{
  const std::optional<tsynth::TileFormat> format =
    fileName != nullptr ? tsynth::tileFormatFor(fileName) : std::nullopt;
  if (!format)
  {
    return std::nullopt;
  }
  try
  {
    return tsynth::tileGridFor(whole[1] - whole[0] + 1, whole[3] - whole[2] + 1, tileSize, *format);
  }
  catch (const tsynth::Error&)
  {
    return std::nullopt;
  }
}

// The extent that holds this rank's tile rows (and one row more to the south,
// in case the heights lie on cells); a single row for a rank with none, so
// that the sources upstream still run on it (the synthesis is collective).
void requestOwnRows(const int whole[6], const tsynth::TileGrid& grid, int update[6])
{
  std::copy(whole, whole + 6, update);
  const auto [first, last] = tsynth::tileRowsOf(grid, tsynth::thisRank(), tsynth::rankCount());
  if (first == last)
  {
    update[3] = update[2];
    return;
  }
  const auto [top, bottom] = tsynth::terrainRowsOf(grid, whole[3] - whole[2] + 1, first, last);
  update[2] = std::max(whole[2], whole[3] - bottom - 1);
  update[3] = whole[3] - top;
}

// A height summary as text, exactly (17 digits), to share with the other ranks.
std::string bytesOf(const tsynth::HeightSummary& h)
{
  std::ostringstream out;
  out << std::setprecision(17) << h.holes << ' ' << h.valid << ' ' << h.min << ' ' << h.max;
  return out.str();
}

tsynth::HeightSummary summaryFrom(const std::string& bytes)
{
  tsynth::HeightSummary h;
  std::istringstream in(bytes);
  in >> h.holes >> h.valid >> h.min >> h.max;
  return h;
}

// The first failure any rank reports (the empty string from each that did not
// fail), the same on every rank.
std::string firstFailure(const std::string& mine)
{
  for (const std::string& said : tsynth::allGatherBytes(mine))
  {
    if (!said.empty())
    {
      return said;
    }
  }
  return "";
}

} // namespace

vtkTypeBool vtkTerrainTileWriter::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()) &&
    tsynth::rankCount() > 1)
  {
    vtkInformation* in = inputVector[0]->GetInformationObject(0);
    int whole[6];
    in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    if (const auto grid = gridOver(whole, this->FileName, this->TileSize))
    {
      int update[6];
      requestOwnRows(whole, *grid, update);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), update, 6);
      in->Remove(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
      in->Remove(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
      return 1;
    }
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

vtkTerrainTileWriter::vtkTerrainTileWriter()
  : TileSize(
      static_cast<int>(tsynth::optionRow(tsynth::tileExportOptionRows(), "TileSize").defaultValue))
{
}

vtkTerrainTileWriter::~vtkTerrainTileWriter()
{
  this->SetFileName(nullptr);
}

int vtkTerrainTileWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

// This rank's share of a write by several ranks: its band of the input, the
// terrain's frame agreed over every rank's band, its tile rows, and rank 0
// the mosaic; published only if no rank failed. Every rank takes part in both
// exchanges whatever happens to it, so that none is left waiting.
void vtkTerrainTileWriter::WriteShare(vtkImageData* image)
{
  const int ranks = tsynth::rankCount();
  const int rank = tsynth::thisRank();
  int whole[6];
  this->GetInputInformation(0, 0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  std::string failure;
  tsynth::Heightfield band;
  int firstRow = 0; // the band's first row, from the north
  int width = 0;
  int height = 0;
  std::optional<tsynth::TileGrid> grid;
  tsynth::TileFormat format = tsynth::TileFormat::GeoTiff;
  std::pair<int, int> own{ 0, 0 };
  tsynth::HeightSummary mine;
  try
  {
    band = tsynth::imageToHeightfield(image, this->GetInputArrayToProcess(0, image));
    tsynth::requireValidHeights(band);
    int extent[6];
    image->GetExtent(extent);
    const int cellsLess = (extent[1] - extent[0] + 1) - band.width; // 1: heights on cells
    width = whole[1] - whole[0] + 1 - cellsLess;
    height = whole[3] - whole[2] + 1 - cellsLess;
    firstRow = whole[3] - extent[3];
    const std::optional<tsynth::TileFormat> f = tsynth::tileFormatFor(this->FileName);
    format = f ? *f : format;
    grid = tsynth::tileGridFor(width, height, this->TileSize, format); // throws with the sentence
    own = tsynth::tileRowsOf(*grid, rank, ranks);
    if (own.first < own.second)
    {
      // Rows counted once over the ranks: each its own up to the next rank's first.
      const auto [top, bottom] = tsynth::terrainRowsOf(*grid, height, own.first, own.second);
      const int rows = own.second == grid->rows ? bottom - top + 1 : bottom - top;
      mine = tsynth::summaryOf(band, top - firstRow, rows);
    }
  }
  catch (const std::exception& e)
  {
    failure = e.what();
  }
  const std::vector<std::string> said =
    tsynth::allGatherBytes(failure.empty() ? bytesOf(mine) : "!" + failure);
  tsynth::HeightSummary all;
  for (const std::string& s : said)
  {
    if (!s.empty() && s[0] == '!')
    {
      vtkErrorMacro(<< s.substr(1));
      this->SetErrorCode(vtkErrorCode::UnknownError);
      return;
    }
    all = tsynth::combined(all, summaryFrom(s));
  }
  tsynth::Publication outputs;
  std::size_t written = 0;
  try
  {
    const tsynth::AbortScope abortScope(this);
    const tsynth::TerrainFrame frame =
      tsynth::terrainFrameFrom(band, width, height, all, format, this->FileName);
    written = tsynth::exportTileRows({ frame, band, firstRow },
      this->FileName,
      *grid,
      format,
      own.first,
      own.second,
      [this](double fraction, const std::string&) {
        this->UpdateProgress(fraction);
      }).tiles.size();
    if (rank == 0 && format == tsynth::TileFormat::GeoTiff)
    {
      tsynth::writeTileMosaic(frame, *grid, this->FileName);
    }
  }
  catch (const std::exception& e)
  {
    failure = "Rank " + std::to_string(rank) + " could not write its tiles: " + e.what();
  }
  const std::string anyFailure = firstFailure(failure);
  if (!anyFailure.empty())
  {
    vtkErrorMacro(<< anyFailure); // nothing is published: no rank's tiles are left
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return;
  }
  std::string unpublished;
  try
  {
    outputs.publish();
  }
  catch (const std::exception& e)
  {
    unpublished = "Rank " + std::to_string(rank) + " could not publish its tiles: " + e.what();
  }
  // Also the end of the write on every rank: when rank 0 returns, all tiles are in place.
  const std::string anyUnpublished = firstFailure(unpublished);
  if (!anyUnpublished.empty())
  {
    vtkErrorMacro(<< anyUnpublished);
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return;
  }
  this->TilesWritten = static_cast<int>(written);
}

void vtkTerrainTileWriter::WriteData()
{
  this->TilesWritten = 0;
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  if (image == nullptr || this->FileName == nullptr || this->FileName[0] == '\0')
  {
    vtkErrorMacro("The Terrain Tile Writer needs a heightfield image and a file name "
                  "(NAME.vrt, NAME.png or NAME.raw).");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  if (tsynth::rankCount() > 1)
  {
    this->WriteShare(image);
    return;
  }
  try
  {
    const tsynth::AbortScope abortScope(this);
    const tsynth::Heightfield hf =
      tsynth::imageToHeightfield(image, this->GetInputArrayToProcess(0, image));
    tsynth::requireValidHeights(hf);
    tsynth::Publication outputs;
    const tsynth::TileExportReport report = tsynth::exportTiles(hf,
      this->FileName,
      this->TileSize,
      [this](double fraction, const std::string&) { this->UpdateProgress(fraction); });
    outputs.publish();
    this->TilesWritten = static_cast<int>(report.tiles.size());
  }
  catch (const tsynth::Cancelled&)
  {
    // Stopped: nothing was published, so no tile of this write is left.
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory writing tiles: use larger tiles or a smaller terrain.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkTerrainTileWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName != nullptr ? this->FileName : "(none)") << "\n";
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "TilesWritten: " << this->TilesWritten << "\n";
}
