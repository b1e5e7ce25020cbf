// A fault-injection shim for the output layer's error paths, loaded with LD_PRELOAD into a
// tsynth under test. It acts only on writes to tsynth's temporaries (".tsynth-PID-N.tmp..."),
// whichever library makes them (GDAL through fwrite, the output layer through write):
//
//   TSYNTH_FAULT_FAIL_AFTER=N   after N bytes in all, every further write fails with ENOSPC,
//                               as on a disk that fills up at that byte;
//   TSYNTH_FAULT_PAUSE_FILE=K   on the first write to the K-th temporary (from 1), creates the
//   TSYNTH_FAULT_MARKER=PATH    file PATH and sleeps until a signal arrives (at most
//                               kLongestPauseS), so a test can signal a command at a known
//                               point: in the middle of its K-th file.
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <dlfcn.h>
#include <fcntl.h>
#include <string>
#include <sys/uio.h>
#include <unistd.h>

namespace
{

constexpr const char* kTemporaryMark = "/.tsynth-";
constexpr int kLongestPauseS = 30;
constexpr int kMaxTrackedFds = 4096;

std::atomic<long long> bytesWritten{ 0 };
std::atomic<int> temporariesSeen{ 0 };
std::atomic<bool> seen[kMaxTrackedFds];

long long envNumber(const char* name, long long fallback)
{
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::atoll(v) : fallback;
}

bool isTemporary(int fd)
{
  char link[64];
  char target[4096];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = ::readlink(link, target, sizeof target - 1);
  if (n <= 0)
  {
    return false;
  }
  target[n] = '\0';
  return std::strstr(target, kTemporaryMark) != nullptr;
}

void pauseIfAsked(int fd)
{
  if (fd < 0 || fd >= kMaxTrackedFds || seen[fd].exchange(true))
  {
    return;
  }
  const int k = ++temporariesSeen;
  const char* marker = std::getenv("TSYNTH_FAULT_MARKER");
  if (marker == nullptr || k != envNumber("TSYNTH_FAULT_PAUSE_FILE", -1))
  {
    return;
  }
  const int m = ::open(marker, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (m >= 0)
  {
    ::close(m);
  }
  timespec pause{ kLongestPauseS, 0 };
  ::nanosleep(&pause, nullptr); // a signal ends it early
}

// How many of `size` bytes to `fd` may go through: all, or (past the limit) none.
bool allowed(int fd, std::size_t size)
{
  if (!isTemporary(fd))
  {
    return true;
  }
  pauseIfAsked(fd);
  const long long limit = envNumber("TSYNTH_FAULT_FAIL_AFTER", -1);
  const long long total =
    bytesWritten.fetch_add(static_cast<long long>(size)) + static_cast<long long>(size);
  if (limit >= 0 && total > limit)
  {
    errno = ENOSPC;
    return false;
  }
  return true;
}

template<typename F>
F real(const char* name)
{
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

} // namespace

extern "C"
{

  ssize_t write(int fd, const void* data, size_t size)
  {
    static auto next = real<ssize_t (*)(int, const void*, size_t)>("write");
    return allowed(fd, size) ? next(fd, data, size) : -1;
  }

  ssize_t pwrite(int fd, const void* data, size_t size, off_t offset)
  {
    static auto next = real<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite");
    return allowed(fd, size) ? next(fd, data, size, offset) : -1;
  }

  ssize_t pwrite64(int fd, const void* data, size_t size, off_t offset)
  {
    static auto next = real<ssize_t (*)(int, const void*, size_t, off_t)>("pwrite64");
    return allowed(fd, size) ? next(fd, data, size, offset) : -1;
  }

  ssize_t writev(int fd, const struct iovec* iov, int count)
  {
    static auto next = real<ssize_t (*)(int, const struct iovec*, int)>("writev");
    std::size_t size = 0;
    for (int k = 0; k < count; ++k)
    {
      size += iov[k].iov_len;
    }
    return allowed(fd, size) ? next(fd, iov, count) : -1;
  }

  // A closed descriptor's number comes back for the next file: it is a new temporary then.
  int close(int fd)
  {
    static auto next = real<int (*)(int)>("close");
    if (fd >= 0 && fd < kMaxTrackedFds)
    {
      seen[fd].store(false);
    }
    return next(fd);
  }

  int fclose(FILE* stream)
  {
    static auto next = real<int (*)(FILE*)>("fclose");
    const int fd = ::fileno(stream);
    if (fd >= 0 && fd < kMaxTrackedFds)
    {
      seen[fd].store(false);
    }
    return next(stream);
  }

  size_t fwrite(const void* data, size_t size, size_t count, FILE* stream)
  {
    static auto next = real<size_t (*)(const void*, size_t, size_t, FILE*)>("fwrite");
    return allowed(::fileno(stream), size * count) ? next(data, size, count, stream) : 0;
  }

} // extern "C"
