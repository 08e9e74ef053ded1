#include "io/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <system_error>

#ifdef OCEANREF_GCOV_DUMP
// tools/mutation.py's coverage build only: the coverage runtime's counters, written out by a
// process that a signal ends (which would otherwise lose them).
extern "C" void __gcov_dump(void);
#endif

namespace oceanref {

namespace fs = std::filesystem;

namespace {

// ---- Temporaries a signal handler can remove -------------------------------------------------
// The one piece of process-wide state in the library: a signal handler can reach nothing else.
// A slot is free (0), being written (1) or holds the name of a live temporary (2); the handler
// only reads slots in state 2 and calls only unlink(2), which is async-signal-safe. A temporary
// whose name does not fit, or that finds every slot taken, is written all the same, only without
// removal on a signal.
struct TemporarySlot {
  std::atomic<int> state{0};
  char path[4096] = {};
};
TemporarySlot g_temporaries[16];

int claim_slot(const std::string& path) {
  if (path.size() >= sizeof(TemporarySlot::path)) return -1;
  for (int i = 0; i < static_cast<int>(std::size(g_temporaries)); ++i) {
    int expected = 0;
    if (g_temporaries[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_temporaries[i].path, path.c_str(), path.size() + 1);
      g_temporaries[i].state.store(2);
      return i;
    }
  }
  return -1;
}

void release_slot(int slot) {
  if (slot >= 0) g_temporaries[slot].state.store(0);
}

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  for (TemporarySlot& slot : g_temporaries) {
    if (slot.state.load() == 2) ::unlink(slot.path);
  }
#ifdef OCEANREF_GCOV_DUMP
  __gcov_dump();
#endif
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

std::string describe(const std::string& flag, const std::string& path) {
  return flag.empty() ? path : flag + ": " + path;
}

std::string error_text(int error) {
  return std::generic_category().message(error);
}

}  // namespace

std::string resolve_output_path(const std::string& flag, const std::string& path) {
  const std::string who = describe(flag, path);
  if (path.empty()) throw OutputPathError(flag + ": the output path is empty");
  std::error_code error;
  fs::path target(path);
  if (fs::is_symlink(fs::symlink_status(target, error))) {
    if (!fs::exists(fs::status(target, error))) {
      throw OutputPathError(who + ": a symbolic link to nothing; give the file's own path");
    }
    target = fs::canonical(target, error);  // the file the chain of links names
    if (error) throw OutputPathError(who + ": cannot follow the link: " + error.message());
  }
  const fs::file_status status = fs::status(target, error);
  if (fs::exists(status)) {
    if (fs::is_directory(status)) throw OutputPathError(who + ": is a directory");
    if (!fs::is_regular_file(status)) {
      throw OutputPathError(who +
                            ": is not a regular file (a device, FIFO or socket); oceanref "
                            "replaces only regular files");
    }
  } else {
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (!fs::is_directory(folder, error)) {
      throw OutputPathError(who + ": the folder " + folder.string() + " does not exist");
    }
  }
  return target.string();
}

void check_output_paths(const std::vector<OutputPath>& outputs,
                        const std::vector<std::string>& inputs) {
  std::map<std::string, std::string> seen;  // weakly canonical path -> flag
  for (const OutputPath& o : outputs) {
    if (o.path.empty()) continue;
    const std::string target = resolve_output_path(o.flag, o.path);
    std::error_code error;
    if (fs::exists(target, error)) {
      for (const std::string& input : inputs) {
        if (fs::exists(input, error) && fs::equivalent(input, target, error)) {
          throw OutputPathError(describe(o.flag, o.path) + ": is the input " + input +
                                "; write the output to another file");
        }
      }
    }
    const std::string key = fs::weakly_canonical(fs::absolute(target, error), error).string();
    const auto [where, inserted] = seen.emplace(error ? target : key, o.flag);
    if (!inserted) {
      throw OutputPathError(o.flag + " and " + where->second + " name the same file " + o.path +
                            "; give each output its own file");
    }
  }
}

OutputFile::OutputFile(const std::string& path)
    : path_(path), target_(resolve_output_path("", path)) {
  const fs::path target(target_);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int n = 0; fd_ < 0; ++n) {
    temporary_ =
        (folder / (".oceanref-" + std::to_string(::getpid()) + "-" + std::to_string(n) + ".tmp"))
            .string();
    release_slot(signal_slot_);
    signal_slot_ = claim_slot(temporary_);
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0 && (errno != EEXIST || n == 999)) {
      const int error = errno;
      release_slot(signal_slot_);  // fail throws: no destructor runs for this object
      fail("cannot create a temporary file in the folder " + folder.string(), error);
    }
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
  release_slot(signal_slot_);
}

void OutputFile::fail(const std::string& what, int error) {
  failed_ = true;
  throw OutputWriteError(path_ + ": " + what + ": " + error_text(error) +
                         " (the previous file, if any, is unchanged)");
}

void OutputFile::write(const void* bytes, std::size_t count) {
  const char* p = static_cast<const char*>(bytes);
  while (count > 0) {
    const ssize_t n = ::write(fd_, p, count);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write", n < 0 ? errno : ENOSPC);
    p += n;
    count -= static_cast<std::size_t>(n);
    position_ += static_cast<std::uint64_t>(n);
  }
}

void OutputFile::seek(std::uint64_t offset) {
  if (::lseek(fd_, static_cast<off_t>(offset), SEEK_SET) < 0) fail("cannot seek", errno);
  position_ = offset;
}

void OutputFile::commit() {
  // A write that failed inside a caller that swallowed the exception (OpenEXR's destructors
  // do) must not become a file.
  if (failed_) fail("an earlier write failed", EIO);
  if (::fsync(fd_) != 0) fail("cannot flush to disk", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot close", errno);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
    fail("cannot rename the finished temporary file over it", errno);
  }
  committed_ = true;
  release_slot(signal_slot_);
  signal_slot_ = -1;
  // Make the rename itself durable; a folder that cannot be fsync'ed (some file systems refuse)
  // does not undo a written file.
  const fs::path target(target_);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

void write_output_file(const std::string& path, std::string_view bytes) {
  OutputFile file(path);
  file.write(bytes);
  file.commit();
}

void remove_output_temporaries_on_signals() {
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, remove_temporaries_and_reraise);
  std::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace oceanref
