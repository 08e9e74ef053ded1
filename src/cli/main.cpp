// oceanref: the command-line front end, a thin layer over the library.
// Exit codes: 0 success, 1 failed check (and a non-finite result), 2 bad input (one line naming
// the flag and range).
#include <CLI/CLI.hpp>
#include <iostream>
#include <sstream>

#include "cli/acf_command.h"
#include "cli/bench_command.h"
#include "cli/brdf_command.h"
#include "cli/compare_command.h"
#include "cli/fields_command.h"
#include "cli/render_command.h"
#include "cli/sky_command.h"
#include "cli/spectrum_command.h"
#include "cli/text.h"
#include "conformance/provenance.h"
#include "core/fp_environment.h"
#include "io/output_file.h"
#include "raster/renderer.h"

int main(int argc, char** argv) {
  // Round to nearest with subnormals, whatever the process was started with (determinism contract).
  const oceanref::ReferenceFpEnvironment fp;
  // An interrupted run leaves no temporary file; a file size limit is a write error.
  oceanref::remove_output_temporaries_on_signals();
  CLI::App app{"oceanref: deterministic CPU reference renderer for spectral ocean surfaces",
               "oceanref"};
  app.set_version_flag("--version", oceanref::version_text());
  app.require_subcommand(1);
  const auto run_spectrum = oceanref::cli::add_spectrum_command(app);
  const auto run_fields = oceanref::cli::add_fields_command(app);
  const auto run_sky = oceanref::cli::add_sky_command(app);
  const auto run_brdf = oceanref::cli::add_brdf_command(app);
  const auto run_render = oceanref::cli::add_render_command(app);
  const auto run_merge = oceanref::cli::add_merge_command(app);
  const auto run_probe = oceanref::cli::add_probe_command(app);
  const auto run_compare = oceanref::cli::add_compare_command(app);
  const auto run_golden = oceanref::cli::add_golden_command(app);
  const auto run_bench = oceanref::cli::add_bench_command(app);
  const auto run_acf = oceanref::cli::add_acf_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const auto named = [&](const CLI::App* sub) { return sub->check_name(argv[1]); };
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands(named).empty()) {
      std::cerr << "oceanref: unknown subcommand '" << oceanref::escape_value(argv[1])
                << "' (see oceanref --help)\n";
      return 2;
    }
    // CLI11 quotes the arguments as typed: escaped, so that raw bytes never reach the terminal.
    std::cerr << "oceanref: " << oceanref::escape_value(e.what(), 1000)
              << " (see oceanref --help)\n";
    return 2;
  }
  try {
    // Output is assembled in memory and written only when complete: no partial tables.
    std::ostringstream out;
    try {
      if (app.got_subcommand("spectrum")) run_spectrum(out);
      if (app.got_subcommand("fields")) run_fields(out);
      if (app.got_subcommand("sky")) run_sky(out);
      if (app.got_subcommand("brdf")) run_brdf(out);
      if (app.got_subcommand("render")) run_render(out);
      if (app.got_subcommand("merge")) run_merge(out);
      if (app.got_subcommand("probe")) run_probe(out);
      if (app.got_subcommand("compare")) run_compare(out);
      if (app.got_subcommand("golden")) run_golden(out);
      if (app.got_subcommand("acf")) run_acf(out);
    } catch (const oceanref::cli::CheckFailed&) {
      std::cout << out.str() << std::flush;
      return 1;
    }
    if (app.got_subcommand("bench")) run_bench(out);
    std::cout << out.str() << std::flush;
    return std::cout ? 0 : 2;
  } catch (const oceanref::NonFiniteOutputError& e) {
    // A result that is not a number is a failed check, never a success (nothing was written).
    std::cerr << "oceanref: non-finite output: " << e.what() << '\n';
    return 1;
  } catch (const oceanref::cli::UsageError& e) {
    std::cerr << "oceanref: " << e.what() << '\n';
    return 2;
  } catch (const std::bad_alloc&) {
    // The large buffers name themselves (OutOfMemoryError); this is any other allocation.
    std::cerr << "oceanref: out of memory: an allocation failed (peak resident memory "
              << oceanref::mebibytes(oceanref::cli::peak_memory_bytes())
              << "); free memory, or lower the resolution, the sample count or --max-memory\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "oceanref: " << e.what() << '\n';
    return 2;
  }
}
