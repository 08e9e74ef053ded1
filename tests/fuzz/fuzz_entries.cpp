#include "fuzz_entries.h"

#include <ImfHeader.h>
#include <unistd.h>
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "cli/brdf_command.h"
#include "cli/sky_command.h"
#include "cli/spectrum_command.h"
#include "conformance/compare.h"
#include "conformance/render_piece.h"
#include "io/exr.h"
#include "io/obj_mesh.h"
#include "scene/scene.h"

namespace oceanref::fuzz {

namespace {

[[noreturn]] void finding(const char* target, const std::string& what) {
  std::fprintf(stderr, "oceanref fuzz %s: not a clean validation error: %s\n", target,
               what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs `body`; validation errors (std::runtime_error — SceneError, CLI11's parse errors, the
// readers' errors, NonFiniteOutputError — and std::invalid_argument, UsageError's base) are clean;
// any other exception is a finding.
template <typename Body>
void guarded(const char* target, Body&& body) {
  try {
    body();
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    finding(target, std::string("exception ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    finding(target, "an exception not derived from std::exception");
  }
}

// One temporary file per process (libFuzzer runs inputs one after the other in a process).
std::string temporary_path(const char* suffix) {
  return (std::filesystem::temp_directory_path() /
          ("oceanref-fuzz-" + std::to_string(::getpid()) + suffix))
      .string();
}

void write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) finding("harness", "cannot write the temporary file " + path);
}

struct RemoveOnExit {
  std::string path;
  ~RemoveOnExit() { std::remove(path.c_str()); }
};

bool writes_a_file(const std::string& argument) {
  return argument.rfind("-o", 0) == 0 || argument.rfind("--o", 0) == 0 ||
         argument.rfind("--size", 0) == 0;
}

}  // namespace

void scene_entry(const std::uint8_t* data, std::size_t size) {
  const RemoveOnExit file{temporary_path(".json")};
  write_file(file.path, data, size);
  guarded("scene", [&] {
    std::ostringstream warnings;
    const Scene scene = load_scene(file.path, &warnings);
    (void)scene;
  });
}

void cli_entry(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> arguments{"oceanref"};
  std::string current;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n' || c == '\0') {
      arguments.push_back(current);
      current.clear();
    } else {
      current.push_back(c);
    }
  }
  if (size > 0) arguments.push_back(current);
  if (arguments.size() > 64) return;
  for (const std::string& a : arguments) {
    if (writes_a_file(a)) return;
  }
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  guarded("cli", [&] {
    // The program's own structure (src/cli/main.cpp) for the subcommands that write no file.
    CLI::App app{"oceanref", "oceanref"};
    app.require_subcommand(1);
    const auto run_spectrum = cli::add_spectrum_command(app);
    const auto run_sky = cli::add_sky_command(app);
    const auto run_brdf = cli::add_brdf_command(app);
    try {
      app.parse(static_cast<int>(arguments.size()), argv.data());
    } catch (const CLI::Success&) {  // --help
      return;
    }
    std::ostringstream out;
    if (app.got_subcommand("spectrum")) run_spectrum(out);
    if (app.got_subcommand("sky")) run_sky(out);
    if (app.got_subcommand("brdf")) run_brdf(out);
  });
}

void exr_entry(const std::uint8_t* data, std::size_t size) {
  const RemoveOnExit file{temporary_path(".exr")};
  write_file(file.path, data, size);
  guarded("exr", [&] {
    const std::vector<ExrPart> parts = read_parts_for_compare(file.path, kMaxFuzzPixelBytes);
    const Comparison c =
        compare_parts(parts, parts, ChannelSelection{}, uniform_profile(ChannelThreshold{}));
    (void)c;
  });
  guarded("exr", [&] { (void)read_exr(file.path, kMaxFuzzPixelBytes); });
}

void piece_entry(const std::uint8_t* data, std::size_t size) {
  const RemoveOnExit file{temporary_path(".piece")};
  write_file(file.path, data, size);
  guarded("piece", [&] { (void)read_render_piece(file.path); });
}

void obj_entry(const std::uint8_t* data, std::size_t size) {
  const RemoveOnExit file{temporary_path(".obj")};
  write_file(file.path, data, size);
  guarded("obj", [&] { (void)load_obj(file.path); });
}

Entry entry_for(std::string_view target) {
  if (target == "scene") return scene_entry;
  if (target == "cli") return cli_entry;
  if (target == "exr") return exr_entry;
  if (target == "piece") return piece_entry;
  if (target == "obj") return obj_entry;
  return nullptr;
}

}  // namespace oceanref::fuzz
