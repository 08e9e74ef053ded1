// `oceanref render` (the reference image, or one tile of it), `oceanref merge` (the tiles into the
// image) and `oceanref probe` (everything behind one pixel).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>

namespace oceanref::cli {

std::function<void(std::ostream& out)> add_render_command(CLI::App& app);
std::function<void(std::ostream& out)> add_merge_command(CLI::App& app);
std::function<void(std::ostream& out)> add_probe_command(CLI::App& app);

}  // namespace oceanref::cli
