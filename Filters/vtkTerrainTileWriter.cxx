#include "vtkTerrainTileWriter.h"

#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/OutputFile.h"
#include "Core/TileExport.h"

#include <vtkErrorCode.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>

#include <exception>
#include <new>

vtkStandardNewMacro(vtkTerrainTileWriter);

vtkTerrainTileWriter::~vtkTerrainTileWriter()
{
  this->SetFileName(nullptr);
}

int vtkTerrainTileWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
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
