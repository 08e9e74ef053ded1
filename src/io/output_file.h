// The one way oceanref writes a file, so that no output path loses data or reports success
// falsely (every writer — EXR, PNG, CSV, JSON, HTML, the golden manifest — goes through it):
//
// - The target is checked first: an existing target must be a regular file (a device, FIFO,
//   socket or directory is refused, never replaced); a symbolic link is followed — the file it
//   names is replaced and the link kept — and a dangling link is refused; the target's folder
//   must exist.
// - The bytes go to a new temporary file with a short name (`.oceanref-<pid>-<n>.tmp`, so a
//   target name of any legal length works) in the target's folder; every write is checked,
//   the file is fsync'ed and closed (both checked), then renamed over the target and the folder
//   fsync'ed. Any failure throws OutputWriteError naming the target and the cause, removes the
//   temporary and leaves the previous target untouched.
// - A program that calls remove_output_temporaries_on_signals() once (the oceanref program
//   does; a host such as Python keeps its own handlers) has temporaries removed on SIGINT,
//   SIGTERM and SIGHUP, before the signal takes its default action.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace oceanref {

// A bad output path (refused before anything is written); `what()` names the flag.
class OutputPathError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A write that failed (after the path was accepted); `what()` names the file and the cause.
class OutputWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output of one command: the flag or key that named it, for messages, and its path.
struct OutputPath {
  std::string flag;
  std::string path;
};

// The file a write to `path` replaces: `path`, or what its chain of symbolic links names.
// Throws OutputPathError (prefixed with `flag`) for a dangling link, an existing non-regular
// file, or a folder that does not exist.
std::string resolve_output_path(const std::string& flag, const std::string& path);

// Checks a command's outputs before any work: each resolves (resolve_output_path); none is the
// same file as one of `inputs` (existing files, compared by device and inode, so links and
// other spellings are caught) or as another output. Empty paths (an output not asked for) are
// skipped. Throws OutputPathError naming the flag.
void check_output_paths(const std::vector<OutputPath>& outputs,
                        const std::vector<std::string>& inputs);

// A file being written (see the file comment). Not committed: the destructor removes the
// temporary and the target stays as it was.
class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(const void* bytes, std::size_t count);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Moves the write position (OpenEXR writes its offset table last).
  void seek(std::uint64_t offset);
  std::uint64_t position() const { return position_; }
  // fsync, close, rename over the target, fsync the folder.
  void commit();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const std::string& what, int error);
  std::string path_;       // as given, for messages
  std::string target_;     // the file replaced (links followed)
  std::string temporary_;  // in the target's folder
  int fd_ = -1;
  int signal_slot_ = -1;
  std::uint64_t position_ = 0;
  bool committed_ = false;
  bool failed_ = false;  // a write failed: commit() refuses
};

// Writes `bytes` to `path` through an OutputFile.
void write_output_file(const std::string& path, std::string_view bytes);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every live temporary and then
// re-raise the signal with its default action, and ignores SIGXFSZ so that a file size limit
// (ulimit -f) is a write error, not a kill. For programs, not libraries; call once in main.
void remove_output_temporaries_on_signals();

}  // namespace oceanref
