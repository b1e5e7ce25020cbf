#include "OutputFile.h"

#include "Error.h"

#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace tsynth
{

OutputFile::OutputFile(std::string target)
  : target_(std::move(target))
{
  const fs::path p(target_);
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
  {
    throw Error("Cannot write " + target_ + ": folder " + dir.string() + " does not exist.");
  }
  temporary_ =
    (dir / ("." + p.filename().string() + ".tmp-" + std::to_string(::getpid()))).string();
}

OutputFile::~OutputFile()
{
  if (!committed_)
  {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void OutputFile::commit()
{
  std::error_code ec;
  if (!fs::exists(temporary_, ec))
  {
    throw Error("Cannot write " + target_ + ": nothing was written.");
  }
  fs::rename(temporary_, target_, ec);
  if (ec)
  {
    throw Error("Cannot write " + target_ + ": " + ec.message() + ".");
  }
  committed_ = true;
}

} // namespace tsynth
