#pragma once
// Plots through gnuplot (Debian's gnuplot-nox), shared by the tools that draw PNG plots from their
// measurements (splat_eval, sample_game): which PNG terminal this gnuplot has, quoting a path for
// the shell, and running a script in a folder.
#include <filesystem>
#include <string>

namespace engine {

// "pngcairo font 'sans,10'" (antialiased) when gnuplot has cairo, else "png" (libgd; gnuplot-nox
// may lack cairo); empty when gnuplot cannot be run. Append " size W,H" for a size.
std::string gnuplot_png_terminal();

// `path` in single quotes for a POSIX shell (a quote inside becomes '\'').
std::string shell_quoted(const std::filesystem::path& path);

// Runs `gnuplot <script>` with `folder` as the working directory, its output and warnings going to
// `folder / log` (plots.gp and plots.log by default). Throws engine::Error naming the script and the
// log when gnuplot fails.
void run_gnuplot(const std::filesystem::path& folder, const std::string& script = "plots.gp",
                 const std::string& log = "plots.log");

}  // namespace engine
