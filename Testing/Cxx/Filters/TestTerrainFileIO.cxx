// Filters/TerrainFileIO.h: a heightfield through a .vti file and back, and
// the files it refuses.
#include "TerrainFileIO.h"
#include "TestData.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

TEST(Filters, VtiRoundTripKeepsHeightsMaskAndGeoreference)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  tsynth::Heightfield hf =
    tsynth::readTerrainFile(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  hf.z[5] = std::numeric_limits<float>::quiet_NaN();
  tsynth::normaliseMask(hf);
  const std::string path = (tsynth::test::scratchDir() / "roundtrip.vti").string();
  tsynth::writeTerrainFile(path, hf);
  {
    // Inline binary, never an appended-data section (see DESIGN.md on expat).
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("AppendedData"), std::string::npos);
    EXPECT_NE(text.find("format=\"binary\""), std::string::npos);
  }
  const tsynth::Heightfield back = tsynth::readTerrainFile(path);
  ASSERT_EQ(back.width, hf.width);
  ASSERT_EQ(back.height, hf.height);
  EXPECT_DOUBLE_EQ(back.cellX, hf.cellX);
  EXPECT_DOUBLE_EQ(back.cellY, hf.cellY);
  EXPECT_EQ(back.validCount(), hf.validCount());
  EXPECT_FALSE(back.isValid(5));
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (hf.isValid(k))
    {
      ASSERT_EQ(back.z[k], hf.z[k]);
    }
  }
  EXPECT_EQ(back.georef.crsWkt, hf.georef.crsWkt);
  EXPECT_EQ(back.georef.geoTransform, hf.georef.geoTransform);

  // A .vti written from VTK goes back to GeoTIFF with its georeference.
  const std::string tif = (tsynth::test::scratchDir() / "from_vti.tif").string();
  tsynth::writeTerrainFile(tif, back);
  tsynth::RasterInfo info;
  tsynth::readTerrainFile(tif, {}, &info);
  EXPECT_TRUE(info.georef.isGeographic);
  EXPECT_NEAR(info.cellX, hf.cellX, 1e-9);
}

TEST(Filters, VtiErrors)
{
  EXPECT_THROW(tsynth::readTerrainFile("/nonexistent/x.vti"), tsynth::Error);
  const std::string junk = (tsynth::test::scratchDir() / "junk.vti").string();
  std::ofstream(junk) << "<VTKFile> not really";
  EXPECT_THROW(tsynth::readTerrainFile(junk), tsynth::Error);
}
