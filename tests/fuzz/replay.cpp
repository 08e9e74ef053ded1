// The crash-regression replay (a plain program, no libFuzzer): every file under
// tests/fuzz/regressions/<target>/ (inputs that once crashed or were slow, and interesting
// seeds) and tests/fuzz/corpus/<target>/ runs through the target's entry function
// (fuzz_entries.h). A clean validation error or success passes; anything else aborts (the entry
// prints the file's target and the exception first), and in the sanitizer build a sanitizer
// report fails the run.
//
//   oceanref_fuzz_replay TARGET DIR...
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/fp_environment.h"
#include "fuzz_entries.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: oceanref_fuzz_replay scene|cli|exr DIR...\n");
    return 2;
  }
  const oceanref::fuzz::Entry entry = oceanref::fuzz::entry_for(argv[1]);
  if (entry == nullptr) {
    std::fprintf(stderr,
                 "oceanref_fuzz_replay: unknown target '%s' (scene, cli, exr, piece, obj)\n",
                 argv[1]);
    return 2;
  }
  const oceanref::ReferenceFpEnvironment fp;
  std::vector<std::filesystem::path> files;
  for (int i = 2; i < argc; ++i) {
    if (!std::filesystem::is_directory(argv[i])) {
      std::fprintf(stderr, "oceanref_fuzz_replay: %s is not a directory\n", argv[i]);
      return 2;
    }
    for (const auto& e : std::filesystem::recursive_directory_iterator(argv[i])) {
      if (e.is_regular_file()) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "oceanref_fuzz_replay: no input files\n");
    return 1;
  }
  for (const auto& path : files) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    std::fprintf(stderr, "%s\n", path.string().c_str());
    std::fflush(stderr);
    entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("oceanref_fuzz_replay %s: %zu inputs replayed, no crash\n", argv[1], files.size());
  return 0;
}
