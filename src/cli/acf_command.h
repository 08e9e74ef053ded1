// `oceanref acf SCENE...`: the autocorrelation function of each scene's displacement (Lutz et al.
// 2024 eq. 22; waves/autocorrelation.h) as CSV, with an SVG plot and a map of the heights.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_acf_command(CLI::App& app);

}  // namespace oceanref::cli
