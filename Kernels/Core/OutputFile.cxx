#include "OutputFile.h"

#include "Error.h"

#include <atomic>
#include <cerrno>
#include <climits>
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

// The temporaries being written, as fixed buffers a signal handler may read. A command writes
// one to three files at a time; a temporary beyond this many is still removed by its
// destructor, only not by a signal.
constexpr int kMaxLiveTemporaries = 16;

struct LiveTemporary
{
  std::atomic<bool> used{ false };
  std::atomic<bool> ready{ false }; // path complete, safe for a signal handler to read
  char path[PATH_MAX] = {};
};

LiveTemporary liveTemporaries[kMaxLiveTemporaries];

int registerTemporary(const std::string& path)
{
  if (path.size() >= PATH_MAX)
  {
    return -1;
  }
  for (int s = 0; s < kMaxLiveTemporaries; ++s)
  {
    bool expected = false;
    if (liveTemporaries[s].used.compare_exchange_strong(expected, true))
    {
      std::memcpy(liveTemporaries[s].path, path.c_str(), path.size() + 1);
      liveTemporaries[s].ready.store(true);
      return s;
    }
  }
  return -1;
}

void releaseTemporary(int slot)
{
  if (slot >= 0)
  {
    liveTemporaries[slot].ready.store(false);
    liveTemporaries[slot].used.store(false);
  }
}

} // namespace

void OutputFile::removeLiveTemporaries()
{
  for (LiveTemporary& t : liveTemporaries)
  {
    if (t.ready.load())
    {
      ::unlink(t.path);
    }
  }
}

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
  slot_ = registerTemporary(temporary_);
}

OutputFile::~OutputFile()
{
  if (!committed_)
  {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
  releaseTemporary(slot_);
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
  // Released after the rename: a signal in between unlinks a name that no longer exists.
  releaseTemporary(slot_);
  slot_ = -1;
}

} // namespace tsynth
