#include "io/file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/errors.h"

namespace octrace {

namespace {
// The temporaries written and not yet renamed (writes happen on the main
// thread), for remove_file_being_written: the first kPending of a set.
constexpr int kPending = 8;
char g_writing[kPending][4096];
std::atomic<bool> g_is_writing[kPending];

// Where the temporary of slot k is tracked, if its name fits.
void track(int k, const std::string& tmp) {
  if (k >= kPending || tmp.size() >= sizeof g_writing[k]) return;
  std::memcpy(g_writing[k], tmp.c_str(), tmp.size() + 1);
  g_is_writing[k] = true;
}
void untrack(int k) {
  if (k < kPending) g_is_writing[k] = false;
}

// Writes `size` bytes to a new temporary beside `path` and flushes it to
// disk; returns its name. On failure nothing is left and RuntimeError
// "PATH: WHAT: reason" is thrown.
std::string write_temporary(int slot, const std::string& path, const void* data, size_t size, const std::string& what) {
  // A name of our own with O_EXCL rather than mkstemp: mkstemp creates the
  // file 0600, and the renamed result should get the usual permissions.
  static std::atomic<uint64_t> counter{0};
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  track(slot, tmp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    untrack(slot);
    throw RuntimeError(path + ": " + what + ": " + std::strerror(errno));
  }
  const auto fail = [&](int err, bool open) {
    if (open) ::close(fd);
    ::unlink(tmp.c_str());
    untrack(slot);
    throw RuntimeError(path + ": " + what + ": " + std::strerror(err));
  };
  const char* bytes = static_cast<const char*>(data);
  for (size_t done = 0; done < size;) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(errno, true);
    done += static_cast<size_t>(n);
  }
  // fsync before rename: otherwise a crash can leave the new name with empty contents.
  if (::fsync(fd) != 0) fail(errno, true);
  if (::close(fd) != 0) fail(errno, false);
  return tmp;
}
}  // namespace

void remove_file_being_written() noexcept {
  for (int k = 0; k < kPending; ++k)
    if (g_is_writing[k].load()) ::unlink(g_writing[k]);
}

void write_file_atomically(const std::string& path, const void* data, size_t size, const std::string& what) {
  write_files_atomically({{path, data, size, what}});
}

void write_files_atomically(const std::vector<FileToWrite>& files) {
  std::vector<std::string> temps;
  // The temporaries from `first` on removed (those before it are renamed).
  const auto discard = [&](size_t first) {
    for (size_t k = first; k < temps.size(); ++k) {
      ::unlink(temps[k].c_str());
      untrack(int(k));
    }
  };
  // Every file to its temporary first; a failure removes those written.
  try {
    for (const FileToWrite& f : files)
      temps.push_back(write_temporary(int(temps.size()), f.path, f.data, f.size, f.what));
  } catch (const RuntimeError&) {
    discard(0);
    throw;
  }
  // Then the renames, each atomic; only one failing here (rare: the
  // temporary was made in the same folder) leaves the ones before it.
  for (size_t k = 0; k < temps.size(); ++k) {
    if (std::rename(temps[k].c_str(), files[k].path.c_str()) != 0) {
      const int err = errno;
      discard(k);
      throw RuntimeError(files[k].path + ": " + files[k].what + ": " + std::strerror(err));
    }
    untrack(int(k));
  }
}

std::string read_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open file: " + std::strerror(errno));
  std::string text;
  struct stat st {};
  if (::fstat(fd, &st) == 0 && st.st_size > 0) text.reserve(static_cast<size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw InputError(path + ": cannot read file: " + std::strerror(err));
    }
    text.append(buf, static_cast<size_t>(n));
  }
  ::close(fd);
  return text;
}

void check_output_folder(const std::string& path) {
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) throw InputError(path + ": folder does not exist");
  if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not a file");
  // access(W_OK) says yes to root for a read-only file system or /proc: make
  // (and remove) a file of our own there, as write_file_atomically will.
  const std::string probe = path + ".tmp-check-" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) throw InputError(path + ": cannot write in its folder: " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace octrace
