#include "OutputFile.h"

#include "Error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace tsynth
{

namespace
{

fs::path folderOf(const fs::path& target)
{
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

fs::path temporaryFor(const fs::path& target)
{
  return folderOf(target) /
    ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()));
}

} // namespace

void checkOutputPath(const std::string& target)
{
  const fs::path p(target);
  const fs::path dir = folderOf(p);
  std::error_code ec;
  if (!fs::exists(dir, ec))
  {
    throw Error("Cannot write " + target + ": folder " + dir.string() + " does not exist.");
  }
  if (!fs::is_directory(dir, ec))
  {
    throw Error("Cannot write " + target + ": " + dir.string() + " is a file, not a folder.");
  }
  if (fs::is_directory(p, ec))
  {
    throw Error("Cannot write " + target + ": it is a folder; give a file name.");
  }
  const std::string probe = temporaryFor(p).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0)
  {
    if (errno == EEXIST)
    {
      return; // this process's own temporary of a write under way
    }
    throw Error("Cannot write " + target + ": " + std::strerror(errno) + ".");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

OutputFile::OutputFile(std::string target)
  : target_(std::move(target))
{
  checkOutputPath(target_);
  temporary_ = temporaryFor(fs::path(target_)).string();
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
