// `oceanref spectrum`: tables of S(ω), D(ω,θ), Θ(k) and the spectral moments as CSV.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

// Registers the subcommand; the returned function runs it after parsing (writes CSV to `out`,
// throws UsageError for bad values).
std::function<void(std::ostream& out)> add_spectrum_command(CLI::App& app);

}  // namespace oceanref::cli
