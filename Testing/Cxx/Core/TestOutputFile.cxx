// Tests of Kernels/Core/OutputFile.cxx.
// A file appears complete or not at all, an existing one is never lost to a
// failed write, and a command's outputs appear together.
#include "Core/OutputFile.h"
#include "ErrorOf.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

using namespace tsynth;
namespace fs = std::filesystem;

namespace
{

fs::path emptyFolder(const std::string& name)
{
  const fs::path dir = test::scratchDir() / ("output-file-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string contents(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

std::size_t filesIn(const fs::path& dir)
{
  return static_cast<std::size_t>(
    std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

} // namespace

TEST(OutputFile, ACommittedFileAppearsWholeAndNoTemporaryStays)
{
  const fs::path dir = emptyFolder("commit");
  const fs::path target = dir / "terrain.json";
  {
    OutputFile file(target.string());
    EXPECT_EQ(fs::path(file.temporaryPath()).parent_path(), dir) << "written beside its target";
    file.write("{\"heights\": 1}\n");
    EXPECT_FALSE(fs::exists(target)) << "visible before its commit";
    file.commit();
  }
  EXPECT_EQ(contents(target), "{\"heights\": 1}\n");
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(OutputFile, AWriteThatFailsOnTheWayLeavesTheOldFile)
{
  const fs::path dir = emptyFolder("abandon");
  const fs::path target = dir / "terrain.json";
  std::ofstream(target) << "old";
  {
    OutputFile file(target.string());
    file.write("new, but the command fails before its commit");
  } // an exception unwinding past it
  EXPECT_EQ(contents(target), "old");
  EXPECT_EQ(filesIn(dir), 1u) << "the temporary was left behind";
}

TEST(OutputFile, APublicationShowsAllOutputsOrNone)
{
  const fs::path dir = emptyFolder("publication");
  std::ofstream(dir / "a.json") << "old a";
  {
    Publication outputs;
    OutputFile a((dir / "a.json").string());
    a.write("new a");
    a.commit();
    OutputFile b((dir / "b.json").string());
    b.write("new b");
    b.commit();
    EXPECT_EQ(contents(dir / "a.json"), "old a") << "replaced before the command succeeded";
    EXPECT_FALSE(fs::exists(dir / "b.json"));
  } // destroyed unpublished: the command failed
  EXPECT_EQ(contents(dir / "a.json"), "old a");
  EXPECT_FALSE(fs::exists(dir / "b.json"));
  EXPECT_EQ(filesIn(dir), 1u);
  {
    Publication outputs;
    OutputFile a((dir / "a.json").string());
    a.write("new a");
    a.commit();
    OutputFile b((dir / "b.json").string());
    b.write("new b");
    b.commit();
    outputs.publish();
  }
  EXPECT_EQ(contents(dir / "a.json"), "new a");
  EXPECT_EQ(contents(dir / "b.json"), "new b");
  EXPECT_EQ(filesIn(dir), 2u);
}

TEST(OutputFile, AnUnwritablePlaceIsNamedBeforeAnyWork)
{
  const fs::path dir = emptyFolder("unwritable");
  const fs::path missing = dir / "no-such-folder" / "out.tif";
  EXPECT_NE(test::errorOf([&] { checkOutputPath(missing.string()); }).find(missing.string()),
    std::string::npos);
  fs::create_directories(dir / "folder.tif");
  EXPECT_NE(test::errorOf([&] { checkOutputPath((dir / "folder.tif").string()); }), "");
  EXPECT_EQ(test::errorOf([&] { checkOutputPath((dir / "fine.tif").string()); }), "");
  EXPECT_EQ(filesIn(dir), 1u) << "the trial file beside the target stayed";
}

TEST(OutputFile, OnePublicationDoesNotWriteOneTargetTwice)
{
  const fs::path dir = emptyFolder("twice");
  Publication outputs;
  OutputFile first((dir / "out.json").string());
  EXPECT_NE(test::errorOf([&] { OutputFile second((dir / "out.json").string()); }), "");
}
