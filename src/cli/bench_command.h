// `oceanref bench`: speed and accuracy figures (reference/ACCURACY.md), never part of ctest.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_bench_command(CLI::App& app);

}  // namespace oceanref::cli
