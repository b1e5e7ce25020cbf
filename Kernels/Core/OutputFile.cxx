#include "OutputFile.h"

#include "Error.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <mutex>
#include <pthread.h>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace tsynth
{

namespace
{

fs::path folderOf(const fs::path& target)
{
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// The target's extension goes on the temporary (a writer may look at it) unless it is
// unusually long: the temporary's name stays far below any file system's name limit.
constexpr std::size_t kLongestKeptExtension = 16;

std::atomic<unsigned> temporaryCount{ 0 };

fs::path temporaryFor(const fs::path& target)
{
  std::string ext = target.extension().string();
  if (ext.size() > kLongestKeptExtension)
  {
    ext.clear();
  }
  return folderOf(target) /
    (".tsynth-" + std::to_string(::getpid()) + "-" + std::to_string(temporaryCount++) + ".tmp" +
      ext);
}

std::string errnoText(int code)
{
  return std::strerror(code);
}

// The temporaries being written, as fixed buffers a signal handler may read. A command writes
// a handful at a time (a debug folder about ten); a temporary beyond this many is still
// removed by its destructor or its Publication, only not by a signal.
constexpr int kMaxLiveTemporaries = 64;

struct LiveTemporary
{
  std::atomic<bool> used{ false };
  std::atomic<bool> ready{ false }; // path complete, safe for a signal handler to read
  char path[PATH_MAX] = {};
};

LiveTemporary liveTemporaries[kMaxLiveTemporaries];

// The folders the open Publication created, for a signal handler to remove (rmdir: only if
// empty) when the process dies; more than this many nested new folders are removed only by
// the Publication's destructor.
constexpr int kMaxCreatedFolders = 8;
LiveTemporary createdFolders[kMaxCreatedFolders];
std::atomic<int> createdFolderCount{ 0 };

void registerCreatedFolder(const std::string& path)
{
  const int k = createdFolderCount.load();
  if (k < kMaxCreatedFolders && path.size() < PATH_MAX)
  {
    std::memcpy(createdFolders[k].path, path.c_str(), path.size() + 1);
    createdFolders[k].ready.store(true);
    createdFolderCount.store(k + 1);
  }
}

void forgetCreatedFolders()
{
  for (LiveTemporary& f : createdFolders)
  {
    f.ready.store(false);
  }
  createdFolderCount.store(0);
}

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

// What a file's name resolves to: symlinks in its folder and "." or ".." removed. Two
// outputs of one command with the same key would replace each other.
std::string pathKey(const std::string& path)
{
  std::error_code ec;
  const fs::path key = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? path : key.string();
}

// The kinds of file an output must never replace, named for the refusal.
const char* nonRegularKind(const struct stat& st)
{
  if (S_ISDIR(st.st_mode))
  {
    return "a folder";
  }
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode))
  {
    return "a device";
  }
  if (S_ISFIFO(st.st_mode))
  {
    return "a pipe (FIFO)";
  }
  if (S_ISSOCK(st.st_mode))
  {
    return "a socket";
  }
  return S_ISREG(st.st_mode) ? nullptr : "not a regular file";
}

// Makes sure what the writer left at `temporary` is on disk: not missing, not empty, and
// fsync and close succeed.
void checkWritten(const std::string& temporary, const std::string& target)
{
  const int fd = ::open(temporary.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0)
  {
    throw Error("Cannot write " + target + ": nothing was written.");
  }
  struct stat st
  {
  };
  const bool empty = ::fstat(fd, &st) != 0 || st.st_size == 0;
  const int synced = ::fsync(fd);
  const int syncError = errno;
  const int closed = ::close(fd);
  if (empty)
  {
    throw Error("Cannot write " + target + ": the file came out empty (is the disk full?).");
  }
  if (synced != 0 && syncError != EINVAL && syncError != EROFS)
  {
    throw Error("Cannot write " + target + ": " + errnoText(syncError) + ".");
  }
  if (closed != 0)
  {
    throw Error("Cannot write " + target + ": " + errnoText(errno) + ".");
  }
}

// The signals that end a process by default and that a user or the system sends: held while
// a Publication renames, so a command's outputs appear together.
void terminatingSignals(sigset_t& set)
{
  sigemptyset(&set);
  for (int sig :
    { SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2, SIGXCPU, SIGXFSZ })
  {
    sigaddset(&set, sig);
  }
}

struct Staged
{
  std::string temporary;
  std::string target;
  int slot = -1;
};

struct PublicationState
{
  std::mutex mutex;
  bool open = false;
  std::vector<std::string> targetKeys; // of every OutputFile made while open
  std::vector<Staged> staged;
  std::vector<std::string> folders;
};

PublicationState& publication()
{
  static PublicationState state;
  return state;
}

void discardStaged(std::vector<Staged>& staged)
{
  for (const Staged& s : staged)
  {
    std::error_code ec;
    fs::remove(s.temporary, ec);
    releaseTemporary(s.slot);
  }
  staged.clear();
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
  for (int k = createdFolderCount.load() - 1; k >= 0; --k)
  {
    if (createdFolders[k].ready.load())
    {
      ::rmdir(createdFolders[k].path);
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
  struct stat st
  {
  };
  if (::stat(target.c_str(), &st) == 0)
  {
    if (const char* kind = nonRegularKind(st))
    {
      throw Error("Cannot write " + target + ": it is " + kind +
        ", which an output never replaces; give a file name.");
    }
  }
  // The probe is a live temporary too: a signal between its creation and its removal must
  // not leave it behind.
  const std::string probe = temporaryFor(p).string();
  const int slot = registerTemporary(probe);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
  {
    const int code = errno;
    releaseTemporary(slot);
    throw Error("Cannot write " + target + ": " + errnoText(code) + ".");
  }
  ::close(fd);
  ::unlink(probe.c_str());
  releaseTemporary(slot);
}

OutputFile::OutputFile(std::string target)
  : target_(std::move(target))
{
  checkOutputPath(target_);
  PublicationState& pub = publication();
  {
    const std::lock_guard<std::mutex> lock(pub.mutex);
    if (pub.open)
    {
      const std::string key = pathKey(target_);
      if (std::find(pub.targetKeys.begin(), pub.targetKeys.end(), key) != pub.targetKeys.end())
      {
        throw Error("Cannot write " + target_ +
          " twice in one command: two of its outputs have that name; give them different names.");
      }
      pub.targetKeys.push_back(key);
    }
  }
  temporary_ = temporaryFor(fs::path(target_)).string();
  slot_ = registerTemporary(temporary_);
}

OutputFile::~OutputFile()
{
  if (!committed_)
  {
    std::error_code ec;
    fs::remove(temporary_, ec);
    releaseTemporary(slot_);
  }
}

void OutputFile::write(const std::string& bytes)
{
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
  {
    throw Error("Cannot write " + target_ + ": " + errnoText(errno) + ".");
  }
  std::size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      const int code = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw Error("Cannot write " + target_ + ": " + errnoText(code) + ".");
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0)
  {
    throw Error("Cannot write " + target_ + ": " + errnoText(errno) + ".");
  }
}

void OutputFile::commit()
{
  checkWritten(temporary_, target_);
  PublicationState& pub = publication();
  {
    const std::lock_guard<std::mutex> lock(pub.mutex);
    if (pub.open)
    {
      pub.staged.push_back({ temporary_, target_, slot_ });
      committed_ = true; // the Publication owns the temporary and its slot now
      return;
    }
  }
  std::error_code ec;
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

Publication::Publication()
{
  PublicationState& pub = publication();
  const std::lock_guard<std::mutex> lock(pub.mutex);
  if (pub.open)
  {
    throw Error("Internal error: two Publications open at once.");
  }
  pub.open = true;
}

Publication::~Publication()
{
  PublicationState& pub = publication();
  const std::lock_guard<std::mutex> lock(pub.mutex);
  discardStaged(pub.staged);
  for (auto f = pub.folders.rbegin(); f != pub.folders.rend(); ++f)
  {
    ::rmdir(f->c_str()); // only if empty: a folder that holds anything else stays
  }
  pub.folders.clear();
  forgetCreatedFolders();
  pub.targetKeys.clear();
  pub.open = false;
}

void createOutputFolder(const std::string& path)
{
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = fs::absolute(path, ec); !p.empty() && !fs::exists(p, ec); p = p.parent_path())
  {
    missing.push_back(p);
    if (p == p.parent_path())
    {
      break;
    }
  }
  PublicationState& pub = publication();
  for (auto p = missing.rbegin(); p != missing.rend(); ++p)
  {
    if (!fs::create_directory(*p, ec) && ec)
    {
      throw Error("Cannot create the folder " + path + ": " + ec.message() + ".");
    }
    const std::lock_guard<std::mutex> lock(pub.mutex);
    if (pub.open)
    {
      pub.folders.push_back(p->string());
      registerCreatedFolder(p->string());
    }
  }
  if (!fs::is_directory(path, ec))
  {
    throw Error("Cannot create the folder " + path + ": a file of that name is in the way.");
  }
}

bool Publication::isOpen()
{
  PublicationState& pub = publication();
  const std::lock_guard<std::mutex> lock(pub.mutex);
  return pub.open;
}

void Publication::publish()
{
  publishStagedOutputs();
}

void publishStagedOutputs()
{
  PublicationState& pub = publication();
  const std::lock_guard<std::mutex> lock(pub.mutex);
  sigset_t held;
  sigset_t before;
  terminatingSignals(held);
  pthread_sigmask(SIG_BLOCK, &held, &before);
  std::string failure;
  std::size_t done = 0;
  for (; done < pub.staged.size(); ++done)
  {
    const Staged& s = pub.staged[done];
    std::error_code ec;
    fs::rename(s.temporary, s.target, ec);
    if (ec)
    {
      failure = "Cannot write " + s.target + ": " + ec.message() + ".";
      break;
    }
    releaseTemporary(s.slot);
  }
  pub.staged.erase(pub.staged.begin(), pub.staged.begin() + static_cast<std::ptrdiff_t>(done));
  discardStaged(pub.staged);
  pub.folders.clear(); // published into: kept
  forgetCreatedFolders();
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (!failure.empty())
  {
    throw Error(failure);
  }
}

} // namespace tsynth
