// The Terrain Tile Writer (Filters/vtkTerrainTileWriter.h) writes the files its
// kernel (Kernels/Core/TileExport.h, `tsynth convert --tile-size`) writes, byte
// for byte, gives the heights back through the mosaic, and writes nothing for
// a name it cannot serve.
#include "FilterTesting.h"
#include "vtkTerrainTileWriter.h"

#include "Core/HeightfieldIO.h"
#include "Core/TileExport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <unistd.h>

namespace tsynth
{
namespace
{

namespace fs = std::filesystem;

// A fresh folder for one test, removed after it.
struct Folder
{
  fs::path path;
  explicit Folder(const std::string& name)
    : path(fs::temp_directory_path() / (name + "-" + std::to_string(::getpid())))
  {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Folder() { fs::remove_all(path); }
};

std::set<std::string> namesIn(const fs::path& folder)
{
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    names.insert(entry.path().filename().string());
  }
  return names;
}

std::string bytesOf(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

} // namespace

TEST(TerrainTileWriterFilter, WritesTheKernelsTilesAndMosaicByteForByte)
{
  const Heightfield dem = test::roughDem(100, 70, true);
  Folder byFilter("tsynth-tile-writer-filter");
  Folder byKernel("tsynth-tile-writer-kernel");
  vtkNew<vtkTerrainTileWriter> writer;
  test::FilterErrors errors(writer);
  writer->SetInputData(test::imageOf(dem));
  writer->SetFileName((byFilter.path / "land.vrt").string().c_str());
  writer->SetTileSize(33);
  ASSERT_EQ(writer->Write(), 1) << errors.text;
  const TileExportReport kernel = exportTiles(dem, (byKernel.path / "land.vrt").string(), 33);
  // 100 x 70 samples in tiles of 33 sharing an edge: 4 columns and 3 rows.
  EXPECT_EQ(writer->GetTilesWritten(), 12);
  ASSERT_EQ(kernel.tiles.size(), 12u);
  const std::set<std::string> names = namesIn(byFilter.path);
  ASSERT_EQ(names, namesIn(byKernel.path));
  for (const std::string& name : names)
  {
    EXPECT_EQ(bytesOf(byFilter.path / name), bytesOf(byKernel.path / name)) << name;
  }
  // The mosaic gives the terrain back, nodata included.
  const Heightfield back = readHeightfield((byFilter.path / "land.vrt").string());
  ASSERT_EQ(back.width, dem.width);
  ASSERT_EQ(back.height, dem.height);
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    ASSERT_EQ(back.isValid(k), dem.isValid(k)) << "cell " << k;
    if (dem.isValid(k))
    {
      ASSERT_EQ(back.z[k], dem.z[k]) << "cell " << k;
    }
  }
}

TEST(TerrainTileWriterFilter, ANameItCannotServeWritesNothing)
{
  Folder folder("tsynth-tile-writer-refusal");
  const Heightfield dem = test::roughDem(40, 40, true);
  for (const char* name : { "land.jpg", "land.png" }) // .png: 16-bit tiles cannot mark nodata
  {
    vtkNew<vtkTerrainTileWriter> writer;
    test::FilterErrors errors(writer);
    writer->SetInputData(test::imageOf(dem));
    writer->SetFileName((folder.path / name).string().c_str());
    writer->SetTileSize(17);
    EXPECT_EQ(writer->Write(), 0) << name;
    EXPECT_FALSE(errors.text.empty()) << name;
    EXPECT_TRUE(namesIn(folder.path).empty()) << name;
  }
}

} // namespace tsynth
