// Tests of Kernels/Core/FileRoles.cxx.
// An output never replaces an input or another output, however the path is
// spelled, and a sidecar counts as the file it describes.
#include "Core/FileRoles.h"
#include "ErrorOf.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace tsynth;
namespace fs = std::filesystem;

namespace
{

// A fresh folder per test, with the files named in it created (empty).
fs::path folderWith(const std::string& name, std::initializer_list<const char*> files)
{
  const fs::path dir = test::scratchDir() / ("file-roles-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* f : files)
  {
    std::ofstream(dir / f) << "x";
  }
  return dir;
}

// The sentence check() throws for `in` read as "the DEM" and `out` written as "-o".
std::string refusal(const fs::path& in, const fs::path& out)
{
  FileRoles roles;
  roles.input(in.string(), "the DEM");
  roles.output(out.string(), "-o");
  return test::errorOf([&] { roles.check(); });
}

} // namespace

TEST(FileRoles, AnOutputOverAnInputIsRefusedHoweverItIsSpelled)
{
  const fs::path dir = folderWith("spelled", { "dem.tif" });
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "dem.tif", dir / "link.tif");
  fs::create_hard_link(dir / "dem.tif", dir / "hard.tif");
  for (const fs::path& out :
    { dir / "dem.tif", dir / "sub" / ".." / "dem.tif", dir / "link.tif", dir / "hard.tif" })
  {
    SCOPED_TRACE(out.string());
    const std::string message = refusal(dir / "dem.tif", out);
    EXPECT_NE(message.find("-o"), std::string::npos) << message;
    EXPECT_NE(message.find("the DEM"), std::string::npos) << message;
  }
  EXPECT_EQ(refusal(dir / "dem.tif", dir / "new.tif"), "");
}

TEST(FileRoles, TwoOutputsOfOneFileAreRefused)
{
  const fs::path dir = folderWith("outputs", { "dem.tif" });
  FileRoles roles;
  roles.input((dir / "dem.tif").string(), "the DEM");
  roles.output((dir / "out.tif").string(), "-o");
  roles.output((dir / "." / "out.tif").string(), "--flow");
  const std::string message = test::errorOf([&] { roles.check(); });
  EXPECT_NE(message.find("--flow"), std::string::npos) << message;
  EXPECT_NE(message.find("-o"), std::string::npos) << message;
}

TEST(FileRoles, A16BitPngsSidecarCountsAsTheOutput)
{
  // out.png brings out.json: an input of that name would be replaced.
  const fs::path dir = folderWith("sidecar", { "out.json" });
  const std::string message = refusal(dir / "out.json", dir / "out.png");
  EXPECT_NE(message.find("sidecar"), std::string::npos) << message;
  // A picture is written alone: its .json neighbour is nobody's business.
  FileRoles picture;
  picture.input((dir / "out.json").string(), "the report");
  picture.output((dir / "out.png").string(), "-o", FileRoles::Content::Other);
  EXPECT_EQ(test::errorOf([&] { picture.check(); }), "");
}

TEST(FileRoles, AFolderIsNoOutput)
{
  const fs::path dir = folderWith("folder", { "dem.tif" });
  fs::create_directories(dir / "out.tif");
  const std::string message = refusal(dir / "dem.tif", dir / "out.tif");
  EXPECT_NE(message.find("out.tif: it is a folder"), std::string::npos) << message;
}
