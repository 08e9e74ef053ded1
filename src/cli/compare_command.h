// `oceanref compare` (metrics and pass/fail between two EXRs) and `oceanref golden verify|update`.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_compare_command(CLI::App& app);
std::function<void(std::ostream& out)> add_golden_command(CLI::App& app);

}  // namespace oceanref::cli
