// The one way oceanref writes a file (io/output_file.h): nothing an output path names is lost or
// replaced falsely — refusals before any work, checked writes, a temporary removed on failure
// and on a signal, the previous file left intact.
#include <doctest/doctest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "io/exr.h"
#include "io/output_file.h"

namespace fs = std::filesystem;
using namespace oceanref;

namespace {
// A fresh, empty folder per test, removed afterwards.
struct TempFolder {
  fs::path path;
  TempFolder() {
    char name[] = "/tmp/oceanref-output-XXXXXX";
    path = ::mkdtemp(name);
  }
  ~TempFolder() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  // Every entry whose name starts with ".oceanref-": temporaries left behind.
  int temporaries() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(path)) {
      n += e.path().filename().string().rfind(".oceanref-", 0) == 0 ? 1 : 0;
    }
    return n;
  }
};

std::string contents(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void put(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}
}  // namespace

TEST_CASE("output file: written whole, replacing the old one, no temporary left") {
  const TempFolder dir;
  write_output_file(dir / "a.csv", "first\n");
  CHECK(contents(dir / "a.csv") == "first\n");
  write_output_file(dir / "a.csv", "second, longer\n");
  CHECK(contents(dir / "a.csv") == "second, longer\n");
  CHECK(dir.temporaries() == 0);
  // A name of 250 characters (the longest most file systems allow is 255): the temporary's
  // name is short, so it does not overflow.
  const std::string long_name = std::string(246, 'n') + ".exr";
  write_output_file(dir / long_name, "x");
  CHECK(contents(dir / long_name) == "x");
}

TEST_CASE("output file: an uncommitted or failed write leaves the previous file intact") {
  const TempFolder dir;
  put(dir / "keep.exr", "old");
  {
    OutputFile f(dir / "keep.exr");
    f.write("partial");
    CHECK(dir.temporaries() == 1);
  }  // no commit: an exception unwound past it
  CHECK(contents(dir / "keep.exr") == "old");
  CHECK(dir.temporaries() == 0);

  // A write beyond the file size limit (ulimit -f) fails with EFBIG (SIGXFSZ ignored, as the
  // program does): an error naming the file, the old file untouched, no temporary left.
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old_limit{};
  REQUIRE(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  rlimit small = old_limit;
  small.rlim_cur = 4096;
  REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string message;
  try {
    write_output_file(dir / "keep.exr", std::string(10000, 'x'));
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  REQUIRE(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  std::signal(SIGXFSZ, old_handler);
  CHECK(message.find("keep.exr: cannot write") != std::string::npos);
  CHECK(message.find("unchanged") != std::string::npos);
  CHECK(contents(dir / "keep.exr") == "old");
  CHECK(dir.temporaries() == 0);

  // A failed write that its caller swallowed (OpenEXR's destructors do) cannot be committed.
  {
    OutputFile f(dir / "keep.exr");
    REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
    std::signal(SIGXFSZ, SIG_IGN);
    try {
      f.write(std::string(10000, 'y'));
    } catch (const std::runtime_error&) {
    }
    REQUIRE(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    std::signal(SIGXFSZ, old_handler);
    CHECK_THROWS_WITH_AS(f.commit(), doctest::Contains("an earlier write failed"),
                         std::runtime_error);
  }
  CHECK(contents(dir / "keep.exr") == "old");
  CHECK(dir.temporaries() == 0);
}

TEST_CASE("output file: the EXR writers go through it (a failed EXR write keeps the old file)") {
  const TempFolder dir;
  ExrImage image;
  image.width = 64;
  image.height = 64;
  image.channels.push_back({"R", 1, std::vector<float>(64 * 64, 0.5f)});
  write_exr(dir / "r.exr", image);
  const std::string good = contents(dir / "r.exr");
  CHECK(read_exr(dir / "r.exr").channels.at(0).values.at(100) == 0.5f);
  for (float& v : image.channels[0].values)
    v = static_cast<float>(&v - image.channels[0].values.data());
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old_limit{};
  REQUIRE(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  rlimit small = old_limit;
  small.rlim_cur = 1024;  // below the file's size (16 KB of incompressible floats)
  REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
  std::string message;
  try {
    write_exr(dir / "r.exr", image);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  REQUIRE(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  std::signal(SIGXFSZ, old_handler);
  CHECK(message.find("r.exr: cannot write:") != std::string::npos);
  CHECK(contents(dir / "r.exr") == good);
  CHECK(dir.temporaries() == 0);
}

TEST_CASE("output file: an EXR written by rows takes no call after a failed write") {
  const TempFolder dir;
  ExrImage layout;
  layout.width = 64;
  layout.height = 64;
  layout.channels.push_back({"R", 1, {}});
  std::vector<std::vector<float>> band(1, std::vector<float>(64 * 32));
  for (std::size_t i = 0; i < band[0].size(); ++i) band[0][i] = static_cast<float>(i) * 1.37f;
  std::string message;
  {
    ExrRowWriter writer(dir / "rows.exr", layout);
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit old_limit{};
    REQUIRE(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    rlimit small = old_limit;
    small.rlim_cur = 1024;  // below 32 rows of incompressible floats (8 KB)
    REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
    try {
      writer.write_rows(band, 32);
    } catch (const std::runtime_error& e) {
      message = e.what();
    }
    REQUIRE(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    std::signal(SIGXFSZ, old_handler);
    CHECK(message.find("rows.exr: cannot write:") != std::string::npos);
    // The disk has room again, but the file is broken: the next rows and finish() are refused.
    CHECK_THROWS_WITH_AS(writer.write_rows(band, 32), doctest::Contains("after a failed write"),
                         std::logic_error);
    CHECK_THROWS_WITH_AS(writer.finish(), doctest::Contains("after a failed write"),
                         std::logic_error);
  }
  CHECK_FALSE(fs::exists(dir / "rows.exr"));
  CHECK(dir.temporaries() == 0);
}

TEST_CASE("output file: refuses what is not a regular file, follows links by the rule") {
  const TempFolder dir;
  // A directory, a character device, a FIFO: never replaced.
  CHECK_THROWS_WITH_AS(OutputFile(dir.path.string()), doctest::Contains("is a directory"),
                       OutputPathError);
  CHECK_THROWS_WITH_AS(OutputFile("/dev/null"), doctest::Contains("not a regular file"),
                       OutputPathError);
  CHECK(fs::is_character_file("/dev/null"));
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(OutputFile(dir / "fifo"), doctest::Contains("not a regular file"),
                       OutputPathError);
  CHECK(fs::is_fifo(dir / "fifo"));
  // A folder that does not exist.
  CHECK_THROWS_WITH_AS(OutputFile(dir / "no/such/folder.exr"), doctest::Contains("does not exist"),
                       OutputPathError);
  // A link to a file: the file is replaced, the link kept.
  put(dir / "real.csv", "old");
  fs::create_symlink("real.csv", dir / "link.csv");
  write_output_file(dir / "link.csv", "new");
  CHECK(fs::is_symlink(dir / "link.csv"));
  CHECK(contents(dir / "real.csv") == "new");
  // A dangling link is refused, and stays as it was.
  fs::create_symlink("nothing.csv", dir / "dangling.csv");
  CHECK_THROWS_WITH_AS(write_output_file(dir / "dangling.csv", "x"),
                       doctest::Contains("link to nothing"), OutputPathError);
  CHECK(fs::is_symlink(dir / "dangling.csv"));
  CHECK(!fs::exists(dir / "nothing.csv"));
  // A folder where no file can be created (/proc): an error naming the folder.
  CHECK_THROWS_WITH_AS(OutputFile("/proc/oceanref-test.exr"),
                       doctest::Contains("cannot create a temporary file in the folder /proc"),
                       std::runtime_error);
  CHECK(dir.temporaries() == 0);
}

TEST_CASE("output paths: never an input, never the same file twice") {
  const TempFolder dir;
  put(dir / "scene.json", "{}");
  fs::create_symlink("scene.json", dir / "alias.json");
  fs::create_hard_link(dir / "scene.json", dir / "hard.json");
  const std::vector<std::string> inputs{dir / "scene.json"};
  for (const std::string& out :
       {dir / "scene.json", dir / "alias.json", dir / "hard.json", dir / "./scene.json"}) {
    CAPTURE(out);
    CHECK_THROWS_WITH_AS(check_output_paths({{"--output", out}}, inputs),
                         doctest::Contains(("--output: " + out + ": is the input").c_str()),
                         OutputPathError);
  }
  // The same new file twice, spelt two ways.
  CHECK_THROWS_WITH_AS(
      check_output_paths({{"--output", dir / "a.exr"}, {"--png", dir / "./a.exr"}}, inputs),
      doctest::Contains("--png and --output name the same file"), OutputPathError);
  // Distinct outputs, empty ones (not asked for) skipped: fine.
  CHECK_THROWS_WITH_AS(check_output_paths({{"--output", "rel.exr"}, {"--png", "./rel.exr"}}, {}),
                       doctest::Contains("--png and --output name the same file"), OutputPathError);
  CHECK_NOTHROW(check_output_paths(
      {{"--output", dir / "a.exr"}, {"--png", dir / "a.png"}, {"--json", ""}}, inputs));
  CHECK(contents(dir / "scene.json") == "{}");
}

TEST_CASE("output file: a signal mid-write removes the temporary (the program's handlers)") {
  const TempFolder dir;
  put(dir / "out.exr", "old");
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    remove_output_temporaries_on_signals();
    OutputFile f(dir / "out.exr");
    f.write("half of a file");
    std::raise(SIGTERM);
    ::_exit(0);  // not reached: SIGTERM's default action ends the process
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(contents(dir / "out.exr") == "old");
  CHECK(dir.temporaries() == 0);
}

TEST_CASE("output file: a committed file gives back its own signal slot, no other file's") {
  // The handler removes the temporaries of the files being written: committing (and destroying)
  // some files must leave the slots of the others in place. Many files in turn, then two at
  // once, the one opened first committed; a signal must still remove the other's temporary.
  const TempFolder dir;
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    remove_output_temporaries_on_signals();
    for (int i = 0; i < 40; ++i) write_output_file(dir / ("done" + std::to_string(i)), "x");
    std::optional<OutputFile> other(std::in_place, dir / "other.exr");  // slot 0
    OutputFile writing(dir / "writing.exr");                            // slot 1
    writing.write("half of a file");
    other->write("a whole file");
    other->commit();
    other.reset();
    std::raise(SIGTERM);
    ::_exit(0);  // not reached
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(dir.temporaries() == 0);
  CHECK(contents(dir / "other.exr") == "a whole file");
  CHECK_FALSE(fs::exists(dir / "writing.exr"));
}

TEST_CASE("output file: a file written when every signal slot is taken releases no other's slot") {
  // 64 files at once, more than the handler's slots (16): the first ones hold the slots, the
  // rest are written without removal on a signal. Committing and closing those must leave the
  // slots of the first ones in place, so a signal still removes every temporary left.
  const TempFolder dir;
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    remove_output_temporaries_on_signals();
    std::vector<std::optional<OutputFile>> files(64);
    for (std::size_t i = 0; i < files.size(); ++i) {
      files[i].emplace(dir / ("file" + std::to_string(i)));
      files[i]->write("half of a file");
    }
    for (std::size_t i = 32; i < files.size(); ++i) {
      files[i]->commit();
      files[i].reset();
    }
    std::raise(SIGTERM);
    ::_exit(0);  // not reached
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  // The 32 committed files are there; the temporaries of the 16 files with slots are gone. The
  // 16 without a slot (files 16-31, neither committed nor removed) leave their temporaries.
  for (int i = 0; i < 64; ++i) CHECK(fs::exists(dir / ("file" + std::to_string(i))) == (i >= 32));
  CHECK(dir.temporaries() == 16);
}
